#include "vtkGeoMipMapConversion.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObject.h"
#include "vtkPointData.h"

#include "Engine.h"    // gmm::validateHeightScale
#include "HugePages.h" // gmm::resizeOnHugePages
#include "Quadtree.h"  // gmm::validateBlockSize

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <unistd.h>
#include <limits>

namespace
{
template <typename T>
void CopyHeights(const T* src, int comps, std::size_t n, float* dst)
{
  // Component 0 of each tuple; non-finite values and values beyond the engine's height
  // range (gmm::kMaxHeight: undeclared nodata such as -FLT_MAX, or a double 1e300 whose
  // cast would be undefined) become NaN, the engine's nodata.
  for (std::size_t k = 0; k < n; ++k)
  {
    const double v = static_cast<double>(src[k * comps]);
    dst[k] = std::abs(v) <= gmm::kMaxHeight ? static_cast<float>(v)
                                            : std::numeric_limits<float>::quiet_NaN();
  }
}

}

namespace vtkGeoMipMapConversion
{
//------------------------------------------------------------------------------
std::string ImageToHeightfield(vtkImageData* image, gmm::Heightfield& hf, vtkDataArray* heights)
{
  if (!image)
  {
    return "no input image";
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1)
  {
    return "the image must be 2D (nx x ny x 1)";
  }
  vtkDataArray* a = heights ? heights : image->GetPointData()->GetScalars();
  if (!a)
  {
    return "the image has no point scalars (heights)";
  }
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1];
  if (static_cast<std::size_t>(a->GetNumberOfTuples()) != n)
  {
    return "the height array does not have one value per sample";
  }
  // VTK 9.1 images carry a direction matrix: accept axis flips (as negative spacing) only.
  double dir[9];
  vtkMatrix3x3::DeepCopy(dir, image->GetDirectionMatrix());
  double sx = dir[0], sy = dir[4];
  if (dir[1] != 0 || dir[2] != 0 || dir[3] != 0 || dir[5] != 0 || dir[6] != 0 || dir[7] != 0 ||
    std::abs(sx) != 1 || std::abs(sy) != 1 || dir[8] == 0)
  {
    return "only axis-aligned image directions are supported";
  }
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  const int* ext = image->GetExtent();
  hf.nx = dims[0];
  hf.ny = dims[1];
  hf.dx = sx * spacing[0];
  hf.dy = sy * spacing[1];
  hf.x0 = origin[0] + ext[0] * hf.dx;
  hf.y0 = origin[1] + ext[2] * hf.dy;
  // The z origin is the datum, as vtkWarpScalar over the image would place the surface;
  // kept in double apart from the float heights, so an ECEF-size origin costs no precision.
  hf.z0 = origin[2] + ext[4] * dir[8] * spacing[2];
  const int comps = a->GetNumberOfComponents();
  hf.z.clear();
  hf.external = nullptr;
  hf.owner.reset();
  if (a->GetDataType() == VTK_FLOAT && comps == 1)
  {
    // Share the array when no value needs sanitising (NaN and finite heights within the
    // engine's range pass as they are; +-Inf the engine handles by copying).
    const float* z = static_cast<const float*>(a->GetVoidPointer(0));
    const bool clean = std::all_of(z, z + n,
      [](float v) { return !(std::abs(v) > gmm::kMaxHeight) || std::isinf(v); });
    if (clean)
    {
      hf.external = z;
      a->Register(nullptr); // the terrain keeps the array alive, not the image
      hf.owner = std::shared_ptr<const void>(a, [](const void* p) {
        static_cast<vtkDataArray*>(const_cast<void*>(p))->UnRegister(nullptr);
      });
      return std::string();
    }
  }
  gmm::resizeOnHugePages(hf.z, n);
  switch (a->GetDataType())
  {
    vtkTemplateMacro(
      CopyHeights(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), comps, n, hf.z.data()));
    default:
      return "the height array is not numeric";
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string CameraToView(vtkCamera* camera, vtkMatrix4x4* dataToWorld, int width, int height,
  gmm::View& view)
{
  if (!camera)
  {
    return "no camera";
  }
  if (width < 1 || height < 1)
  {
    return "empty viewport";
  }
  // Everything in world coordinates; the actor's matrix goes to the engine whole, which
  // culls and bounds the error exactly under it (no reduction to one scale factor).
  view.model = glm::dmat4(1.0);
  if (dataToWorld)
  {
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        view.model[c][r] = dataToWorld->GetElement(r, c); // glm is column-major
      }
    }
  }
  double pos[3], fp[3];
  camera->GetPosition(pos);
  camera->GetFocalPoint(fp);
  const double* vu = camera->GetViewUp();
  view.eye = glm::dvec3(pos[0], pos[1], pos[2]);
  view.forward = glm::dvec3(fp[0] - pos[0], fp[1] - pos[1], fp[2] - pos[2]);
  view.up = glm::dvec3(vu[0], vu[1], vu[2]);
  double angle = camera->GetViewAngle();
  if (camera->GetUseHorizontalViewAngle())
  {
    // The engine wants the vertical angle: convert through the viewport's aspect.
    const double t = std::tan(vtkMath::RadiansFromDegrees(angle) / 2.0);
    angle = 2.0 * vtkMath::DegreesFromRadians(std::atan(t * height / width));
  }
  view.fovYDegrees = angle;
  view.parallel = camera->GetParallelProjection() != 0;
  view.parallelScale = camera->GetParallelScale();
  const double* range = camera->GetClippingRange();
  view.nearDistance = range[0];
  view.farDistance = range[1];
  view.viewportWidth = width;
  view.viewportHeight = height;
  // The camera's own world -> clip matrix: culling then follows a window centre, a view
  // shear or any other projection setting exactly.
  vtkMatrix4x4* clip =
    camera->GetCompositeProjectionTransformMatrix(static_cast<double>(width) / height, -1, 1);
  view.hasClipMatrix = true;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view.clipFromWorld[c][r] = clip->GetElement(r, c);
    }
  }
  return gmm::validateView(view);
}

bool AcceptPixelError(vtkObject* self, double tau, double& current, const char* what)
{
  if (!(tau >= 0.0 && std::isfinite(tau)))
  {
    vtkErrorWithObjectMacro(
      self, << what << " must be a finite number >= 0, got " << tau << "; keeping " << current);
    return false;
  }
  if (tau == current)
  {
    return false;
  }
  current = tau;
  return true;
}

//------------------------------------------------------------------------------
double AvailableMemoryBytes()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kib * 1024.0;
    }
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages > 0 && size > 0)
  {
    return static_cast<double>(pages) * size;
  }
#endif
  return 0.0;
}

//------------------------------------------------------------------------------
bool AcceptBlockSize(vtkObject* self, int quads, int& current)
{
  const std::string err = gmm::validateBlockSize(quads);
  if (!err.empty())
  {
    vtkErrorWithObjectMacro(self, "BlockSize: " << err << "; keeping " << current);
    return false;
  }
  if (quads == current)
  {
    return false;
  }
  current = quads;
  return true;
}

//------------------------------------------------------------------------------
bool AcceptCount(vtkObject* self, const char* name, const char* zeroMeans, long long count, std::size_t& current)
{
  if (count < 0)
  {
    vtkErrorWithObjectMacro(
      self, "" << name << " " << count << " must be >= 0 (0: " << zeroMeans << "); kept " << current);
    return false;
  }
  return AcceptSetting(static_cast<std::size_t>(count), current);
}

void PrintFrameSettings(std::ostream& os, vtkIndent indent, const gmm::FrameSettings& settings)
{
  os << indent << "PixelError: " << settings.pixelError << "\n";
  os << indent << "TriangleBudget: " << settings.triangleBudget << "\n";
  os << indent << "HeightScale: " << settings.heightScale << "\n";
  os << indent << "Geomorphing: " << settings.geomorphing << "\n";
  os << indent << "GeomorphRange: " << settings.geomorphRange << "\n";
  os << indent << "GeomorphMerges: " << settings.geomorphMerges << "\n";
  os << indent << "GeomorphMeasureSamples: " << settings.geomorphMeasureSamples << "\n";
}

bool AcceptHeightScale(vtkObject* self, double scale, double& current)
{
  const std::string err = gmm::validateHeightScale(scale);
  if (!err.empty())
  {
    vtkErrorWithObjectMacro(self, "HeightScale: " << err << "; keeping " << current);
    return false;
  }
  if (scale == current)
  {
    return false;
  }
  current = scale;
  return true;
}

//------------------------------------------------------------------------------
void SampleNormal(const gmm::Heightfield& hf, int i, int j, double heightScale, float n[3])
{
  const double gx = heightScale * gmm::sampleSlope(hf, i, j, true);
  const double gy = heightScale * gmm::sampleSlope(hf, i, j, false);
  // Upward normal of z = h(x, y); the sign of dx, dy is already inside gx, gy.
  const double len = std::sqrt(gx * gx + gy * gy + 1.0);
  n[0] = static_cast<float>(-gx / len);
  n[1] = static_cast<float>(-gy / len);
  n[2] = static_cast<float>(1.0 / len);
}
}
