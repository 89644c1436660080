// TerrainGDAL: what every GDAL user in this module shares (private header): registering
// the drivers once, capturing GDAL's error messages for our own, closing datasets.
#pragma once

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <mutex>
#include <string>

namespace gmm
{

// GDALAllRegister, once per process.
inline void registerGdal()
{
  static std::once_flag once;
  std::call_once(once, []() { GDALAllRegister(); });
}

// Captures GDAL's errors (thread-local handler) while it lives, so that they end up in
// our error text instead of on stderr.
struct GdalErrors
{
  std::string text;
  static void CPL_STDCALL handler(CPLErr cls, CPLErrorNum, const char* msg)
  {
    auto* self = static_cast<GdalErrors*>(CPLGetErrorHandlerUserData());
    if (self && cls >= CE_Failure && msg)
    {
      self->text += (self->text.empty() ? "" : "; ") + std::string(msg);
    }
  }
  GdalErrors() { CPLPushErrorHandlerEx(&GdalErrors::handler, this); }
  ~GdalErrors() { CPLPopErrorHandler(); }
  GdalErrors(const GdalErrors&) = delete;
  GdalErrors& operator=(const GdalErrors&) = delete;
  std::string suffix() const { return text.empty() ? std::string() : " (GDAL: " + text + ")"; }
};

// Closes the dataset when it goes away.
struct GdalDataset
{
  GDALDatasetH h = nullptr;
  GdalDataset() = default;
  explicit GdalDataset(GDALDatasetH ds)
    : h(ds)
  {
  }
  ~GdalDataset()
  {
    if (h)
    {
      GDALClose(h);
    }
  }
  GdalDataset(const GdalDataset&) = delete;
  GdalDataset& operator=(const GdalDataset&) = delete;
};

// A CRS as the reader records it: "AUTHORITY:CODE" when it has one, else its WKT.
inline std::string crsName(OGRSpatialReferenceH srs)
{
  const char* auth = OSRGetAuthorityName(srs, nullptr);
  const char* code = OSRGetAuthorityCode(srs, nullptr);
  if (auth && code)
  {
    return std::string(auth) + ":" + code;
  }
  char* wkt = nullptr;
  OSRExportToWkt(srs, &wkt);
  const std::string name = wkt ? wkt : "unknown";
  CPLFree(wkt);
  return name;
}

} // namespace gmm
