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
 *   (recorded as "EPSG:4326 (assumed)"): resampled onto a regular grid in a local metric
 *   frame, the WGS84 transverse Mercator projection (GeographicLib::TransverseMercator,
 *   scale 1) on the raster's central meridian, shifted so that the raster's south-west
 *   sample (lon0, lat0) is (0, 0). Field data "GeographicOrigin" holds (lon0, lat0) and
 *   "CentralMeridian" the meridian; GeographicToLocal / LocalToGeographic convert.
 *   Why transverse Mercator: it is conformal (the same scale in every direction, so slopes
 *   and shapes are kept) and its scale is exactly 1 on the central meridian, growing only
 *   with the distance E from it, as 1 + E^2 / (2 R^2); heights stay heights above the
 *   datum. A local tangent plane would instead shrink distances radially only (not
 *   conformal) and, used for heights, bend the terrain down by the earth's curvature
 *   (about 160 m at 45 km). The equirectangular frame used before (one pair of radii of
 *   curvature at the centre latitude) was off by up to 0.9 % east-west on a one-degree
 *   SRTM tile at 46.5 N, because the east-west scale drifts with latitude across it.
 *   The grid: spacing = the source's sample steps in metres at its centre latitude
 *   (east-west and north-south, so about as many samples as the source), nodes at
 *   multiples of the spacing from (0, 0), covering the footprint of the source (its
 *   curved corners hold NaN). A node's height is bilinear in the 4 source samples around
 *   its lon/lat (the nearest one when any of the 4 is nodata). Rasters wider than 40
 *   degrees of longitude are refused (reproject them). What the mapper draws, and the
 *   screen-space error it certifies, refer to this resampled grid.
 *   **Accuracy**: horizontal distances on the grid match WGS84 geodesic distances
 *   (GeographicLib::Geodesic) between the points the nodes represent to a relative error
 *   of at most GetGeographicDistanceError() = 4e-5 (0.004 %) for rasters up to 1 degree
 *   of longitude wide, at any latitude. The error is the projection's scale, so it grows
 *   with the square of the width. Measured on 20000 random node pairs: Rainier (N46W122)
 *   1.8e-5, N42E001 2.1e-5, N48W125 1.7e-5, Boulder (0.2 degree wide) 8.8e-7; 3.7e-5 on a
 *   synthetic one-degree tile at the equator, the widest in metres (Testing/Python/
 *   TestGeographicFrame.py and TestTerrainReaderData.py check the figure).
 * - Images read through OpenImageIO have no georeference: origin (0, 0), Spacing metres.
 *   A GDAL raster without a geotransform is read the same way, rows north-up, with a
 *   warning (a GeoTIFF that lost its tags should not pass unnoticed).
 *
 * Void filling (FillNodata, off by default): nodata samples that have a valid sample
 * within FillSearchDistance samples are filled with GDAL's GDALFillNodata (gdal_alg.h):
 * the nearest valid sample in each of four quadrants around the void sample (searched on
 * the sample grid, Euclidean distance in sample steps), weighted by inverse distance, then
 * FillSmoothingIterations passes of a 3x3 mean over the filled samples only. It runs on
 * the output grid, after any geographic resampling, so every sample that is valid without
 * filling keeps exactly the same value; nodes of a geographic raster's grid that lie
 * outside the source's footprint (its curved corners) stay NaN, as do voids farther than
 * the search distance from any valid sample. The filled samples are marked in the point
 * array "FilledNodata" (unsigned char: 1 filled, 0 original or still nodata), present only
 * when FillNodata is on: colour by it (SelectColorArray, a lookup table) or set those
 * samples back to NaN to exclude them. Filled values are interpolated, not measured: a
 * void 2 km wide over a ridge comes out as a smooth saddle. With FillNodata off the
 * output is the same as without the feature. Bad parameters (a search distance that is
 * not finite and positive, smoothing iterations outside 0..1000) fail the update with an
 * error naming the file and the parameter.
 *
 * Field data: "CRS" (string: "EPSG:xxxx", the WKT, or "none"), "SourceFormat" (GDAL driver
 * or OpenImageIO format name), "HeightUnit" (string), "GeographicOrigin" (2 doubles) and
 * "CentralMeridian" (1 double), both only for geographic rasters.
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

class vtkImageData;

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

  ///@{
  /**
   * Void filling (see the class description). FillNodata: off by default.
   * FillSearchDistance: how far, in samples, to look for valid samples (finite, > 0;
   * default 100, as gdal_fillnodata). FillSmoothingIterations: 3x3 mean passes over the
   * filled samples (0..1000, default 0).
   */
  vtkSetMacro(FillNodata, vtkTypeBool);
  vtkGetMacro(FillNodata, vtkTypeBool);
  vtkBooleanMacro(FillNodata, vtkTypeBool);
  vtkSetMacro(FillSearchDistance, double);
  vtkGetMacro(FillSearchDistance, double);
  vtkSetMacro(FillSmoothingIterations, int);
  vtkGetMacro(FillSmoothingIterations, int);
  ///@}

  ///@{
  /**
   * Memory, in bytes, a read may take (0, default: the memory available on this machine
   * now). Before reading the samples the reader estimates what the read needs (the
   * heights, which the output image adopts without a copy, as much again for the decoded
   * image of a tiled image file, once more for a geographic raster's resampling, and the
   * masks and work rasters of void filling) and refuses a file that does not fit, with an
   * error naming the file, its size and the memory available.
   */
  vtkSetMacro(MemoryLimit, vtkTypeInt64);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Geographic rasters: lon/lat (degrees, WGS84) to the image's x, y (metres) and back,
   * using the field data of an image this reader produced. Return false (and leave the
   * output untouched) when the image has no "GeographicOrigin" / "CentralMeridian".
   */
  static bool GeographicToLocal(vtkImageData* image, double lon, double lat, double xy[2]);
  static bool LocalToGeographic(vtkImageData* image, double x, double y, double lonLat[2]);
  ///@}

  /**
   * The geographic frame of an image this reader produced: (lon0, lat0, central meridian)
   * from "GeographicOrigin" and "CentralMeridian". False (frame untouched) when absent.
   */
  static bool GetGeographicFrame(vtkImageData* image, double frame[3]);

  /**
   * The stated accuracy of the geographic frame (see the class description): the largest
   * relative error of a horizontal distance on the grid against the WGS84 geodesic
   * distance, for rasters up to 1 degree of longitude wide.
   */
  static double GetGeographicDistanceError() { return 4e-5; }

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
  vtkTypeInt64 MemoryLimit = 0;
  vtkTypeBool FillNodata = 0;
  double FillSearchDistance = 100.0;
  int FillSmoothingIterations = 0;

private:
  vtkGeoMipMapTerrainReader(const vtkGeoMipMapTerrainReader&) = delete;
  void operator=(const vtkGeoMipMapTerrainReader&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
