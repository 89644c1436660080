#include "TerrainFill.h"

#include "TerrainGDAL.h" // registerGdal, GdalErrors, GdalDataset

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace gmm
{

std::string checkFillOptions(double searchDistance, int smoothingIterations)
{
  if (!(std::isfinite(searchDistance) && searchDistance > 0.0))
  {
    return "FillSearchDistance " + std::to_string(searchDistance) +
      " is not finite and positive (it is a distance in samples)";
  }
  if (smoothingIterations < 0 || smoothingIterations > kMaxFillSmoothingIterations)
  {
    return "FillSmoothingIterations " + std::to_string(smoothingIterations) + " is not in 0.." +
      std::to_string(kMaxFillSmoothingIterations);
  }
  return std::string();
}

double fillMemoryBytes(double nx, double ny, int smoothingIterations)
{
  // Our two byte masks, GDAL's work rasters (row index as UInt16/UInt32, value as float,
  // filter mask byte) and its smoothing rows (iterations + 2 rows of 3 floats, 2 bytes).
  const double perSample = 2.0 + (nx > 65533 || ny > 65533 ? 4.0 : 2.0) + 4.0 + 1.0;
  const double smoothing = smoothingIterations > 0 ? (smoothingIterations + 2.0) * nx * 14.0 : 0.0;
  return perSample * nx * ny + smoothing;
}

namespace
{
int CPL_STDCALL gdalProgress(double fraction, const char*, void* data)
{
  (*static_cast<const std::function<void(double)>*>(data))(fraction);
  return TRUE;
}
} // namespace

std::string fillNodata(HeightBuffer& z, int nx, int ny, double searchDistance,
  int smoothingIterations, const std::vector<unsigned char>* inside,
  std::vector<unsigned char>& filled, const std::function<void(double)>& progress)
{
  std::string problem = checkFillOptions(searchDistance, smoothingIterations);
  if (!problem.empty())
  {
    return problem;
  }
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  if (nx < 1 || ny < 1 || z.size() != n || (inside && inside->size() != n))
  {
    return "cannot be filled: the heights and the grid disagree in size";
  }
  filled.assign(n, 0);
  std::size_t voids = 0, valid = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const bool missing = std::isnan(z[k]);
    filled[k] = missing ? 1 : 0; // for now: was nodata
    voids += missing;
    valid += !missing;
  }
  if (voids == 0 || valid == 0)
  {
    filled.assign(n, 0); // nothing to fill, or nothing to fill from
    progress(1.0);
    return std::string();
  }
  registerGdal();
  GdalErrors errors;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  if (!mem)
  {
    return "cannot be filled: GDAL's MEM driver is missing" + errors.suffix();
  }
  // A MEM dataset whose one band is our buffer (no copy): GDAL fills it in place.
  GdalDataset ds(GDALCreate(mem, "", nx, ny, 0, GDT_Float32, nullptr));
  char pointer[64] = { 0 }; // CPLPrintPointer does not terminate the string
  CPLPrintPointer(pointer, z.data(), static_cast<int>(sizeof(pointer) - 1));
  CPLStringList bandOptions;
  bandOptions.SetNameValue("DATAPOINTER", pointer);
  bandOptions.SetNameValue("PIXELOFFSET", "4");
  bandOptions.SetNameValue("LINEOFFSET", std::to_string(4LL * nx).c_str());
  if (!ds.h || GDALAddBand(ds.h, GDT_Float32, bandOptions.List()) != CE_None)
  {
    return "cannot be filled: GDAL could not wrap the heights in a MEM dataset" + errors.suffix();
  }
  GDALRasterBandH band = GDALGetRasterBand(ds.h, 1);
  // NaN as the band's nodata: GDAL derives the validity mask from the heights themselves
  // (no mask raster to build), and recomputes it before smoothing.
  GDALSetRasterNoDataValue(band, std::numeric_limits<double>::quiet_NaN());
  CPLStringList options;
  options.SetNameValue("TEMP_FILE_DRIVER", "MEM"); // GDAL's default writes GTiff files
  // Beyond the raster's diagonal a larger distance changes nothing; capping keeps GDAL's
  // int conversion of it in range.
  const double distance = std::min(searchDistance, std::hypot(double(nx), double(ny)) + 2.0);
  if (GDALFillNodata(band, nullptr, distance, 0, smoothingIterations, options.List(),
        &gdalProgress, const_cast<std::function<void(double)>*>(&progress)) != CE_None)
  {
    return "could not be filled" + errors.suffix();
  }
  GDALFlushCache(ds.h);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!filled[k])
    {
      continue; // an original sample: GDAL wrote back the same bits
    }
    if (inside && !(*inside)[k])
    {
      z[k] = nan; // outside the footprint of the data: stays nodata
      filled[k] = 0;
    }
    else
    {
      filled[k] = std::isnan(z[k]) ? 0 : 1; // beyond the search distance: still nodata
    }
  }
  return std::string();
}

} // namespace gmm
