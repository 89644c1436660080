// Mapper / filter agreement and large coordinates.
// 1. vtkGeoMipMapFilter with the mapper's camera and viewport gives exactly the mapper's
//    triangle count, and its output drawn by a stock vtkPolyDataMapper fills the depth
//    buffer as the mapper does (same surface; shading differs by design: the mapper lights
//    every fragment with full-resolution normals, the stock mapper interpolates the
//    normals of the coarse triangles' vertices).
// 2. The same DEM at the origin, at (500000, 5000000) (UTM-like) and at 6.4e6 on every axis
//    (ECEF-like, heights included), camera shifted by the same offset, renders the same
//    pictures through a 100-frame camera creep without vertex jitter: the VBO shift/scale
//    keeps float32 precision (see LargeCoordinates).
#include "GeoMipMapTestUtilities.h"
#include "vtkGeoMipMapFilter.h"
#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"

#include "vtkFloatArray.h"
#include "vtkPointData.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <vector>

namespace
{
void SetCamera(vtkCamera* cam, double ox, double oy, double oz = 0.0)
{
  cam->SetPosition(ox - 1500, oy - 2500, oz + 3500);
  cam->SetFocalPoint(ox + 3000, oy + 3000, oz + 600);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(35);
}

// The synthetic DEM with heights rounded to the float32 step at 6.4e6 (0.5 m), so that the
// same float heights plus 6.4e6 (the ECEF-like copy) are exact: all placements then hold
// the identical surface and any difference in the pictures is the renderer's.
vtkSmartPointer<vtkImageData> PlacedDEM(vtkImageData* base, double ox, double oy, double oz)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->DeepCopy(base);
  img->SetOrigin(ox, oy, 0.0);
  auto* z = vtkFloatArray::SafeDownCast(img->GetPointData()->GetScalars());
  for (vtkIdType k = 0; k < z->GetNumberOfTuples(); ++k)
  {
    const double q = static_cast<double>(static_cast<float>(z->GetValue(k) + 6.4e6)) - 6.4e6;
    z->SetValue(k, static_cast<float>(q + oz));
  }
  return img;
}

struct Placement
{
  const char* Name;
  double Offset[3];
};

// The same DEM at the origin, at a UTM-like and at an ECEF-like offset (heights included),
// seen by a camera offset by the same amount that creeps 0.25 m per frame (about 1/50
// pixel at the terrain): every placement must draw the origin's pictures (every frame
// within 0.5 % of pixels, channel tolerance 8; measured: 0 pixels, bit-identical) with the
// engine picking the same triangles and visible blocks every frame, and its frame-to-frame
// change must not exceed the origin's by more than 0.1 % of the pixels. Float32 vertex
// jitter does: with the VBO shift/scale disabled, the ECEF copy measured 0.29 % excess.
int LargeCoordinates(vtkRenderWindow* win, vtkRenderer* ren, vtkActor* actor)
{
  const int frames = 100;
  const double creep = 0.25;
  const Placement placements[] = { { "origin", { 0, 0, 0 } },
    { "UTM (500000, 5000000, 0)", { 500000, 5000000, 0 } },
    { "ECEF (6.4e6, 6.4e6, 6.4e6)", { 6.4e6, 6.4e6, 6.4e6 } } };
  int* size = win->GetSize();
  const int pixels = size[0] * size[1];
  auto base = gmmtest::SyntheticImage(257, 257, 30.0, 5, 2000.0);
  std::vector<vtkSmartPointer<vtkImageData>> originShots;
  std::vector<std::array<vtkIdType, 2>> originStats;
  std::vector<int> originSteps;
  int failures = 0;
  for (const Placement& pl : placements)
  {
    const double* o = pl.Offset;
    vtkNew<vtkGeoMipMapMapper> mapper;
    mapper->SetInputData(PlacedDEM(base, o[0], o[1], o[2]));
    mapper->SetPixelError(2.0);
    mapper->ScalarVisibilityOff();
    actor->SetMapper(mapper);
    const bool isOrigin = originShots.empty();
    vtkSmartPointer<vtkImageData> previous;
    int worstVsOrigin = 0, worstStepExcess = -pixels, statMismatches = 0, firstDiffer = 0;
    long stepSum = 0;
    for (int f = 0; f < frames; ++f)
    {
      SetCamera(ren->GetActiveCamera(), o[0] + f * creep, o[1] + f * creep, o[2]);
      ren->ResetCameraClippingRange();
      win->Render();
      auto shot = gmmtest::Grab(win);
      const std::array<vtkIdType, 2> stats = { mapper->GetNumberOfRenderedTriangles(),
        mapper->GetNumberOfVisibleBlocks() };
      const int step = previous ? gmmtest::CountDifferentPixels(previous, shot, 8) : 0;
      stepSum += step;
      if (isOrigin)
      {
        originShots.push_back(shot);
        originStats.push_back(stats);
        originSteps.push_back(step);
      }
      else
      {
        const int differ = gmmtest::CountDifferentPixels(originShots[f], shot, 8);
        firstDiffer = f == 0 ? differ : firstDiffer;
        worstVsOrigin = std::max(worstVsOrigin, differ);
        worstStepExcess = std::max(worstStepExcess, step - originSteps[f]);
        statMismatches += stats != originStats[f] ? 1 : 0;
      }
      previous = shot;
    }
    std::cout << pl.Name << ": frame 0 " << mapper->GetNumberOfRenderedTriangles()
              << " triangles; consecutive frames differ in " << stepSum / double(frames - 1)
              << " pixels on average";
    if (!isOrigin)
    {
      std::cout << "; vs origin: frame 0 " << firstDiffer << " pixels ("
                << 100.0 * firstDiffer / pixels << " %), worst frame " << worstVsOrigin << " ("
                << 100.0 * worstVsOrigin / pixels << " %), worst step excess " << worstStepExcess
                << ", frames with other triangle/block counts " << statMismatches;
      if (worstVsOrigin > pixels / 200 || worstStepExcess > pixels / 1000 || statMismatches)
      {
        std::cout << "  <-- FAIL";
        ++failures;
      }
    }
    std::cout << "\n";
  }
  return failures;
}

// The mapper (its vertex shader places and morphs the vertices) against the filter (the
// CPU does, gmm::morphedHeight) drawn by a stock vtkPolyDataMapper, for one DEM, block size
// and camera: the same triangle count, and the same depth buffer but for the rasterisation
// of shared edges (0.1 % of pixels differing by more than `tolerance`). Returns the failures.
int DepthAgreement(const char* what, vtkImageData* image, int block, const double position[3],
  const double focal[3], double tolerance, vtkRenderWindow* win, vtkRenderer* ren, vtkActor* actor)
{
  int failures = 0;
  const int W = win->GetSize()[0], H = win->GetSize()[1];
  vtkNew<vtkGeoMipMapMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlockSize(block);
  mapper->SetPixelError(2.0);
  mapper->ScalarVisibilityOff();
  actor->SetMapper(mapper);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(position[0], position[1], position[2]);
  cam->SetFocalPoint(focal[0], focal[1], focal[2]);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(35);
  ren->ResetCameraClippingRange();
  win->Render();
  auto mapperDepth = gmmtest::GrabDepth(win);

  vtkNew<vtkGeoMipMapFilter> filter;
  filter->SetInputData(image);
  filter->SetBlockSize(block);
  filter->SetCamera(cam); // clipping range as the render left it
  filter->SetViewportSize(W, H);
  filter->SetPixelError(2.0);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  const vtkIdType filterTris = out->GetNumberOfPolys();
  const vtkIdType samples = image->GetNumberOfPoints();
  std::cout << what << ": mapper " << mapper->GetNumberOfRenderedTriangles() << " triangles, filter "
            << filterTris << " (field " << out->GetFieldData()->GetArray("Triangles")->GetTuple1(0)
            << "), points " << out->GetNumberOfPoints() << " of " << samples << "\n";
  if (filterTris != mapper->GetNumberOfRenderedTriangles() || filterTris == 0 || out->GetNumberOfPoints() >= samples)
  {
    ++failures;
  }
  vtkNew<vtkPolyDataMapper> stock;
  stock->SetInputConnection(filter->GetOutputPort());
  stock->ScalarVisibilityOff();
  actor->SetMapper(stock);
  win->Render();
  auto stockDepth = gmmtest::GrabDepth(win);
  double worst = 0.0;
  const int differ = gmmtest::CountDifferentDepths(mapperDepth, stockDepth, tolerance, &worst);
  std::cout << what << ": mapper vs filter+stock mapper: " << differ << " pixels differ in depth by > " << tolerance
            << ", max " << worst << "\n";
  if (differ > W * H / 1000) // 0.1 %: rasterisation of shared edges only
  {
    ++failures;
  }
  return failures;
}
}

int TestGeoMipMapFilterAgreement(int, char*[])
{
  int failures = 0;
  vtkNew<vtkActor> actor;
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  auto win = gmmtest::OffscreenWindow(400, 300, ren);
  const double position[3] = { -1500, -2500, 3500 }, focal[3] = { 3000, 3000, 600 };
  failures += DepthAgreement("low oblique view", gmmtest::SyntheticImage(257, 257, 30.0, 5, 2000.0), 32, position,
    focal, 1e-5, win, ren, actor);
  // High over gentle terrain with small blocks: nodes whose block corners glide onto their
  // fans (FanMorph.h; 38 such nodes in this view when it was set up), which the shader reads
  // per block corner. Far away, so the depths are compared more finely.
  const double high[3] = { -3000, -3000, 6000 }, far[3] = { 9000, 9000, 0 };
  failures += DepthAgreement("high view, corners gliding", gmmtest::SyntheticImage(513, 513, 30.0, 1, 300.0), 16,
    high, far, 1e-6, win, ren, actor);
  failures += LargeCoordinates(win, ren, actor);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
