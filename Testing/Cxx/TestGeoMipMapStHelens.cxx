// Mt St Helens (USGS DEM, UTM coordinates near 5.1e6 m) read by VTK's own vtkDEMReader and
// drawn by vtkGeoMipMapMapper with an elevation colour map: the reader's output plugs in
// directly. Regression image; skips when the data is absent (GeoMipMapTestUtilities.h DataFile).
#include "GeoMipMapTestUtilities.h"
#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDEMReader.h"
#include "vtkLookupTable.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"

#include <iostream>

int TestGeoMipMapStHelens(int argc, char* argv[])
{
  std::string file;
  int missing = 0;
  if (!gmmtest::DataFile("SainteHelens.dem", file, missing))
  {
    return missing;
  }
  vtkNew<vtkDEMReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();

  vtkNew<vtkLookupTable> lut; // green lowlands to white summit
  lut->SetHueRange(0.33, 0.0);
  lut->SetSaturationRange(0.6, 0.0);
  lut->SetValueRange(0.5, 1.0);
  vtkNew<vtkGeoMipMapMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetLookupTable(lut);
  mapper->SetScalarRange(682, 2543);
  mapper->SetPixelError(1.0);

  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(1, 1, 2); // vertical exaggeration: the bound is exact under it
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.1, 0.1, 0.2);
  ren->AddActor(actor);
  auto win = gmmtest::OffscreenWindow(400, 300, ren);
  ren->ResetCamera();
  vtkCamera* cam = ren->GetActiveCamera();
  cam->Elevation(-55);
  cam->Azimuth(20);
  cam->OrthogonalizeViewUp();
  cam->Zoom(1.1);
  ren->ResetCameraClippingRange();
  win->Render();
  std::cout << "triangles " << mapper->GetNumberOfRenderedTriangles() << " (full "
            << 2 * 326 * 466 << "), visible blocks " << mapper->GetNumberOfVisibleBlocks()
            << ", certified error " << mapper->GetMaximumScreenSpaceError() << " px, LOD "
            << mapper->GetLastUpdateTime() * 1e3 << " ms\n";
  if (!gmmtest::DrawnWithinTau(reader->GetOutput(), ren, actor, "St Helens, 2x actor z scale"))
  {
    return EXIT_FAILURE;
  }
  int retVal = vtkRegressionTestImage(win);
  return retVal == vtkRegressionTester::PASSED ? EXIT_SUCCESS : EXIT_FAILURE;
}
