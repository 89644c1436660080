// Helpers shared by the geomipmap VTK rendering tests: synthetic terrain images, a
// full-resolution reference mesh built without the engine, window grabs and pixel counts.
#ifndef GeoMipMapTestUtilities_h
#define GeoMipMapTestUtilities_h

#include "GeoMipMapTestData.h"
#include "SyntheticTerrain.h"
#include "vtkGeoMipMapFilter.h"
#include "vtkGeoMipMapMapper.h"
#include "vtkGeoMipMapScreenError.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace gmmtest
{
// Deterministic fractal terrain as a vtkImageData with float "Elevation" point scalars.
inline vtkSmartPointer<vtkImageData> SyntheticImage(
  int nx, int ny, double spacing, unsigned seed, double amplitude, double x0 = 0, double y0 = 0)
{
  gmm::Heightfield hf = gmm::makeSyntheticTerrain(nx, ny, spacing, seed, amplitude, 1);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, 1);
  image->SetSpacing(spacing, spacing, 1.0);
  image->SetOrigin(x0, y0, 0.0);
  vtkNew<vtkFloatArray> z;
  z->SetName("Elevation");
  z->SetNumberOfTuples(static_cast<vtkIdType>(hf.z.size()));
  std::copy(hf.z.begin(), hf.z.end(), z->GetPointer(0));
  image->GetPointData()->SetScalars(z);
  return image;
}

// Every grid quad as two triangles (skipping nodata), with normals from
// vtkPolyDataNormals: an engine-independent reference surface.
inline vtkSmartPointer<vtkPolyData> FullResolutionMesh(vtkImageData* image)
{
  int d[3];
  image->GetDimensions(d);
  vtkDataArray* h = image->GetPointData()->GetScalars();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(d[0]) * d[1]);
  for (vtkIdType k = 0; k < pts->GetNumberOfPoints(); ++k)
  {
    double p[3];
    image->GetPoint(k, p);
    double z = h->GetComponent(k, 0);
    pts->SetPoint(k, p[0], p[1], std::isfinite(z) ? z : 0.0);
  }
  vtkNew<vtkCellArray> tris;
  auto ok = [h](vtkIdType k) { return std::isfinite(h->GetComponent(k, 0)); };
  for (int j = 0; j + 1 < d[1]; ++j)
  {
    for (int i = 0; i + 1 < d[0]; ++i)
    {
      vtkIdType a = j * d[0] + i, b = a + 1, c = a + d[0], e = c + 1;
      if (ok(a) && ok(b) && ok(c) && ok(e))
      {
        vtkIdType t1[3] = { a, b, e }, t2[3] = { a, e, c };
        tris->InsertNextCell(3, t1);
        tris->InsertNextCell(3, t2);
      }
    }
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(pts);
  mesh->SetPolys(tris);
  mesh->GetPointData()->SetScalars(h);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(mesh);
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->Update();
  return normals->GetOutput();
}

// An off-screen window of w x h pixels without multisampling (deterministic pixels for
// image comparison), holding `ren` when given.
inline vtkSmartPointer<vtkRenderWindow> OffscreenWindow(int w, int h, vtkRenderer* ren = nullptr)
{
  auto win = vtkSmartPointer<vtkRenderWindow>::New();
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(w, h);
  if (ren)
  {
    win->AddRenderer(ren);
  }
  return win;
}

// An RGB checkerboard texture image of size x size texels, squares of `cell` texels; the
// square holding texel (0, 0) has colour a, its neighbours colour b.
inline vtkSmartPointer<vtkImageData> Checkerboard(
  int size, int cell, const unsigned char a[3], const unsigned char b[3])
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(size, size, 1);
  img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      unsigned char* p = static_cast<unsigned char*>(img->GetScalarPointer(x, y, 0));
      const unsigned char* c = ((x / cell) + (y / cell)) % 2 == 0 ? a : b;
      p[0] = c[0];
      p[1] = c[1];
      p[2] = c[2];
    }
  }
  return img;
}

// ---------------------------------------------------------------------------------------
// The measured screen-space error of what vtkGeoMipMapMapper drew, independent of the
// engine's own bound: vtkGeoMipMapFilter with the same camera, actor matrix, viewport,
// tau, block size and height scale gives the mapper's triangles
// (TestGeoMipMapFilterAgreement; the triangle counts are compared on every use), and
// vtkGeoMipMapScreenError (no engine code) measures them against the full-resolution
// heightfield, projecting with the camera's own composite matrix times the actor's:
// data -> world -> clip. Same as Testing/Python/gmmtestutil.py.

struct MeasuredFrame
{
  vtkIdType Triangles = 0;   // of the filter's copy
  double MaximumError = 0.0; // pixels, over the in-view samples
  double Percentile99Error = 0.0;
  vtkIdType InView = 0, Uncovered = 0;
};

// Measures the last frame `ren` drew of `actor` (a vtkGeoMipMapMapper over `image`). Call
// it right after the render.
inline MeasuredFrame MeasureDrawn(vtkImageData* image, vtkRenderer* ren, vtkActor* actor)
{
  auto* mapper = vtkGeoMipMapMapper::SafeDownCast(actor->GetMapper());
  vtkMatrix4x4* m = actor->GetMatrix(); // also brings GetIsIdentity up to date
  if (actor->GetIsIdentity())
  {
    m = nullptr;
  }
  const int* size = ren->GetSize();
  vtkNew<vtkGeoMipMapFilter> filter;
  filter->SetInputData(image);
  filter->SetCamera(ren->GetActiveCamera());
  filter->SetModelMatrix(m);
  filter->SetViewportSize(size[0], size[1]);
  filter->SetPixelError(mapper->GetPixelError());
  filter->SetBlockSize(mapper->GetBlockSize());
  filter->SetHeightScale(mapper->GetHeightScale());
  filter->Update();
  vtkNew<vtkMatrix4x4> clip;
  clip->DeepCopy(
    ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  if (m)
  {
    vtkMatrix4x4::Multiply4x4(clip, m, clip); // data -> world -> clip
  }
  vtkNew<vtkGeoMipMapScreenError> error;
  error->SetHeightfield(image);
  error->SetHeightScale(mapper->GetHeightScale());
  error->SetMesh(filter->GetOutput());
  error->SetViewportSize(size[0], size[1]);
  error->SetProjectionMatrix(clip);
  MeasuredFrame r;
  r.Triangles = filter->GetOutput()->GetNumberOfPolys();
  if (error->Compute())
  {
    r.MaximumError = error->GetMaximumError();
    r.Percentile99Error = error->GetPercentile99Error();
    r.InView = error->GetNumberOfSamplesInView();
    r.Uncovered = error->GetNumberOfUncoveredSamples();
  }
  return r;
}

// True when the last frame of `actor` measures within the mapper's tau, the measured mesh
// is the drawn one (same triangle count), something was in view and (unless allowed) every
// in-view sample was covered. Prints what it measured, prefixed by `what`.
inline bool DrawnWithinTau(
  vtkImageData* image, vtkRenderer* ren, vtkActor* actor, const char* what, bool uncoveredOk = false)
{
  auto* mapper = vtkGeoMipMapMapper::SafeDownCast(actor->GetMapper());
  const MeasuredFrame f = MeasureDrawn(image, ren, actor);
  const double tau = mapper->GetPixelError();
  const vtkIdType drawn = mapper->GetNumberOfRenderedTriangles();
  std::cout << what << ": mapper " << drawn << " triangles, filter " << f.Triangles
            << "; measured error " << f.MaximumError << " px (p99 " << f.Percentile99Error
            << "), tau " << tau << "; " << f.InView << " samples in view, " << f.Uncovered
            << " uncovered\n";
  bool ok = true;
  if (f.Triangles != drawn || drawn <= 0 || f.InView <= 0)
  {
    std::cout << "  FAIL: not the drawn mesh, or nothing drawn / in view\n";
    ok = false;
  }
  if (!(f.MaximumError <= tau + 1e-6))
  {
    std::cout << "  FAIL: measured screen error above tau\n";
    ok = false;
  }
  if (!uncoveredOk && f.Uncovered)
  {
    std::cout << "  FAIL: in-view samples not covered\n";
    ok = false;
  }
  return ok;
}

// The window's current RGB pixels.
inline vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* win)
{
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(win);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOff();
  w2i->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(w2i->GetOutput());
  return out;
}

// The window's depth buffer (floats in [0, 1], 1 = background).
inline vtkSmartPointer<vtkImageData> GrabDepth(vtkRenderWindow* win)
{
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(win);
  w2i->SetInputBufferTypeToZBuffer();
  w2i->ReadFrontBufferOff();
  w2i->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(w2i->GetOutput());
  return out;
}

// Number of pixels whose depths differ by more than `tol`.
inline int CountDifferentDepths(vtkImageData* a, vtkImageData* b, double tol, double* maxDiff = nullptr)
{
  const vtkIdType n = a->GetNumberOfPoints();
  vtkDataArray* da = a->GetPointData()->GetScalars();
  vtkDataArray* db = b->GetPointData()->GetScalars();
  int count = 0;
  double worst = 0.0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    const double d = std::abs(da->GetTuple1(k) - db->GetTuple1(k));
    worst = std::max(worst, d);
    count += d > tol ? 1 : 0;
  }
  if (maxDiff)
  {
    *maxDiff = worst;
  }
  return count;
}

inline unsigned char* Pixel(vtkImageData* img, int x, int y)
{
  return static_cast<unsigned char*>(img->GetScalarPointer(x, y, 0));
}

// Number of pixels whose largest channel difference exceeds `tol`.
inline int CountDifferentPixels(vtkImageData* a, vtkImageData* b, int tol, int* maxDiff = nullptr)
{
  int d[3];
  a->GetDimensions(d);
  int count = 0, worst = 0;
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      unsigned char *p = Pixel(a, x, y), *q = Pixel(b, x, y);
      int m = 0;
      for (int c = 0; c < 3; ++c)
      {
        m = std::max(m, std::abs(int(p[c]) - int(q[c])));
      }
      worst = std::max(worst, m);
      count += m > tol ? 1 : 0;
    }
  }
  if (maxDiff)
  {
    *maxDiff = worst;
  }
  return count;
}
}

#endif
