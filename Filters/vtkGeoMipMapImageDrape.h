/**
 * @class   vtkGeoMipMapImageDrape
 * @brief   brings a georeferenced colour image (an orthophoto) into a terrain's frame
 *
 * vtkGeoMipMapImageDrape reads an image file through GDAL (GeoTIFF orthophotos and any
 * GDAL raster with RGB(A) bands, a grey band, or a palette) and produces the image that
 * vtkGeoMipMapMapper::SetDrapeImage lays over the terrain: a 2D vtkImageData of unsigned
 * char RGBA ("DrapeRGBA", alpha 0 where the image has no data), whose origin and spacing
 * put each pixel centre at its ground position in the terrain's x, y. The image is placed
 * by both files' georeference, never stretched over the terrain: where it does not cover
 * the terrain the terrain keeps its own colouring, and parts beyond the terrain are kept
 * (they are simply not drawn).
 *
 * The terrain's frame comes from the field data vtkGeoMipMapTerrainReader writes into its
 * output (SetTerrain: that output, updated): "CRS", and for lon/lat DEMs the local
 * transverse Mercator frame ("GeographicOrigin", "CentralMeridian"). Then:
 * - image in the terrain's (projected) CRS, north-up, within MaximumSize: its pixels are
 *   used as they are (no resampling);
 * - otherwise (another CRS, a lon/lat terrain, a rotated image, or larger than
 *   MaximumSize): GDAL's warper reprojects it (bilinear) into the frame, at about the
 *   image's own resolution (GDALSuggestedWarpOutput2) or coarser to fit MaximumSize.
 *   Pixels outside the source image get alpha 0.
 * An image without a CRS is taken to be in the terrain's CRS (with a warning); one
 * without a geotransform is refused (drape it over the extent with a vtkTexture instead).
 * Source nodata values and alpha bands become alpha 0.
 *
 * Limits: 8-bit bands only; at most 16384 x 16384 pixels in the frame (set MaximumSize to
 * resample a larger image; the mapper also refuses a drape larger than the OpenGL
 * texture limit). A failed read (missing file, no georeference, a terrain without CRS,
 * 16-bit bands, too large) ends in an error naming the file and the problem, and the
 * update fails.
 *
 * Field data of the output: "CRS" (the image's own CRS, as found or assumed) and
 * "DrapeWarped" (1 when GDAL resampled the image).
 *
 * @sa vtkGeoMipMapMapper::SetDrapeImage vtkGeoMipMapTerrainReader
 */

#ifndef vtkGeoMipMapImageDrape_h
#define vtkGeoMipMapImageDrape_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

class vtkImageData;
namespace gmm
{
struct DrapeOptions;
struct DrapeRaster;
struct TerrainFrame;
}

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapImageDrape : public vtkImageAlgorithm
{
public:
  static vtkGeoMipMapImageDrape* New();
  vtkTypeMacro(vtkGeoMipMapImageDrape, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The image to drape.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /**
   * The terrain whose frame the image is brought into: vtkGeoMipMapTerrainReader's
   * output, already updated (only its field data is used).
   */
  void SetTerrain(vtkImageData* terrain);
  vtkImageData* GetTerrain();
  ///@}

  ///@{
  /**
   * Largest side of the output, in pixels; 0 (default) keeps the image's resolution. A
   * larger image is resampled to fit (for the mapper, the OpenGL texture size limit, which
   * vtkTextureObject::GetMaximumTextureSize gives). Negative values are refused.
   */
  vtkSetMacro(MaximumSize, int);
  vtkGetMacro(MaximumSize, int);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkGeoMipMapImageDrape();
  ~vtkGeoMipMapImageDrape() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  int MaximumSize = 0;
  vtkSmartPointer<vtkImageData> Terrain;

private:
  // The terrain's frame and the output grid; false after an error naming the file.
  bool Plan(gmm::TerrainFrame& frame, gmm::DrapeRaster& plan);
  gmm::DrapeOptions Options() const;

  vtkGeoMipMapImageDrape(const vtkGeoMipMapImageDrape&) = delete;
  void operator=(const vtkGeoMipMapImageDrape&) = delete;
};

#endif
