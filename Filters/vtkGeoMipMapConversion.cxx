#include "vtkGeoMipMapConversion.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObject.h"
#include "vtkPointData.h"

#include <cmath>
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

// World position of a data-space point through a 4x4 matrix.
void Transform(const double m[16], const double p[3], double out[3])
{
  double w = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
  for (int r = 0; r < 3; ++r)
  {
    out[r] = (m[r * 4] * p[0] + m[r * 4 + 1] * p[1] + m[r * 4 + 2] * p[2] + m[r * 4 + 3]) / w;
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
    std::abs(sx) != 1 || std::abs(sy) != 1)
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
  hf.z.resize(n);
  const int comps = a->GetNumberOfComponents();
  switch (a->GetDataType())
  {
    vtkTemplateMacro(
      CopyHeights(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), comps, n, hf.z.data()));
    default:
      return "the height array is not numeric";
  }
  return gmm::validateHeightfield(hf);
}

//------------------------------------------------------------------------------
std::string CameraToView(
  vtkCamera* camera, vtkMatrix4x4* dataToWorld, int width, int height, gmm::View& view)
{
  if (!camera)
  {
    return "no camera";
  }
  if (width < 1 || height < 1)
  {
    return "empty viewport";
  }
  double inv[16];
  double scale = 1.0;
  if (dataToWorld)
  {
    vtkMatrix4x4::Invert(dataToWorld->GetData(), inv);
    double m3[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        m3[r][c] = dataToWorld->GetElement(r, c);
      }
    }
    const double det = vtkMath::Determinant3x3(m3);
    if (!std::isfinite(det) || det == 0.0)
    {
      return "singular actor matrix";
    }
    // Distances in data units are world distances / scale (exact for uniform scale).
    scale = std::cbrt(std::abs(det));
  }
  else
  {
    vtkMatrix4x4::Identity(inv);
  }
  double pos[3], fp[3], upEnd[3], eye[3], focal[3], upPt[3];
  camera->GetPosition(pos);
  camera->GetFocalPoint(fp);
  const double* vu = camera->GetViewUp();
  for (int k = 0; k < 3; ++k)
  {
    upEnd[k] = pos[k] + vu[k];
  }
  // Points, not directions, go through the inverse so translations are handled too.
  Transform(inv, pos, eye);
  Transform(inv, fp, focal);
  Transform(inv, upEnd, upPt);
  view.eye = glm::dvec3(eye[0], eye[1], eye[2]);
  view.forward = glm::dvec3(focal[0] - eye[0], focal[1] - eye[1], focal[2] - eye[2]);
  view.up = glm::dvec3(upPt[0] - eye[0], upPt[1] - eye[1], upPt[2] - eye[2]);
  double angle = camera->GetViewAngle();
  if (camera->GetUseHorizontalViewAngle())
  {
    // The engine wants the vertical angle: convert through the viewport's aspect.
    const double t = std::tan(vtkMath::RadiansFromDegrees(angle) / 2.0);
    angle = 2.0 * vtkMath::DegreesFromRadians(std::atan(t * height / width));
  }
  view.fovYDegrees = angle;
  view.parallel = camera->GetParallelProjection() != 0;
  view.parallelScale = camera->GetParallelScale() / scale;
  const double* range = camera->GetClippingRange();
  view.nearDistance = range[0] / scale;
  view.farDistance = range[1] / scale;
  view.viewportWidth = width;
  view.viewportHeight = height;
  return gmm::validateView(view);
}

bool AcceptPixelError(vtkObject* self, double tau, double& current)
{
  if (!(tau >= 0.0 && std::isfinite(tau)))
  {
    vtkErrorWithObjectMacro(
      self, "PixelError must be a finite number >= 0, got " << tau << "; keeping " << current);
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
void SampleNormal(const gmm::Heightfield& hf, int i, int j, float n[3])
{
  // Slope along one axis from the valid neighbours of (i, j): central when both exist.
  auto slope = [&hf](int i0, int j0, int di, int dj, double step, int count) {
    const float c = hf.height(i0, j0);
    const int ia = i0 - di, ja = j0 - dj, ib = i0 + di, jb = j0 + dj;
    const bool hasA = ia >= 0 && ja >= 0 && std::isfinite(hf.height(ia, ja));
    const bool hasB = ib < hf.nx && jb < hf.ny && (di ? ib < count : jb < count) &&
      std::isfinite(hf.height(ib, jb));
    if (hasA && hasB)
    {
      return (hf.height(ib, jb) - hf.height(ia, ja)) / (2.0 * step);
    }
    if (hasB && std::isfinite(c))
    {
      return (hf.height(ib, jb) - c) / step;
    }
    if (hasA && std::isfinite(c))
    {
      return (c - hf.height(ia, ja)) / step;
    }
    return 0.0;
  };
  const double gx = slope(i, j, 1, 0, hf.dx, hf.nx);
  const double gy = slope(i, j, 0, 1, hf.dy, hf.ny);
  // Upward normal of z = h(x, y); the sign of dx, dy is already inside gx, gy.
  const double len = std::sqrt(gx * gx + gy * gy + 1.0);
  n[0] = static_cast<float>(-gx / len);
  n[1] = static_cast<float>(-gy / len);
  n[2] = static_cast<float>(1.0 / len);
}
}
