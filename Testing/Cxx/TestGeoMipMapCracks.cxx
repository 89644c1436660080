// Crack test: over rough synthetic terrain, lit, on a magenta background, several oblique
// views at tau = 4 pixels. A crack or T-junction gap lets the background through, so no
// magenta pixel may appear inside the terrain's silhouette. The silhouette is computed
// independently: the full-resolution mesh (every grid triangle, stock vtkPolyDataMapper)
// rendered with the same camera, its terrain mask eroded by ceil(tau) + 1 pixels (the LOD
// surface may legitimately move the outline by up to tau pixels).
#include "GeoMipMapTestUtilities.h"
#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
bool IsMagenta(const unsigned char* p)
{
  return p[0] > 250 && p[1] < 5 && p[2] > 250;
}
}

int TestGeoMipMapCracks(int, char*[])
{
  const double tau = 4.0;
  const int W = 400, H = 300;
  auto image = gmmtest::SyntheticImage(257, 257, 30.0, 7, 2500.0);

  vtkNew<vtkGeoMipMapMapper> lod;
  lod->SetInputData(image);
  lod->SetPixelError(tau);
  lod->SetBlockSize(16); // many blocks: many seams between different levels
  lod->ScalarVisibilityOff();
  vtkNew<vtkPolyDataMapper> full;
  full->SetInputData(gmmtest::FullResolutionMesh(image));
  full->ScalarVisibilityOff();

  vtkNew<vtkActor> actor;
  actor->GetProperty()->SetColor(0.8, 0.75, 0.6);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(1, 0, 1);
  ren->AddActor(actor);
  auto win = gmmtest::OffscreenWindow(W, H, ren);

  // Oblique views from around the terrain (centre 3840, 3840), low and high.
  const double views[][6] = { { -2000, -3000, 4500, 3840, 3840, 800 },
    { 9000, -1500, 3500, 3500, 4200, 900 }, { 9500, 9000, 5000, 3600, 3600, 700 },
    { -1500, 8000, 3000, 4000, 3500, 1000 }, { 3840, -6000, 9000, 3840, 3000, 600 },
    { 1000, 1000, 3200, 4500, 4500, 1200 } };
  const int erode = static_cast<int>(std::ceil(tau)) + 1;
  int failures = 0;
  int v = 0;
  for (const auto& c : views)
  {
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetPosition(c[0], c[1], c[2]);
    cam->SetFocalPoint(c[3], c[4], c[5]);
    cam->SetViewUp(0, 0, 1);
    cam->SetViewAngle(40);

    actor->SetMapper(full);
    ren->ResetCameraClippingRange();
    win->Render();
    auto reference = gmmtest::Grab(win);
    actor->SetMapper(lod);
    win->Render();
    auto shot = gmmtest::Grab(win);

    // Mask of terrain pixels in the reference, eroded by `erode` pixels.
    std::vector<char> inside(W * H, 0);
    for (int y = 0; y < H; ++y)
    {
      for (int x = 0; x < W; ++x)
      {
        inside[y * W + x] = !IsMagenta(gmmtest::Pixel(reference, x, y));
      }
    }
    int insideCount = 0, holes = 0;
    for (int y = erode; y < H - erode; ++y)
    {
      for (int x = erode; x < W - erode; ++x)
      {
        bool in = true;
        for (int dy = -erode; dy <= erode && in; ++dy)
        {
          for (int dx = -erode; dx <= erode && in; ++dx)
          {
            in = inside[(y + dy) * W + x + dx] != 0;
          }
        }
        if (in)
        {
          ++insideCount;
          if (IsMagenta(gmmtest::Pixel(shot, x, y)))
          {
            ++holes;
          }
        }
      }
    }
    std::cout << "view " << v << ": triangles " << lod->GetNumberOfRenderedTriangles()
              << ", certified error " << lod->GetMaximumScreenSpaceError() << " px, "
              << insideCount << " pixels inside, " << holes << " magenta inside\n";
    if (insideCount < W * H / 10)
    {
      std::cerr << "view " << v << ": the terrain covers too little of the image\n";
      ++failures;
    }
    if (holes > 0 || lod->GetMaximumScreenSpaceError() > tau)
    {
      ++failures;
    }
    ++v;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
