// TerrainIO: GDAL / OpenImageIO reading behind vtkGeoMipMapTerrainReader (private header);
// lon/lat rasters are then resampled to a metric grid by TerrainGeographic.h.
//
// Kept free of VTK so the format logic (georeference, units, nodata, size checks) reads in
// one place; the reader only copies the result into a vtkImageData.
#pragma once

#include "HeightBuffer.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace gmm
{

// The most samples a raster may hold (the reader's image is indexed by int).
constexpr long long kMaxRasterSamples = 2147483647LL;

struct TerrainReadOptions
{
  double heightScale = 1.0;
  double heightOffset = 0.0;
  double spacing = 1.0; // images without georeference
  bool terrainRGB = false;
  // Void filling (TerrainFill.h), after any geographic resampling, on the final grid.
  bool fillNodata = false;
  double fillSearchDistance = 100.0; // samples
  int fillSmoothingIterations = 0;
};

struct TerrainRaster
{
  int nx = 0, ny = 0;
  double x0 = 0.0, y0 = 0.0; // sample (0, 0): south-west, metres
  double dx = 1.0, dy = 1.0; // metres, positive (rows are flipped to j northwards)
  std::string crs = "none";
  std::string format;        // GDAL driver / OpenImageIO format name
  std::string heightUnit;
  bool geographic = false;
  bool georeferenced = true;     // false: a GDAL raster without geotransform (Spacing used)
  // Geographic only (vtkGeoMipMapTerrainReader.h): the local transverse Mercator frame,
  // whose origin (0, 0) is the source's south-west sample (lon0, lat0), and the source's
  // sample steps in degrees. The result is resampled onto a regular grid in that frame.
  double lon0 = 0.0, lat0 = 0.0;
  double centralMeridian = 0.0;
  double lonStep = 0.0, latStep = 0.0;
  HeightBuffer z;                // nx * ny, row j = northwards, NaN = nodata
  std::vector<unsigned char> filled; // fillNodata only: nx * ny, 1 where a void was filled
};

// Reads the header only (no sample is read; nothing large is allocated). Returns "" on
// success, else a sentence saying what is wrong (the caller adds the file name).
std::string readTerrainHeader(
  const std::string& path, const TerrainReadOptions& opt, TerrainRaster& out);

// Reads header and heights. progress(fraction) is called now and then.
std::string readTerrain(const std::string& path, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>& progress);

// A file's contents held in memory (a fuzzer's input, a download). name is the file name
// the bytes stand for: its extension picks OpenImageIO or GDAL as for a file, SRTM tiles
// are recognised by it, and messages use it; nothing is opened under it. data must stay
// valid during the read. Only formats whose dataset is one file are tried: the one-file
// GDAL drivers of kKnownDrivers in TerrainIO.cxx (a file may be any GDAL raster), and the
// OpenImageIO formats that read through an IOProxy.
struct TerrainBytes
{
  const void* data = nullptr;
  std::size_t size = 0;
  std::string name;
};

// The same two reads, from memory: same checks, results and messages as from a file.
std::string readTerrainHeader(
  const TerrainBytes& bytes, const TerrainReadOptions& opt, TerrainRaster& out);
std::string readTerrain(const TerrainBytes& bytes, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>& progress);

} // namespace gmm
