/**
 * @class   vtkGeoMipMapTerrainReader
 * @brief   read a DEM or a heightmap image into a 2D elevation image in metres
 *
 * vtkGeoMipMapTerrainReader turns every supported elevation file into one shape of
 * vtkImageData, so nothing downstream knows the file format: dimensions nx x ny x 1, point
 * scalars "Elevation" (float32, metres, active scalars), NaN where there is no data, j
 * increasing northwards (y up) and i eastwards, x and y in metres.
 *
 * Formats:
 * - Through GDAL: GeoTIFF and every raster GDAL reads (SRTM .hgt, USGS .dem, ESRI ASCII
 *   .asc, ...). Band 1 is read; GDAL's nodata value, non-finite values and heights beyond
 *   float range become NaN; a colour (RGB or palette) raster is refused; band
 *   scale/offset are applied; heights in feet (GDAL unit type "ft", "foot", "US survey
 *   foot") are converted to metres.
 * - Through OpenImageIO: plain image heightmaps (.png, .jpg, .bmp, .tga, .pgm/.ppm, .exr,
 *   .hdr), 8/16/32-bit integer or float greyscale (a 2-channel grey + alpha image uses
 *   grey), and Mapbox terrain-RGB PNGs when TerrainRGB is on:
 *   h = (R * 65536 + G * 256 + B) / 10 - 10000 m. Terrain-RGB is not auto-detected (an RGB
 *   photo and a terrain-RGB tile cannot be told apart reliably): an RGB(A) image read with
 *   TerrainRGB off is an error that asks for it, and a greyscale image with TerrainRGB on is
 *   an error too.
 *
 * Heights: h = HeightScale * v + HeightOffset, where v is metres for GDAL rasters and
 * terrain-RGB, and the stored value for greyscale images (so for a 16-bit PNG in
 * decimetres use HeightScale 0.1). Field data "HeightUnit" holds the unit of v.
 *
 * Georeference (GDAL rasters). GDAL's geotransform gives pixel corners; samples are put
 * at pixel centres (+0.5 pixel). Rotated geotransforms are refused.
 * - Projected CRS: x, y are the CRS coordinates converted to metres (e.g. UTM eastings and
 *   northings: large values, on purpose, as in the source).
 * - Geographic CRS (lon/lat), or no CRS with a geotransform inside the lon/lat range
 *   (recorded as "EPSG:4326 (assumed)"): a local metric frame. With (lon0, lat0) the
 *   south-west sample and lat_c the latitude of the DEM's centre,
 *   x = (lon - lon0) * pi/180 * N(lat_c) * cos(lat_c),  y = (lat - lat0) * pi/180 * M(lat_c),
 *   where M and N are the WGS84 meridional and prime-vertical radii of curvature from
 *   GeographicLib::Ellipsoid::WGS84(). The origin is (0, 0) at the south-west sample; the
 *   field data array "GeographicOrigin" holds (lon0, lat0). The error of this
 *   equirectangular frame over a one-degree tile is below 0.1 % of distances.
 * - Images read through OpenImageIO have no georeference: origin (0, 0), Spacing metres.
 *   A GDAL raster without a geotransform is read the same way, rows north-up, with a
 *   warning (a GeoTIFF that lost its tags should not pass unnoticed).
 *
 * Field data: "CRS" (string: "EPSG:xxxx", the WKT, or "none"), "SourceFormat" (GDAL driver
 * or OpenImageIO format name), "HeightUnit" (string), "GeographicOrigin" (2 doubles, only
 * for geographic rasters).
 *
 * Robustness: a missing, empty, truncated or malformed file, an unsupported sample type, or
 * a header whose size the file cannot hold (checked against the file size and a cap of
 * 2^31 - 1 samples before anything is allocated) ends in vtkErrorMacro naming the file and
 * the problem, and the update fails. The reader stays usable for the next file. A file
 * whose samples are all nodata reads, with a warning: nothing will be drawn.
 *
 * @sa vtkGeoMipMapFractalSource vtkDEMReader
 */

#ifndef vtkGeoMipMapTerrainReader_h
#define vtkGeoMipMapTerrainReader_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <memory> // For std::unique_ptr

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapTerrainReader : public vtkImageAlgorithm
{
public:
  static vtkGeoMipMapTerrainReader* New();
  vtkTypeMacro(vtkGeoMipMapTerrainReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Name of the file to read.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /**
   * Heights are HeightScale * value + HeightOffset (defaults 1 and 0). For images without
   * georeference, HeightScale is the number of metres per stored unit.
   */
  vtkSetMacro(HeightScale, double);
  vtkGetMacro(HeightScale, double);
  vtkSetMacro(HeightOffset, double);
  vtkGetMacro(HeightOffset, double);
  ///@}

  ///@{
  /**
   * Sample spacing in metres for images without georeference (default 1). Ignored for
   * georeferenced rasters, whose spacing comes from the file.
   */
  vtkSetMacro(Spacing, double);
  vtkGetMacro(Spacing, double);
  ///@}

  ///@{
  /**
   * Decode RGB(A) images as Mapbox terrain-RGB (default off; see the class description).
   */
  vtkSetMacro(TerrainRGB, vtkTypeBool);
  vtkGetMacro(TerrainRGB, vtkTypeBool);
  vtkBooleanMacro(TerrainRGB, vtkTypeBool);
  ///@}

protected:
  vtkGeoMipMapTerrainReader();
  ~vtkGeoMipMapTerrainReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  double HeightScale = 1.0;
  double HeightOffset = 0.0;
  double Spacing = 1.0;
  vtkTypeBool TerrainRGB = 0;

private:
  vtkGeoMipMapTerrainReader(const vtkGeoMipMapTerrainReader&) = delete;
  void operator=(const vtkGeoMipMapTerrainReader&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
