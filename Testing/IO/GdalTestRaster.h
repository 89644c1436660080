// One-band rasters the IO tests write with GDAL's own drivers (a MEM dataset, copied out
// by the driver), georeferenced in UTM zone 10N or WGS 84 lon/lat.
#pragma once

#include <gdal.h>
#include <ogr_srs_api.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace gmmtest
{

struct GdalRaster
{
  const char* driver = "GTiff";
  GDALDataType type = GDT_Float32;
  int nx = 0, ny = 0;
  std::vector<double> values; // nx * ny, row 0 = north
  bool geographic = false;    // EPSG:4326 (degrees), else EPSG:32610 (metres)
  double west = 500000.0, north = 4000000.0, step = 30.0; // upper-left corner, pixel size
  bool hasNodata = false;
  double nodata = 0.0;
};

// Writes `r` to `path` (EXPECTs success) and returns the path.
inline std::string writeGdalRaster(const std::string& path, const GdalRaster& r)
{
  GDALAllRegister();
  GDALDatasetH src = GDALCreate(GDALGetDriverByName("MEM"), "", r.nx, r.ny, 1, r.type, nullptr);
  GDALRasterBandH band = GDALGetRasterBand(src, 1);
  if (r.hasNodata)
  {
    GDALSetRasterNoDataValue(band, r.nodata);
  }
  EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, r.nx, r.ny, const_cast<double*>(r.values.data()),
              r.nx, r.ny, GDT_Float64, 0, 0),
    CE_None);
  double gt[6] = { r.west, r.step, 0, r.north, 0, -r.step };
  GDALSetGeoTransform(src, gt);
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, r.geographic ? 4326 : 32610);
  OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
  GDALSetSpatialRef(src, srs);
  OSRDestroySpatialReference(srs);
  GDALDatasetH out = GDALCreateCopy(
    GDALGetDriverByName(r.driver), path.c_str(), src, FALSE, nullptr, nullptr, nullptr);
  EXPECT_NE(out, nullptr) << r.driver << " " << path;
  if (out)
  {
    GDALClose(out);
  }
  GDALClose(src);
  return path;
}

} // namespace gmmtest
