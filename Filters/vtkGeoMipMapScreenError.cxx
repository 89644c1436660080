#include "vtkGeoMipMapScreenError.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkGeoMipMapScreenError);
vtkCxxSetObjectMacro(vtkGeoMipMapScreenError, Heightfield, vtkImageData);
vtkCxxSetObjectMacro(vtkGeoMipMapScreenError, Mesh, vtkPolyData);
vtkCxxSetObjectMacro(vtkGeoMipMapScreenError, ReferenceMesh, vtkPolyData);

namespace
{
// Heights by sample index without a virtual call per sample for float / double arrays.
struct Heights
{
  const float* F = nullptr;
  const double* D = nullptr;
  vtkDataArray* Any = nullptr;
  double operator()(vtkIdType k) const
  {
    return this->F ? this->F[k] : (this->D ? this->D[k] : this->Any->GetComponent(k, 0));
  }
};

// Pixel position of a world point; false when it is behind the camera (clip w <= 0).
// inView: inside the six frustum planes.
struct Projector
{
  const double* M;
  double W, H;
  bool operator()(double x, double y, double z, double& px, double& py, bool& inView) const
  {
    const double cx = M[0] * x + M[1] * y + M[2] * z + M[3];
    const double cy = M[4] * x + M[5] * y + M[6] * z + M[7];
    const double cz = M[8] * x + M[9] * y + M[10] * z + M[11];
    const double cw = M[12] * x + M[13] * y + M[14] * z + M[15];
    if (!(cw > 0.0))
    {
      inView = false;
      return false;
    }
    inView = std::abs(cx) <= cw && std::abs(cy) <= cw && std::abs(cz) <= cw;
    px = 0.5 * (cx / cw + 1.0) * this->W;
    py = 0.5 * (cy / cw + 1.0) * this->H;
    return true;
  }
};

// The rectangle of grid indices holding every in-view sample, and the drawn z range per
// sample inside it (NaN = no triangle covers it).
struct Window
{
  int I0 = 0, I1 = -1, J0 = 0, J1 = -1;
  std::vector<float> Lo, Hi;
  int Width() const { return this->I1 - this->I0 + 1; }
  bool Empty() const { return this->I1 < this->I0 || this->J1 < this->J0; }
};

// Rasterises one triangle (grid coordinates gx, gy and heights z of its corners) into
// the window: every integer sample inside or on an edge gets its interpolated z.
void Rasterise(const double gx[3], const double gy[3], const double z[3], Window& w)
{
  const double area = (gx[1] - gx[0]) * (gy[2] - gy[0]) - (gx[2] - gx[0]) * (gy[1] - gy[0]);
  if (std::abs(area) < 1e-12)
  {
    return; // vertical or degenerate: covers no area in x, y
  }
  const double eps = 1e-9; // relative barycentric slack: grid-aligned edges hit samples
  const int i0 = std::max(w.I0, static_cast<int>(std::ceil(std::min({ gx[0], gx[1], gx[2] }) - 1e-7)));
  const int i1 = std::min(w.I1, static_cast<int>(std::floor(std::max({ gx[0], gx[1], gx[2] }) + 1e-7)));
  const int j0 = std::max(w.J0, static_cast<int>(std::ceil(std::min({ gy[0], gy[1], gy[2] }) - 1e-7)));
  const int j1 = std::min(w.J1, static_cast<int>(std::floor(std::max({ gy[0], gy[1], gy[2] }) + 1e-7)));
  for (int j = j0; j <= j1; ++j)
  {
    for (int i = i0; i <= i1; ++i)
    {
      const double l1 = ((i - gx[0]) * (gy[2] - gy[0]) - (gx[2] - gx[0]) * (j - gy[0])) / area;
      const double l2 = ((gx[1] - gx[0]) * (j - gy[0]) - (i - gx[0]) * (gy[1] - gy[0])) / area;
      const double l0 = 1.0 - l1 - l2;
      if (l0 < -eps || l1 < -eps || l2 < -eps)
      {
        continue;
      }
      const float zs = static_cast<float>(l0 * z[0] + l1 * z[1] + l2 * z[2]);
      const std::size_t k = static_cast<std::size_t>(j - w.J0) * w.Width() + (i - w.I0);
      if (std::isnan(w.Lo[k]))
      {
        w.Lo[k] = w.Hi[k] = zs;
      }
      else
      {
        w.Lo[k] = std::min(w.Lo[k], zs);
        w.Hi[k] = std::max(w.Hi[k], zs);
      }
    }
  }
}

// Rasterises every polygon of `mesh` (fanned into triangles) into the window; heights
// relative to z0.
void RasteriseMesh(vtkPolyData* mesh, const double* origin, const double* spacing, double z0, Window& w)
{
  vtkPoints* pts = mesh->GetPoints();
  vtkCellArray* polys = mesh->GetPolys();
  if (!pts || !polys)
  {
    return;
  }
  auto it = vtkSmartPointer<vtkCellArrayIterator>::Take(polys->NewIterator());
  double p[3], gx[3], gy[3], gz[3];
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    for (vtkIdType t = 1; t + 1 < n; ++t)
    {
      const vtkIdType corner[3] = { ids[0], ids[t], ids[t + 1] };
      for (int c = 0; c < 3; ++c)
      {
        pts->GetPoint(corner[c], p);
        gx[c] = (p[0] - origin[0]) / spacing[0];
        gy[c] = (p[1] - origin[1]) / spacing[1];
        gz[c] = p[2] - z0;
      }
      Rasterise(gx, gy, gz, w);
    }
  }
}
}

//------------------------------------------------------------------------------
vtkGeoMipMapScreenError::vtkGeoMipMapScreenError()
{
  vtkMatrix4x4::Identity(this->Matrix);
}

//------------------------------------------------------------------------------
vtkGeoMipMapScreenError::~vtkGeoMipMapScreenError()
{
  this->SetHeightfield(nullptr);
  this->SetMesh(nullptr);
  this->SetReferenceMesh(nullptr);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapScreenError::SetProjectionMatrix(vtkMatrix4x4* m)
{
  if (!m)
  {
    this->HasMatrix = false;
    return;
  }
  vtkMatrix4x4::DeepCopy(this->Matrix, m);
  this->HasMatrix = true;
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapScreenError::Compute()
{
  this->MaximumError = this->Percentile99Error = this->MeanError = 0.0;
  this->NumberOfSamplesInView = this->NumberOfUncoveredSamples = 0;
  vtkImageData* img = this->Heightfield;
  if (!img || !this->Mesh || !this->HasMatrix)
  {
    vtkErrorMacro("Compute needs a Heightfield, a Mesh and a ProjectionMatrix.");
    return false;
  }
  int dims[3];
  img->GetDimensions(dims);
  vtkDataArray* scalars = img->GetPointData()->GetScalars();
  if (dims[0] < 2 || dims[1] < 2 || dims[2] != 1 || !scalars ||
    scalars->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    vtkErrorMacro("Heightfield must be a 2D image (nx x ny x 1, nx, ny >= 2) with point "
                  "scalars; got " << dims[0] << " x " << dims[1] << " x " << dims[2] << ".");
    return false;
  }
  if (this->ViewportSize[0] < 1 || this->ViewportSize[1] < 1)
  {
    vtkErrorMacro("ViewportSize must be positive.");
    return false;
  }
  const double* origin = img->GetOrigin();
  const double* spacing = img->GetSpacing();
  if (spacing[0] == 0.0 || spacing[1] == 0.0)
  {
    vtkErrorMacro("Heightfield spacing must be non-zero.");
    return false;
  }
  Heights h;
  h.F = vtkFloatArray::SafeDownCast(scalars) ? vtkFloatArray::SafeDownCast(scalars)->GetPointer(0) : nullptr;
  h.D = vtkDoubleArray::SafeDownCast(scalars) ? vtkDoubleArray::SafeDownCast(scalars)->GetPointer(0) : nullptr;
  h.Any = scalars;
  const Projector project{ this->Matrix, double(this->ViewportSize[0]), double(this->ViewportSize[1]) };
  const int nx = dims[0], ny = dims[1];
  auto sx = [&](int i) { return origin[0] + i * spacing[0]; };
  auto sy = [&](int j) { return origin[1] + j * spacing[1]; };
  // The true surface: origin z + HeightScale * h (where vtkWarpScalar with that scale factor
  // puts it). Drawn heights are kept relative to origin z, so a 6.4e6 m origin costs the
  // float raster no precision.
  const double z0 = origin[2], scale = this->HeightScale;
  auto sz = [&](vtkIdType k) { return z0 + scale * h(k); };

  // Pass 1: the index rectangle of the in-view samples.
  Window w;
  w.I0 = nx;
  w.J0 = ny;
  double px, py;
  bool in;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const double z = sz(static_cast<vtkIdType>(j) * nx + i);
      if (!std::isnan(z) && project(sx(i), sy(j), z, px, py, in) && in)
      {
        w.I0 = std::min(w.I0, i), w.I1 = std::max(w.I1, i);
        w.J0 = std::min(w.J0, j), w.J1 = std::max(w.J1, j);
      }
    }
  }
  if (w.Empty())
  {
    return true; // nothing in view: no error
  }
  const std::size_t cells = static_cast<std::size_t>(w.Width()) * (w.J1 - w.J0 + 1);
  w.Lo.assign(cells, std::numeric_limits<float>::quiet_NaN());
  w.Hi.assign(cells, std::numeric_limits<float>::quiet_NaN());

  // Pass 2: rasterise the mesh over the grid (polygons fanned into triangles), and the
  // reference mesh, if any, into a window of its own.
  Window ref = w;
  RasteriseMesh(this->Mesh, origin, spacing, z0, w);
  if (this->ReferenceMesh)
  {
    RasteriseMesh(this->ReferenceMesh, origin, spacing, z0, ref);
  }


  // Pass 3: pixel distance between the true and the drawn point, worst of lo / hi.
  std::vector<float> errors;
  errors.reserve(cells);
  double sum = 0.0;
  for (int j = w.J0; j <= w.J1; ++j)
  {
    for (int i = w.I0; i <= w.I1; ++i)
    {
      const double z = sz(static_cast<vtkIdType>(j) * nx + i);
      double tx, ty;
      if (std::isnan(z) || !project(sx(i), sy(j), z, tx, ty, in) || !in)
      {
        continue;
      }
      ++this->NumberOfSamplesInView;
      const std::size_t k = static_cast<std::size_t>(j - w.J0) * w.Width() + (i - w.I0);
      bool ok = !std::isnan(w.Lo[k]);
      if (this->ReferenceMesh)
      {
        bool dummy;
        ok = ok && !std::isnan(ref.Lo[k]) && project(sx(i), sy(j), z0 + ref.Lo[k], tx, ty, dummy);
      }
      double worst = -1.0;
      for (const float zd : { w.Lo[k], w.Hi[k] })
      {
        bool dummy;
        ok = ok && project(sx(i), sy(j), z0 + zd, px, py, dummy);
        worst = std::max(worst, std::hypot(px - tx, py - ty));
      }
      if (!ok)
      {
        ++this->NumberOfUncoveredSamples;
        continue;
      }
      errors.push_back(static_cast<float>(worst));
      sum += worst;
    }
  }
  if (!errors.empty())
  {
    this->MaximumError = *std::max_element(errors.begin(), errors.end());
    this->MeanError = sum / errors.size();
    const std::size_t q = static_cast<std::size_t>(0.99 * (errors.size() - 1));
    std::nth_element(errors.begin(), errors.begin() + q, errors.end());
    this->Percentile99Error = errors[q];
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapScreenError::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Heightfield: " << this->Heightfield << "\n";
  os << indent << "Mesh: " << this->Mesh << "\n";
  os << indent << "ReferenceMesh: " << this->ReferenceMesh << "\n";
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1] << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "Percentile99Error: " << this->Percentile99Error << "\n";
  os << indent << "MeanError: " << this->MeanError << "\n";
  os << indent << "NumberOfSamplesInView: " << this->NumberOfSamplesInView << "\n";
  os << indent << "NumberOfUncoveredSamples: " << this->NumberOfUncoveredSamples << "\n";
}
