#include "TerrainDrape.h"

#include "TerrainGDAL.h" // registerGdal, GdalErrors, GdalDataset, crsName

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>

namespace gmm
{
namespace
{

// The most pixels a drape holds: 16384 x 16384 (1 GiB as RGBA), OpenGL's usual texture
// limit. A larger image must be resampled (DrapeOptions::maximumSize).
constexpr long long kMaxDrapePixels = 16384LL * 16384LL;

// GDAL utility options from a list of arguments.
CPLStringList argList(const std::vector<std::string>& args)
{
  CPLStringList list;
  for (const std::string& a : args)
  {
    list.AddString(a.c_str());
  }
  return list;
}

std::string wktOf(const OGRSpatialReference& srs)
{
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  const std::string s = wkt ? wkt : "";
  CPLFree(wkt);
  return s;
}

// Everything a drape is made from: the image as R, G, B (+ alpha) bytes, and the frame.
struct Plan
{
  GdalDataset file; // the image as opened
  GdalDataset rgb;  // a VRT over it: bands R, G, B and, when hasAlpha, A (closed first)
  bool hasAlpha = false;
  double gt[6] = { 0, 1, 0, 0, 0, 1 };
  int width = 0, height = 0;
  OGRSpatialReference target; // the frame's CRS (geographic terrain: its local TM)
  OGRSpatialReference source; // the image's CRS, as found or assumed
  double linear = 1.0;        // frame metres per target unit
  bool direct = false;        // no warp: the file's pixels as they are
  double warpGt[6] = { 0, 1, 0, 0, 0, 1 }; // warp only: the output grid
};

// The VRT of R, G, B (+ A) bands: RGB(A) by colour interpretation (else bands 1, 2, 3),
// grey (+ alpha) repeated three times, a palette expanded. 8-bit bands only.
std::string colourBands(Plan& p)
{
  GDALDatasetH ds = p.file.h;
  const int n = GDALGetRasterCount(ds);
  if (n < 1)
  {
    return "the file has no raster band";
  }
  auto interp = [ds](int b) { return GDALGetRasterColorInterpretation(GDALGetRasterBand(ds, b)); };
  std::vector<int> bands;
  int alpha = 0;
  std::vector<std::string> args = { "-of", "VRT" };
  if (n == 1 && interp(1) == GCI_PaletteIndex)
  {
    args.insert(args.end(), { "-expand", "rgba" });
    bands = { 1 };
    p.hasAlpha = true;
  }
  else
  {
    int r = 0, g = 0, b = 0;
    for (int k = 1; k <= n; ++k)
    {
      const GDALColorInterp c = interp(k);
      r = (c == GCI_RedBand && !r) ? k : r;
      g = (c == GCI_GreenBand && !g) ? k : g;
      b = (c == GCI_BlueBand && !b) ? k : b;
      alpha = (c == GCI_AlphaBand && !alpha) ? k : alpha;
    }
    if (!(r && g && b))
    {
      if (n >= 3)
      {
        r = 1, g = 2, b = 3; // no colour interpretation: the usual order
      }
      else
      {
        r = g = b = 1; // grey
        alpha = (n == 2 && !alpha) ? 2 : alpha;
      }
    }
    bands = { r, g, b };
    if (alpha)
    {
      bands.push_back(alpha);
    }
    p.hasAlpha = alpha != 0;
    for (int k : bands)
    {
      args.insert(args.end(), { "-b", std::to_string(k) });
    }
  }
  for (int k : bands)
  {
    const GDALDataType t = GDALGetRasterDataType(GDALGetRasterBand(ds, k));
    if (t != GDT_Byte)
    {
      return std::string("the file has ") + GDALGetDataTypeName(t) + " band(s): only 8-bit colour images "
             "can be draped (convert with gdal_translate -ot Byte -scale)";
    }
  }
  CPLStringList list = argList(args);
  GDALTranslateOptions* opts = GDALTranslateOptionsNew(list.List(), nullptr);
  int usage = 0;
  p.rgb.h = GDALTranslate("", ds, opts, &usage);
  GDALTranslateOptionsFree(opts);
  if (!p.rgb.h)
  {
    return "the file could not be opened as colour bands";
  }
  if (p.hasAlpha)
  {
    GDALSetRasterColorInterpretation(GDALGetRasterBand(p.rgb.h, 4), GCI_AlphaBand);
  }
  return std::string();
}

// The frame's CRS: the terrain's own (projected), or the local transverse Mercator frame
// of a geographic terrain (its lon/lat datum, shifted so that (lon0, lat0) is (0, 0)).
std::string frameCrs(const TerrainFrame& frame, Plan& p, OGRSpatialReference& terrain)
{
  if (frame.crs.empty() || frame.crs == "none")
  {
    return "the terrain has no CRS (its field data says none), so there is no frame to place "
           "the image in";
  }
  std::string name = frame.crs;
  const std::string assumed = " (assumed)";
  if (name.size() > assumed.size() &&
    name.compare(name.size() - assumed.size(), assumed.size(), assumed) == 0)
  {
    name.erase(name.size() - assumed.size());
  }
  if (terrain.SetFromUserInput(name.c_str()) != OGRERR_NONE)
  {
    return "the terrain's CRS (" + frame.crs.substr(0, 80) + ") is not one GDAL knows";
  }
  terrain.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!frame.geographic)
  {
    if (!terrain.IsProjected())
    {
      return "the terrain's CRS is not projected, and the terrain has no geographic frame "
             "(GeographicOrigin, CentralMeridian) in its field data";
    }
    p.target = terrain;
    p.linear = terrain.GetLinearUnits();
    return std::string();
  }
  // The reader's frame uses WGS 84's ellipsoid (GeographicLib); GRS 80 (NAD83) differs by
  // 0.1 mm, other ellipsoids by metres.
  if (std::abs(terrain.GetSemiMajor() - 6378137.0) > 0.5 ||
    std::abs(terrain.GetInvFlattening() - 298.257223563) > 1e-3)
  {
    return "the terrain's lon/lat are not on the WGS 84 (or GRS 80) ellipsoid, which the "
           "reader's metric frame assumes";
  }
  p.target.CopyGeogCSFrom(&terrain);
  p.target.SetTM(0.0, frame.centralMeridian, 1.0, 0.0, 0.0);
  p.target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> toTM(
    OGRCreateCoordinateTransformation(&terrain, &p.target));
  double x = frame.lon0, y = frame.lat0;
  if (!toTM || !toTM->Transform(1, &x, &y))
  {
    return "GDAL cannot build the terrain's transverse Mercator frame";
  }
  p.target.SetTM(0.0, frame.centralMeridian, 1.0, -x, -y);
  p.linear = 1.0;
  return std::string();
}

std::string plan(const std::string& path, const TerrainFrame& frame, const DrapeOptions& opt,
  Plan& p, DrapeRaster& out)
{
  out = DrapeRaster();
  if (opt.maximumSize < 0)
  {
    return "MaximumSize " + std::to_string(opt.maximumSize) +
      " is negative (0: the image's own size, else at least 1 pixel)";
  }
  p.file.h = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!p.file.h)
  {
    return "the file is not an image GDAL can read";
  }
  p.width = GDALGetRasterXSize(p.file.h);
  p.height = GDALGetRasterYSize(p.file.h);
  if (GDALGetGeoTransform(p.file.h, p.gt) != CE_None)
  {
    return "the file has no georeference (geotransform): a drape is placed by its "
           "coordinates, not stretched over the terrain";
  }
  if (!std::all_of(p.gt, p.gt + 6, [](double v) { return std::isfinite(v); }) || p.gt[1] == 0.0 ||
    p.gt[5] == 0.0)
  {
    return "the file has a degenerate georeference (geotransform)";
  }
  std::string problem = colourBands(p);
  if (!problem.empty())
  {
    return problem;
  }
  OGRSpatialReference terrain;
  problem = frameCrs(frame, p, terrain);
  if (!problem.empty())
  {
    return problem;
  }
  const OGRSpatialReference* own = OGRSpatialReference::FromHandle(GDALGetSpatialRef(p.file.h));
  if (own)
  {
    p.source = *own;
  }
  else
  {
    p.source = terrain;
    out.warning = "the file has no CRS; it is taken to be in the terrain's (" +
      frame.crs.substr(0, 80) + ")";
  }
  p.source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  out.crs = crsName(OGRSpatialReference::ToHandle(&p.source));

  const int maxSize = opt.maximumSize;
  const bool fits = maxSize == 0 || (p.width <= maxSize && p.height <= maxSize);
  p.direct = !frame.geographic && fits && p.gt[2] == 0.0 && p.gt[4] == 0.0 &&
    p.source.IsSame(&p.target);
  if (p.direct)
  {
    std::copy(p.gt, p.gt + 6, p.warpGt);
    out.nx = p.width;
    out.ny = p.height;
  }
  else
  {
    // GDAL's suggestion keeps about the image's resolution; MaximumSize coarsens it.
    const std::string src = wktOf(p.source), dst = wktOf(p.target);
    CPLStringList to;
    to.SetNameValue("SRC_SRS", src.c_str());
    to.SetNameValue("DST_SRS", dst.c_str());
    void* transformer = GDALCreateGenImgProjTransformer2(p.rgb.h, nullptr, to.List());
    double extent[4] = { 0, 0, 0, 0 };
    int w = 0, h = 0;
    const bool ok = transformer &&
      GDALSuggestedWarpOutput2(p.rgb.h, GDALGenImgProjTransform, transformer, p.warpGt, &w, &h,
        extent, 0) == CE_None;
    if (transformer)
    {
      GDALDestroyGenImgProjTransformer(transformer);
    }
    if (!ok || w < 1 || h < 1)
    {
      return "the file cannot be reprojected into the terrain's frame";
    }
    double res = p.warpGt[1];
    if (maxSize > 0 && (w > maxSize || h > maxSize))
    {
      res *= static_cast<double>(std::max(w, h)) / maxSize;
      w = std::min(maxSize, std::max(1, static_cast<int>(std::ceil((extent[2] - extent[0]) / res))));
      h = std::min(maxSize, std::max(1, static_cast<int>(std::ceil((extent[3] - extent[1]) / res))));
    }
    const double west = extent[0], north = extent[3];
    const double pixel[6] = { west, res, 0.0, north, 0.0, -res };
    std::copy(pixel, pixel + 6, p.warpGt);
    out.nx = w;
    out.ny = h;
    out.warped = true;
  }
  if (static_cast<long long>(out.nx) * out.ny > kMaxDrapePixels)
  {
    return "the image is " + std::to_string(out.nx) + " x " + std::to_string(out.ny) +
      " pixels in the terrain's frame, more than the 16384 x 16384 a drape holds: set "
      "MaximumSize (e.g. 8192) to resample it";
  }
  // Pixel centres of the south-west and north-east pixels, in frame metres.
  const double* g = p.warpGt;
  const double xa = g[0] + 0.5 * g[1], xb = g[0] + (out.nx - 0.5) * g[1];
  const double ya = g[3] + 0.5 * g[5], yb = g[3] + (out.ny - 0.5) * g[5];
  out.x0 = std::min(xa, xb) * p.linear;
  out.y0 = std::min(ya, yb) * p.linear;
  out.dx = std::abs(g[1]) * p.linear;
  out.dy = std::abs(g[5]) * p.linear;
  return std::string();
}

// Reads R, G, B, A of `ds` (nx x ny, 3 or 4 bands; alpha from the mask of band 1 when 3)
// into out.rgba, row 0 south, columns west to east given the geotransform's signs.
std::string readPixels(GDALDatasetH ds, bool hasAlpha, const double gt[6], DrapeRaster& out)
{
  const int nx = out.nx, ny = out.ny;
  std::vector<unsigned char> buf(static_cast<std::size_t>(nx) * ny * 4, 255);
  int bands[4] = { 1, 2, 3, 4 };
  if (GDALDatasetRasterIO(ds, GF_Read, 0, 0, nx, ny, buf.data(), nx, ny, GDT_Byte,
        hasAlpha ? 4 : 3, bands, 4, 4LL * nx, 1) != CE_None)
  {
    return "the file could not be read: truncated or corrupt";
  }
  if (!hasAlpha)
  {
    GDALRasterBandH mask = GDALGetMaskBand(GDALGetRasterBand(ds, 1));
    if (!(GDALGetMaskFlags(GDALGetRasterBand(ds, 1)) & GMF_ALL_VALID) &&
      GDALRasterIO(mask, GF_Read, 0, 0, nx, ny, buf.data() + 3, nx, ny, GDT_Byte, 4, 4LL * nx) !=
        CE_None)
    {
      return "the file could not be read (its nodata mask): truncated or corrupt";
    }
  }
  const bool flipRows = gt[5] < 0.0, flipCols = gt[1] < 0.0;
  out.rgba.resize(buf.size());
  for (int r = 0; r < ny; ++r)
  {
    const unsigned char* src = buf.data() + static_cast<std::size_t>(r) * nx * 4;
    unsigned char* dst = out.rgba.data() + static_cast<std::size_t>(flipRows ? ny - 1 - r : r) * nx * 4;
    for (int c = 0; c < nx; ++c)
    {
      std::memcpy(dst + 4 * (flipCols ? nx - 1 - c : c), src + 4 * c, 4);
    }
  }
  return std::string();
}

} // namespace

std::string planDrape(const std::string& path, const TerrainFrame& frame,
  const DrapeOptions& options, DrapeRaster& out)
{
  registerGdal();
  GdalErrors errors;
  Plan p;
  const std::string problem = plan(path, frame, options, p, out);
  return problem.empty() ? problem : problem + errors.suffix();
}

std::string readDrape(const std::string& path, const TerrainFrame& frame,
  const DrapeOptions& options, DrapeRaster& out)
{
  registerGdal();
  GdalErrors errors;
  Plan p;
  std::string problem = plan(path, frame, options, p, out);
  if (!problem.empty())
  {
    return problem + errors.suffix();
  }
  try
  {
    if (p.direct)
    {
      problem = readPixels(p.rgb.h, p.hasAlpha, p.warpGt, out);
      return problem.empty() ? problem : problem + errors.suffix();
    }
    const double* g = p.warpGt;
    const double east = g[0] + out.nx * g[1], south = g[3] + out.ny * g[5];
    std::vector<std::string> args = { "-of", "MEM", "-r", "bilinear", "-dstalpha", "-s_srs",
      wktOf(p.source), "-t_srs", wktOf(p.target), "-te", CPLSPrintf("%.17g", g[0]),
      CPLSPrintf("%.17g", south), CPLSPrintf("%.17g", east), CPLSPrintf("%.17g", g[3]), "-ts",
      std::to_string(out.nx), std::to_string(out.ny), "-wo", "NUM_THREADS=ALL_CPUS" };
    CPLStringList list = argList(args);
    GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(list.List(), nullptr);
    int usage = 0;
    GDALDatasetH src = p.rgb.h;
    GdalDataset warped(GDALWarp("", nullptr, 1, &src, opts, &usage));
    GDALWarpAppOptionsFree(opts);
    if (!warped.h || GDALGetRasterCount(warped.h) != 4)
    {
      return "the file could not be reprojected into the terrain's frame" + errors.suffix();
    }
    problem = readPixels(warped.h, true, p.warpGt, out);
    return problem.empty() ? problem : problem + errors.suffix();
  }
  catch (const std::bad_alloc&)
  {
    out.rgba = std::vector<unsigned char>();
    return "the image needs more memory than is available";
  }
}

} // namespace gmm
