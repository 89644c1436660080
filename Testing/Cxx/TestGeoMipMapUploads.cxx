// Buffer traffic of vtkGeoMipMapMapper: the heights go to the GPU once per change of the
// height array (never for a camera move, a new PixelError, a texture or a colouring
// change), and the triangle index buffer is uploaded only when the engine's indices change
// (never for a static camera). Also checks that two renderers with different cameras
// sharing the mapper each get their own LOD, and that a texture shows and goes away
// without any height upload (texture coordinates come from the shader).
#include "GeoMipMapTestUtilities.h"
#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"

#include <iostream>

#define CHECK(cond)                                                                         \
  do                                                                                        \
  {                                                                                         \
    if (!(cond))                                                                            \
    {                                                                                       \
      std::cerr << __LINE__ << ": failed: " #cond "\n";                                   \
      ++failures;                                                                           \
    }                                                                                       \
  } while (false)

int TestGeoMipMapUploads(int, char*[])
{
  int failures = 0;
  auto image = gmmtest::SyntheticImage(257, 257, 30.0, 3, 1500.0);
  vtkNew<vtkGeoMipMapMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  auto win = gmmtest::OffscreenWindow(400, 300, ren);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(-2000, -3000, 4000);
  cam->SetFocalPoint(3840, 3840, 700);
  cam->SetViewUp(0, 0, 1);
  ren->ResetCameraClippingRange();

  win->Render();
  const int v0 = mapper->GetNumberOfHeightUploads(), i0 = mapper->GetNumberOfIndexUploads();
  std::cout << "first frame: height uploads " << v0 << ", index uploads " << i0
            << ", triangles " << mapper->GetNumberOfRenderedTriangles() << "\n";
  CHECK(v0 == 1);
  CHECK(i0 >= 1);
  CHECK(mapper->GetNumberOfRenderedTriangles() > 0);
  // GPU memory: the heights where they are a texture (read in place, as llvmpipe's shared
  // heights are, they take none) and the index buffer, which holds this frame's triangles.
  const vtkTypeInt64 heightBytes = mapper->GetHeightsShared() ? 0 : 257 * 257 * 4;
  std::cout << "GPU memory: " << mapper->GetGPUMemoryBytes() << " bytes for 257 x 257 samples"
            << (mapper->GetHeightsShared() ? " (heights shared)" : "") << "\n";
  CHECK(mapper->GetGPUMemoryBytes() >=
    heightBytes + 3 * 4 * static_cast<vtkTypeInt64>(mapper->GetNumberOfRenderedTriangles()));

  // Static camera: nothing is uploaded, the indices are reused.
  for (int k = 0; k < 3; ++k)
  {
    win->Render();
  }
  CHECK(mapper->GetIndicesReused());
  CHECK(mapper->GetNumberOfHeightUploads() == v0);
  CHECK(mapper->GetNumberOfIndexUploads() == i0);

  // Camera moves: indices only, uploaded exactly when the engine made new ones.
  mapper->SetPixelError(4.0);
  win->Render();
  int changed = 0;
  for (int k = 0; k < 5; ++k)
  {
    const int before = mapper->GetNumberOfIndexUploads();
    cam->Azimuth(10);
    ren->ResetCameraClippingRange();
    win->Render();
    const int uploads = mapper->GetNumberOfIndexUploads() - before;
    CHECK(uploads == (mapper->GetIndicesReused() ? 0 : 1));
    changed += mapper->GetIndicesReused() ? 0 : 1;
  }
  CHECK(changed > 0);
  const int i1 = mapper->GetNumberOfIndexUploads();
  std::cout << "after 5 camera moves: height uploads " << mapper->GetNumberOfHeightUploads()
            << ", index uploads " << i1 << "\n";
  CHECK(mapper->GetNumberOfHeightUploads() == v0);
  CHECK(i1 > i0);

  // A new tau changes the indices, not the vertices.
  const vtkIdType before = mapper->GetNumberOfRenderedTriangles();
  mapper->SetPixelError(8.0);
  win->Render();
  std::cout << "tau 8: triangles " << mapper->GetNumberOfRenderedTriangles() << " (was "
            << before << "), height uploads " << mapper->GetNumberOfHeightUploads() << "\n";
  CHECK(mapper->GetNumberOfRenderedTriangles() < before);
  CHECK(mapper->GetNumberOfHeightUploads() == v0);
  CHECK(mapper->GetNumberOfIndexUploads() == i1 + 1);
  mapper->SetPixelError(-1.0); // rejected with an error, previous value kept
  CHECK(mapper->GetPixelError() == 8.0);

  // New heights: uploaded again; the image alone modified (no new heights): nothing.
  image->Modified();
  win->Render();
  CHECK(mapper->GetNumberOfHeightUploads() == v0);
  image->GetPointData()->GetScalars()->Modified();
  win->Render();
  CHECK(mapper->GetNumberOfHeightUploads() == v0 + 1);

  // Colouring and textures change shaders, never the heights.
  mapper->ScalarVisibilityOff();
  win->Render();
  const int v1 = mapper->GetNumberOfHeightUploads();
  CHECK(v1 == v0 + 1);
  // Pixels clearly green (the texture's colour): none on the untextured grey surface.
  auto greenPixels = [&win]() {
    auto img = gmmtest::Grab(win);
    int dims[3];
    img->GetDimensions(dims);
    int green = 0;
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        const unsigned char* p = gmmtest::Pixel(img, x, y);
        green += (p[1] > 40 && p[1] > 2 * p[0] && p[1] > 2 * p[2]) ? 1 : 0;
      }
    return green;
  };
  const int greenBefore = greenPixels();
  const unsigned char light[3] = { 20, 230, 20 }, dark[3] = { 20, 90, 20 };
  vtkNew<vtkTexture> texture;
  texture->SetInputData(gmmtest::Checkerboard(8, 1, light, dark));
  actor->SetTexture(texture);
  win->Render();
  const int greenTextured = greenPixels();
  CHECK(mapper->GetNumberOfHeightUploads() == v1);
  actor->SetTexture(nullptr);
  win->Render();
  win->Render();
  const int greenAfter = greenPixels();
  std::cout << "green pixels: untextured " << greenBefore << ", textured " << greenTextured
            << ", texture removed " << greenAfter << "; height uploads "
            << mapper->GetNumberOfHeightUploads() - v1 << " for adding and removing it\n";
  CHECK(greenBefore == 0 && greenAfter == 0);
  CHECK(greenTextured > 400 * 300 / 10);
  CHECK(mapper->GetNumberOfHeightUploads() == v1);
  mapper->ScalarVisibilityOn();

  // Two renderers, different cameras, one mapper: the LOD follows the camera drawn.
  // The right one sees the whole terrain from far above (few triangles), the left one
  // is close to the ground.
  ren->SetViewport(0, 0, 0.5, 1);
  vtkNew<vtkRenderer> ren2;
  ren2->SetViewport(0.5, 0, 1, 1);
  ren2->AddActor(actor);
  win->AddRenderer(ren2);
  ren2->GetActiveCamera()->SetPosition(3840, 3840, 60000);
  ren2->GetActiveCamera()->SetFocalPoint(3840, 3840, 0);
  ren2->ResetCameraClippingRange();
  cam->SetPosition(3000, 3000, 2500);
  cam->SetFocalPoint(3840, 3840, 700);
  ren->ResetCameraClippingRange();
  ren2->DrawOff();
  win->Render();
  const vtkIdType nearTris = mapper->GetNumberOfRenderedTriangles();
  ren2->DrawOn();
  ren->DrawOff();
  win->Render();
  const vtkIdType farTris = mapper->GetNumberOfRenderedTriangles();
  ren->DrawOn();
  const int i2 = mapper->GetNumberOfIndexUploads();
  win->Render(); // both: ren draws first, then ren2
  std::cout << "near camera " << nearTris << " triangles, far camera " << farTris
            << "; both renderers: last drawn " << mapper->GetNumberOfRenderedTriangles()
            << ", index uploads in that frame " << mapper->GetNumberOfIndexUploads() - i2
            << "\n";
  CHECK(farTris < nearTris);
  CHECK(mapper->GetNumberOfIndexUploads() - i2 == 2);
  CHECK(mapper->GetNumberOfRenderedTriangles() == farTris);
  CHECK(mapper->GetNumberOfHeightUploads() == v1);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
