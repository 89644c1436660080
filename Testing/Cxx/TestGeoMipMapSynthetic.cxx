// Synthetic terrain from vtkGeoMipMapFractalSource through vtkGeoMipMapMapper, exercising
// the stock features together: a texture with the mapper's texture coordinates (left),
// and LUT colouring with parallel projection and a rotated, translated actor (right).
// Each side's drawn triangles must measure within tau against the full-resolution terrain
// (vtkGeoMipMapScreenError, independent of the engine). Regression image.
#include "GeoMipMapTestUtilities.h"
#include "vtkGeoMipMapFractalSource.h"
#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLookupTable.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"

#include <iostream>

int TestGeoMipMapSynthetic(int argc, char* argv[])
{
  vtkNew<vtkGeoMipMapFractalSource> source;
  source->SetDimensions(513, 513);
  source->SetSpacing(20.0);
  source->SetSeed(11);
  source->SetAmplitude(2000.0);

  // Texture: a 16 x 16 red/white checkerboard over the whole extent.
  const unsigned char white[3] = { 230, 230, 230 }, red[3] = { 230, 40, 40 };
  vtkNew<vtkTexture> texture;
  texture->SetInputData(gmmtest::Checkerboard(256, 16, white, red));
  texture->InterpolateOn();

  vtkNew<vtkGeoMipMapMapper> textured;
  textured->SetInputConnection(source->GetOutputPort());
  textured->ScalarVisibilityOff();
  textured->SetPixelError(2.0);
  vtkNew<vtkActor> left;
  left->SetMapper(textured);
  left->SetTexture(texture);

  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.6, 0.0);
  vtkNew<vtkGeoMipMapMapper> coloured;
  coloured->SetInputConnection(source->GetOutputPort());
  coloured->SetLookupTable(lut);
  coloured->SetScalarRange(0, 2000);
  coloured->SetPixelError(2.0);
  vtkNew<vtkActor> right;
  right->SetMapper(coloured);
  right->SetOrigin(5120, 5120, 0);
  right->RotateZ(30);
  right->SetPosition(1000, -500, 200);

  auto win = gmmtest::OffscreenWindow(400, 300);
  vtkNew<vtkRenderer> r1, r2;
  r1->SetViewport(0, 0, 0.5, 1);
  r2->SetViewport(0.5, 0, 1, 1);
  r1->AddActor(left);
  r2->AddActor(right);
  win->AddRenderer(r1);
  win->AddRenderer(r2);
  for (vtkRenderer* r : { r1.GetPointer(), r2.GetPointer() })
  {
    r->SetBackground(0.15, 0.15, 0.15);
    r->ResetCamera();
    r->GetActiveCamera()->Elevation(-60);
    r->GetActiveCamera()->OrthogonalizeViewUp();
    r->ResetCamera();
  }
  r2->GetActiveCamera()->ParallelProjectionOn();
  r2->ResetCamera();
  r1->GetActiveCamera()->Zoom(1.5);
  r2->GetActiveCamera()->Zoom(1.5);
  win->Render();
  // The screen error of what was drawn, measured independently of the engine's bound
  // (GeoMipMapTestUtilities.h MeasureDrawn), in both renderers: the right one through the
  // actor's rotation and translation, with a parallel projection.
  vtkImageData* image = source->GetOutput();
  const bool leftOk = gmmtest::DrawnWithinTau(image, r1, left, "textured (perspective)");
  const bool rightOk =
    gmmtest::DrawnWithinTau(image, r2, right, "coloured (parallel, rotated + translated actor)");
  if (!leftOk || !rightOk)
  {
    return EXIT_FAILURE;
  }
  int retVal = vtkRegressionTestImage(win);
  return retVal == vtkRegressionTester::PASSED ? EXIT_SUCCESS : EXIT_FAILURE;
}
