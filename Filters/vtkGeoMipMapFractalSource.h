/**
 * @class   vtkGeoMipMapFractalSource
 * @brief   deterministic synthetic mountains of any size, as a DEM image
 *
 * vtkGeoMipMapFractalSource produces the same kind of output as
 * vtkGeoMipMapTerrainReader (a 2D vtkImageData with float32 point scalars "Elevation",
 * metres, active scalars) from gmm::makeSyntheticTerrain: seeded fractal terrain
 * (fBm massifs plus a ridged multifractal), heights in [0, Amplitude] metres, origin
 * (0, 0), x east, y north. The same Seed, Dimensions, Spacing and Amplitude always give
 * bit-identical heights, whatever the number of threads; it fills 16385 x 16385 samples
 * in well under a minute on two cores, for tests and benchmarks beyond the real DEMs.
 *
 * Dimensions below 2 x 2, above 2^31 - 1 samples in total, or a spacing that is not
 * finite and positive make the update fail with an error.
 *
 * @sa vtkGeoMipMapTerrainReader
 */

#ifndef vtkGeoMipMapFractalSource_h
#define vtkGeoMipMapFractalSource_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <string> // For std::string

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapFractalSource : public vtkImageAlgorithm
{
public:
  static vtkGeoMipMapFractalSource* New();
  vtkTypeMacro(vtkGeoMipMapFractalSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of samples along x and y (default 1025 x 1025). Any size >= 2 x 2.
   */
  vtkSetVector2Macro(Dimensions, int);
  vtkGetVector2Macro(Dimensions, int);
  ///@}

  ///@{
  /**
   * Distance between samples in metres, the same along x and y (default 30).
   */
  vtkSetMacro(Spacing, double);
  vtkGetMacro(Spacing, double);
  ///@}

  ///@{
  /**
   * Seed of the terrain (default 1). Different seeds give unrelated terrains.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Height range in metres: heights span [0, Amplitude] (default 1500).
   */
  vtkSetMacro(Amplitude, double);
  vtkGetMacro(Amplitude, double);
  ///@}

protected:
  vtkGeoMipMapFractalSource();
  ~vtkGeoMipMapFractalSource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Empty when the parameters are usable, else why not.
  std::string CheckParameters() const;

  int Dimensions[2] = { 1025, 1025 };
  double Spacing = 30.0;
  unsigned int Seed = 1;
  double Amplitude = 1500.0;

private:
  vtkGeoMipMapFractalSource(const vtkGeoMipMapFractalSource&) = delete;
  void operator=(const vtkGeoMipMapFractalSource&) = delete;
};

#endif
