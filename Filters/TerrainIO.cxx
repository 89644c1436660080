#include "TerrainIO.h"

#include "TerrainFill.h"       // fillNodata
#include "TerrainGDAL.h"       // GdalErrors, GdalDataset, registerGdal, crsName
#include "TerrainGeographic.h" // geoGrid

#include "Heightfield.h" // gmm::kMaxHeight

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Ellipsoid.hpp>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <set>
#include <sys/stat.h>

namespace gmm
{
namespace
{

constexpr double kPi = 3.14159265358979323846;
// Compressed formats: a sample costs at least 1/1100 byte (deflate tops out near 1032:1),
// with a floor so that small, highly compressible files still read.
constexpr double kMaxCompression = 1100.0;
constexpr double kCompressedFloorBytes = 64.0 * 1024 * 1024;

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// GDAL drivers this reader knows by name. bytes: how few bytes a sample can take in their
// files, for checkSize (any other driver is taken as compressed). oneFile: a dataset is
// one file, so it can be read from memory. Bytes in memory are offered to those drivers
// only: a format that needs a second file cannot be read from one buffer, and the other
// drivers are formats this reader does not know (a file on disk may still be any raster).
enum class SampleBytes
{
  Text,           // at least a digit and a separator
  Raw,            // the sample type's size
  TiffCompressed, // the sample type's size unless the TIFF says it is compressed
};
struct KnownDriver
{
  const char* name;
  SampleBytes bytes;
  bool oneFile;
};
constexpr KnownDriver kKnownDrivers[] = {
  { "GTiff", SampleBytes::TiffCompressed, true },
  { "SRTMHGT", SampleBytes::Raw, true },
  { "USGSDEM", SampleBytes::Text, true },
  { "AAIGrid", SampleBytes::Text, true },
  { "GRASSASCIIGrid", SampleBytes::Text, true },
  { "XYZ", SampleBytes::Text, true },
  { "ISG", SampleBytes::Text, true },
  { "GXF", SampleBytes::Text, true },
  { "BT", SampleBytes::Raw, true },
  { "EHdr", SampleBytes::Raw, false }, // these need a header file beside the data
  { "ENVI", SampleBytes::Raw, false },
  { "GenBin", SampleBytes::Raw, false },
  { "PAux", SampleBytes::Raw, false },
};

// What to read: a file, or bytes in memory standing for a file of that name.
struct Input
{
  std::string name;
  bool inMemory = false;
  const void* data = nullptr; // inMemory only
  std::size_t size = 0;       // inMemory only
};

// A scaled height as float; NaN (nodata) when not finite or beyond the engine's height
// range (gmm::kMaxHeight, 1e38): such values are undeclared nodata sentinels (-FLT_MAX is
// common), and beyond float range the cast would be undefined (a float64 1e300).
float toHeight(double v)
{
  return std::abs(v) <= gmm::kMaxHeight ? static_cast<float>(v) : kNaN;
}

bool hasImageExtension(const std::string& path)
{
  static const std::set<std::string> ext = { "png", "jpg", "jpeg", "bmp", "tga", "pgm", "ppm",
    "pnm", "exr", "hdr", "gif", "webp" };
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos)
  {
    return false;
  }
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext.count(e) > 0;
}

// Decoded bytes the header claims, against what the file can hold. minBytesPerSample > 0:
// uncompressed or text format (each sample needs that many bytes in the file); 0: compressed.
std::string checkSize(long long nx, long long ny, double fileSize, double minBytesPerSample)
{
  if (nx < 1 || ny < 1)
  {
    return "has an empty raster (" + std::to_string(nx) + " x " + std::to_string(ny) + ")";
  }
  if (nx > kMaxRasterSamples / ny)
  {
    return "claims " + std::to_string(nx) + " x " + std::to_string(ny) +
      " samples, more than the 2^31 - 1 this reader accepts";
  }
  const double samples = static_cast<double>(nx) * ny;
  const double limit = minBytesPerSample > 0
    ? fileSize / minBytesPerSample
    : std::max(fileSize * kMaxCompression, kCompressedFloorBytes) / 4.0;
  if (samples > limit)
  {
    return "claims " + std::to_string(nx) + " x " + std::to_string(ny) + " samples, but the file (" +
      std::to_string(static_cast<long long>(fileSize)) +
      " bytes) cannot hold that many: truncated or corrupt header";
  }
  return std::string();
}

double footToMetre(const std::string& unit)
{
  std::string u = unit;
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return std::tolower(c); });
  if (u.find("us survey") != std::string::npos || u == "us-ft" || u == "ftus")
  {
    return 1200.0 / 3937.0;
  }
  if (u == "ft" || u == "feet" || u == "foot" || u == "international foot")
  {
    return 0.3048;
  }
  return 1.0;
}

double minBytesPerSample(GDALDatasetH ds, const std::string& driver, GDALDataType type)
{
  for (const KnownDriver& d : kKnownDrivers)
  {
    if (driver == d.name)
    {
      const bool compressed = d.bytes == SampleBytes::TiffCompressed &&
        GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
      return d.bytes == SampleBytes::Text ? 2.0
        : compressed                      ? 0.0
                                          : GDALGetDataTypeSizeBytes(type);
    }
  }
  return 0.0;
}

// The nullptr-terminated list of kKnownDrivers' one-file drivers, for GDALOpenEx.
const char* const* oneFileDrivers()
{
  static const std::vector<const char*> list = [] {
    std::vector<const char*> l;
    for (const KnownDriver& d : kKnownDrivers)
    {
      if (d.oneFile)
      {
        l.push_back(d.name);
      }
    }
    l.push_back(nullptr);
    return l;
  }();
  return list.data();
}

// Bytes in memory as a GDAL /vsimem/ file (not copied) named like the file they stand for
// (SRTMHGT needs the tile name), in a folder of its own; unlinked when this goes away.
class VsiMemFile
{
public:
  explicit VsiMemFile(const Input& in)
  {
    static std::atomic<unsigned long long> serial{ 0 };
    const auto slash = in.name.find_last_of('/');
    path_ = "/vsimem/geomipmap-" + std::to_string(++serial) + "/" +
      (slash == std::string::npos ? in.name : in.name.substr(slash + 1));
    // GDAL only reads it (the dataset is opened read-only): the const_cast is safe.
    VSILFILE* f = VSIFileFromMemBuffer(path_.c_str(),
      static_cast<GByte*>(const_cast<void*>(in.data)), static_cast<vsi_l_offset>(in.size), FALSE);
    if (f)
    {
      VSIFCloseL(f);
    }
  }
  ~VsiMemFile() { VSIUnlink(path_.c_str()); }
  VsiMemFile(const VsiMemFile&) = delete;
  VsiMemFile& operator=(const VsiMemFile&) = delete;
  const std::string& path() const { return path_; }

private:
  std::string path_;
};

std::string gdalHeader(GDALDatasetH ds, double fileSize, const TerrainReadOptions& opt,
  TerrainRaster& out, double& unitToMetre)
{
  const std::string driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
  out.format = driver;
  out.nx = 0;
  out.ny = 0;
  const long long nx = GDALGetRasterXSize(ds), ny = GDALGetRasterYSize(ds);
  if (GDALGetRasterCount(ds) < 1)
  {
    return "has no raster band";
  }
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  const GDALDataType type = GDALGetRasterDataType(band);
  if (type == GDT_Unknown || GDALDataTypeIsComplex(type))
  {
    return std::string("has an unsupported sample type (") + GDALGetDataTypeName(type) + ")";
  }
  // A colour image (RGB or palette) would give one colour channel as heights: garbage.
  const GDALColorInterp colour = GDALGetRasterColorInterpretation(band);
  if (colour == GCI_RedBand || colour == GCI_PaletteIndex)
  {
    return std::string("is a colour (") + GDALGetColorInterpretationName(colour) +
      ") image, not a single-band heightmap";
  }
  std::string problem = checkSize(nx, ny, fileSize, minBytesPerSample(ds, driver, type));
  if (!problem.empty())
  {
    return problem;
  }
  out.nx = static_cast<int>(nx);
  out.ny = static_cast<int>(ny);
  const char* unit = GDALGetRasterUnitType(band);
  out.heightUnit = (unit && *unit) ? unit : "m";
  unitToMetre = footToMetre(out.heightUnit);

  double gt[6] = { 0, 1, 0, 0, 0, 1 };
  const bool hasGt = GDALGetGeoTransform(ds, gt) == CE_None;
  if (!hasGt)
  {
    // No georeference: like an image (north up, origin 0, the reader's Spacing).
    out.x0 = out.y0 = 0.0;
    out.dx = out.dy = opt.spacing;
    out.georeferenced = false;
    return std::string();
  }
  if (!std::all_of(gt, gt + 6, [](double v) { return std::isfinite(v); }))
  {
    return "has a non-finite geotransform (origin or pixel size)"; // found by fuzzing
  }
  if (gt[2] != 0.0 || gt[4] != 0.0 || gt[1] == 0.0 || gt[5] == 0.0)
  {
    return "has a rotated or degenerate geotransform, which is not supported";
  }
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
  bool geographic = srs && OSRIsGeographic(srs);
  double linear = 1.0;
  if (srs)
  {
    out.crs = crsName(srs);
    if (!geographic)
    {
      linear = OSRGetLinearUnits(srs, nullptr);
    }
  }
  // Sample centres of the south-west and north-east samples (GDAL corners + 0.5 pixel).
  const double xa = gt[0] + 0.5 * gt[1], xb = gt[0] + (nx - 0.5) * gt[1];
  const double ya = gt[3] + 0.5 * gt[5], yb = gt[3] + (ny - 0.5) * gt[5];
  const double west = std::min(xa, xb), east = std::max(xa, xb);
  const double south = std::min(ya, yb), north = std::max(ya, yb);
  if (!srs && west >= -180.5 && east <= 180.5 && south >= -90.5 && north <= 90.5 &&
    std::abs(gt[1]) < 1.0 && std::abs(gt[5]) < 1.0)
  {
    geographic = true; // e.g. an ESRI .asc without .prj holding lon/lat
    out.crs = "EPSG:4326 (assumed)";
  }
  if (geographic)
  {
    const GeographicLib::Ellipsoid& wgs84 = GeographicLib::Ellipsoid::WGS84();
    const double latc = 0.5 * (south + north);
    const double m = wgs84.MeridionalCurvatureRadius(latc);
    const double n = wgs84.TransverseCurvatureRadius(latc);
    out.geographic = true;
    out.lon0 = west;
    out.lat0 = south;
    out.centralMeridian = 0.5 * (west + east);
    out.lonStep = std::abs(gt[1]);
    out.latStep = std::abs(gt[5]);
    out.x0 = out.y0 = 0.0;
    // The source's resolution at its centre: the spacing of the resampled grid (geoGrid).
    out.dx = std::abs(gt[1]) * kPi / 180.0 * n * std::cos(latc * kPi / 180.0);
    out.dy = std::abs(gt[5]) * kPi / 180.0 * m;
  }
  else
  {
    out.x0 = west * linear;
    out.y0 = south * linear;
    out.dx = std::abs(gt[1]) * linear;
    out.dy = std::abs(gt[5]) * linear;
  }
  // Huge origins or pixel sizes (or latitudes beyond the poles) overflow or flip the metres.
  if (!(std::isfinite(out.x0) && std::isfinite(out.y0) && std::isfinite(out.dx) &&
        std::isfinite(out.dy) && out.dx > 0.0 && out.dy > 0.0))
  {
    return "has a georeference out of range (origin or pixel size in metres not finite/positive)";
  }
  return std::string();
}

std::string gdalRead(const Input& in, double fileSize, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>* progress)
{
  registerGdal();
  GdalErrors errors;
  // Declared before the dataset, so that it is unlinked after the dataset is closed.
  const std::unique_ptr<VsiMemFile> mem(in.inMemory ? new VsiMemFile(in) : nullptr);
  const std::string& path = mem ? mem->path() : in.name;
  GdalDataset ds;
  ds.h = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
    mem ? oneFileDrivers() : nullptr, nullptr, nullptr);
  if (!ds.h)
  {
    const std::string& name = in.name;
    if (name.size() > 4 && (name.compare(name.size() - 4, 4, ".hgt") == 0 ||
                             name.compare(name.size() - 4, 4, ".HGT") == 0))
    {
      // GDAL recognises SRTM tiles by size alone: say which sizes would have worked.
      return "is not a raster GDAL can read: SRTM .hgt tiles are identified by size, e.g. "
             "1201 x 1201 (2884802 bytes) or 3601 x 3601 (25934402 bytes) int16 samples; this "
             "one has " +
        std::to_string(static_cast<long long>(fileSize)) + " bytes" + errors.suffix();
    }
    return "is not a raster GDAL can read" + errors.suffix();
  }
  double unitToMetre = 1.0;
  std::string problem = gdalHeader(ds.h, fileSize, opt, out, unitToMetre);
  if (!problem.empty() || !progress)
  {
    return problem.empty() ? problem : problem + errors.suffix();
  }
  GDALRasterBandH band = GDALGetRasterBand(ds.h, 1);
  // Without a geotransform GDAL reports (0, 1, 0, 0, 0, 1), but row 0 is still the top
  // (north) row, as in any image: flip rows then too.
  double gt[6] = { 0, 1, 0, 0, 0, -1 };
  const bool hasGt = GDALGetGeoTransform(ds.h, gt) == CE_None;
  const bool flipRows = !hasGt || gt[5] < 0.0, flipCols = hasGt && gt[1] < 0.0;
  int hasNodata = 0, hasScale = 0, hasOffset = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &hasNodata);
  const float nodataF = static_cast<float>(nodata);
  const double bandScale = GDALGetRasterScale(band, &hasScale);
  const double bandOffset = GDALGetRasterOffset(band, &hasOffset);
  const double scale = (hasScale ? bandScale : 1.0) * unitToMetre * opt.heightScale;
  const double offset = (hasOffset ? bandOffset : 0.0) * unitToMetre * opt.heightScale + opt.heightOffset;

  const int nx = out.nx, ny = out.ny;
  out.z.assign(static_cast<std::size_t>(nx) * ny);
  // Chunks of about 4 M samples. GDAL's cache is flushed once a chunk has consumed whole
  // rows of the file's blocks (a block flushed before it is used up would be decoded
  // again): chunks are whole block rows where blocks are shorter than a chunk.
  int blockX = 0, blockY = 0;
  GDALGetBlockSize(band, &blockX, &blockY);
  blockY = std::max(1, std::min(blockY, ny));
  int chunk = std::max(1, std::min(ny, (1 << 22) / nx));
  if (blockY <= chunk)
  {
    chunk = chunk / blockY * blockY;
  }
  std::vector<float> buf(static_cast<std::size_t>(chunk) * nx);
  for (int r0 = 0; r0 < ny; r0 += chunk)
  {
    const int rows = std::min(chunk, ny - r0);
    if (GDALRasterIO(band, GF_Read, 0, r0, nx, rows, buf.data(), nx, rows, GDT_Float32, 0, 0) !=
      CE_None)
    {
      return "could not be read at rows " + std::to_string(r0) + ".." +
        std::to_string(r0 + rows - 1) + ": truncated or corrupt" + errors.suffix();
    }
    for (int r = 0; r < rows; ++r)
    {
      const int j = flipRows ? ny - 1 - (r0 + r) : r0 + r;
      const float* src = buf.data() + static_cast<std::size_t>(r) * nx;
      float* dst = out.z.data() + static_cast<std::size_t>(j) * nx;
      for (int c = 0; c < nx; ++c)
      {
        const float v = src[c];
        const bool missing = !std::isfinite(v) || (hasNodata && v == nodataF);
        dst[flipCols ? nx - 1 - c : c] = missing ? kNaN : toHeight(scale * v + offset);
      }
    }
    // Drop the blocks GDAL cached for this chunk once they are used up: they are in out.z
    // now, and the cache (5 % of the machine's memory by default) would otherwise add up
    // to a second copy of a large DEM at the read's peak.
    if ((r0 + rows) % blockY == 0 || r0 + rows == ny)
    {
      GDALFlushRasterCache(band);
    }
    (*progress)(static_cast<double>(r0 + rows) / ny);
  }
  return std::string();
}

// One image row of grey samples to heights.
template <class T>
void greyRow(const T* src, int nx, double scale, double offset, float* dst)
{
  for (int c = 0; c < nx; ++c)
  {
    dst[c] = toHeight(scale * static_cast<double>(src[c]) + offset);
  }
}

// Image rows [first, first + rows) (row 0 at the top: north), `rows` rows of nx samples
// of type T in buf, to heights z (nx x ny, row j northwards: image row r is row ny - 1 - r).
template <class T>
void convertGrey(const unsigned char* buf, int nx, int first, int rows, int ny, double scale,
  double offset, float* z)
{
  const T* src = reinterpret_cast<const T*>(buf);
  for (int r = 0; r < rows; ++r)
  {
    greyRow(src + static_cast<std::size_t>(r) * nx, nx, scale, offset,
      z + static_cast<std::size_t>(ny - 1 - (first + r)) * nx);
  }
}

// Half floats: converted to float (exactly) by OpenImageIO, a row at a time.
void convertGreyHalf(const unsigned char* buf, int nx, int first, int rows, int ny,
  double scale, double offset, float* z)
{
  std::vector<float> row(static_cast<std::size_t>(nx));
  for (int r = 0; r < rows; ++r)
  {
    OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, buf + static_cast<std::size_t>(r) * nx * 2,
      OIIO::TypeDesc::FLOAT, row.data(), nx);
    greyRow(row.data(), nx, scale, offset, z + static_cast<std::size_t>(ny - 1 - (first + r)) * nx);
  }
}

// Terrain-RGB (Mapbox: height = (R * 65536 + G * 256 + B) / 10 - 10000 m), the same rows.
void convertTerrainRGB(const unsigned char* buf, int nx, int first, int rows, int ny,
  double scale, double offset, float* z)
{
  for (int r = 0; r < rows; ++r)
  {
    const unsigned char* p = buf + static_cast<std::size_t>(r) * nx * 3;
    float* dst = z + static_cast<std::size_t>(ny - 1 - (first + r)) * nx;
    for (int c = 0; c < nx; ++c, p += 3)
    {
      const double h = (p[0] * 65536.0 + p[1] * 256.0 + p[2]) / 10.0 - 10000.0;
      dst[c] = toHeight(scale * h + offset);
    }
  }
}

// The converter of grey samples of `type`, or nullptr for a type heights cannot have.
using GreyConverter = void (*)(const unsigned char*, int, int, int, int, double, double, float*);
GreyConverter greyConverter(OIIO::TypeDesc::BASETYPE type)
{
  using OIIO::TypeDesc;
  switch (type)
  {
    case TypeDesc::UINT8: return convertGrey<uint8_t>;
    case TypeDesc::INT8: return convertGrey<int8_t>;
    case TypeDesc::UINT16: return convertGrey<uint16_t>;
    case TypeDesc::INT16: return convertGrey<int16_t>;
    case TypeDesc::UINT32: return convertGrey<uint32_t>;
    case TypeDesc::INT32: return convertGrey<int32_t>;
    case TypeDesc::HALF: return convertGreyHalf;
    case TypeDesc::FLOAT: return convertGrey<float>;
    case TypeDesc::DOUBLE: return convertGrey<double>;
    default: return nullptr;
  }
}

std::string oiioRead(const Input& file, double fileSize, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>* progress)
{
  using OIIO::TypeDesc;
  // In memory: OpenImageIO picks the format from the name, and reads through the proxy,
  // declared before the image, which must not outlive it.
  OIIO::Filesystem::IOMemReader mem(file.data, file.inMemory ? file.size : 0);
  auto in = OIIO::ImageInput::open(file.name, nullptr, file.inMemory ? &mem : nullptr);
  if (!in)
  {
    return "is not an image OpenImageIO can read (" + OIIO::geterror() + ")";
  }
  const OIIO::ImageSpec spec = in->spec();
  out.format = in->format_name();
  out.nx = out.ny = 0;
  if (spec.depth > 1)
  {
    return "is a volume image, not a heightmap";
  }
  std::string problem = checkSize(spec.width, spec.height, fileSize, 0.0);
  if (!problem.empty())
  {
    return problem;
  }
  const bool rgb = spec.nchannels >= 3;
  if (rgb && !opt.terrainRGB)
  {
    return "has " + std::to_string(spec.nchannels) +
      " channels (RGB): turn TerrainRGB on if it is a terrain-RGB tile, or convert it to greyscale";
  }
  if (!rgb && opt.terrainRGB)
  {
    return "is greyscale but TerrainRGB is on: terrain-RGB needs an RGB(A) image";
  }
  if (rgb && spec.format != TypeDesc::UINT8)
  {
    return std::string("is terrain-RGB with ") + spec.format.c_str() + " channels; 8-bit expected";
  }
  out.nx = spec.width;
  out.ny = spec.height;
  out.dx = out.dy = opt.spacing;
  out.x0 = out.y0 = 0.0;
  out.heightUnit = rgb ? "m" : "stored unit";
  if (!progress)
  {
    return std::string();
  }
  const int nx = out.nx, ny = out.ny;
  const double scale = opt.heightScale, offset = opt.heightOffset;
  const TypeDesc f = spec.format;
  const bool isFloat = f == TypeDesc::HALF || f == TypeDesc::FLOAT || f == TypeDesc::DOUBLE;
  // Samples are read in the file's own type (TypeDesc::UNKNOWN): integers must not be
  // converted (OpenImageIO would normalise them to [0, 1]), and given any explicit type,
  // even the file's own, OpenImageIO 2.4 converts through a temporary buffer of about 64 MB
  // per call, whatever the image's size. Only channels of different types (possible in
  // EXR) are converted by OpenImageIO: to float, or to the integer type f.
  const bool mixed = !spec.channelformats.empty();
  const TypeDesc readAs = mixed && isFloat ? TypeDesc(TypeDesc::FLOAT) : f;
  const GreyConverter grey = rgb ? nullptr : greyConverter(TypeDesc::BASETYPE(readAs.basetype));
  if (!rgb && !grey)
  {
    return std::string("has an unsupported sample type (") + f.c_str() + ")";
  }
  out.z.assign(static_cast<std::size_t>(nx) * ny);
  // Scanline images are decoded in chunks of about 4 M samples, so that the decoded image
  // is never held whole beside the heights (a 16-bit PNG held it at 2 bytes a sample more);
  // tiled ones (some TIFF and EXR files) whole, as OpenImageIO reads tiles.
  const int channels = rgb ? 3 : 1;
  const bool chunked = spec.tile_width == 0;
  const int chunk = chunked ? std::max(1, std::min(ny, (1 << 22) / nx)) : ny;
  std::vector<unsigned char> buf(static_cast<std::size_t>(chunk) * nx * channels * readAs.size());
  const TypeDesc format = mixed ? readAs : TypeDesc(TypeDesc::UNKNOWN);
  for (int r0 = 0; r0 < ny; r0 += chunk)
  {
    const int rows = std::min(chunk, ny - r0);
    const bool read = chunked
      ? in->read_scanlines(0, 0, spec.y + r0, spec.y + r0 + rows, spec.z, 0, channels, format, buf.data())
      : in->read_image(0, 0, 0, channels, format, buf.data());
    if (!read)
    {
      return "could not be decoded: truncated or corrupt (" + in->geterror() + ")";
    }
    (rgb ? convertTerrainRGB : grey)(buf.data(), nx, r0, rows, ny, scale, offset, out.z.data());
    (*progress)(static_cast<double>(r0 + rows) / ny);
  }
  return std::string();
}

// The size of a file on disk in bytes, or a sentence saying why it cannot be read.
std::string fileSize(const std::string& path, double& size)
{
  struct stat st;
  if (stat(path.c_str(), &st) != 0)
  {
    return "does not exist or cannot be accessed";
  }
  if (!S_ISREG(st.st_mode))
  {
    return "is not a regular file";
  }
  size = static_cast<double>(st.st_size);
  return std::string();
}

std::string readAny(const Input& in, const TerrainReadOptions& opt, TerrainRaster& out,
  const std::function<void(double)>* progress)
{
  out = TerrainRaster();
  if (in.name.empty())
  {
    return "no file name was given";
  }
  double size = static_cast<double>(in.size);
  if (in.inMemory && !in.data && in.size > 0)
  {
    return "was given as a null pointer with " + std::to_string(in.size) + " bytes";
  }
  if (!in.inMemory)
  {
    const std::string problem = fileSize(in.name, size);
    if (!problem.empty())
    {
      return problem;
    }
  }
  if (size == 0.0)
  {
    return "is empty";
  }
  try
  {
    return hasImageExtension(in.name) ? oiioRead(in, size, opt, out, progress)
                                      : gdalRead(in, size, opt, out, progress);
  }
  catch (const std::bad_alloc&)
  {
    out.z.clear();
    return "needs more memory than is available";
  }
}

// A read, then the geographic lattice resampled to the local grid, then voids filled when
// asked (header: size only).
std::string readAndGrid(const Input& in, const TerrainReadOptions& opt, TerrainRaster& out,
  const std::function<void(double)>* progress)
{
  if (opt.fillNodata)
  {
    const std::string problem = checkFillOptions(opt.fillSearchDistance, opt.fillSmoothingIterations);
    if (!problem.empty())
    {
      return "cannot be read with " + problem;
    }
  }
  // Filling: the read reports progress up to 0.7, the fill the rest.
  const bool fill = opt.fillNodata && progress;
  const std::function<void(double)> readPart = [progress](double f) { (*progress)(0.7 * f); };
  const std::function<void(double)> fillPart = [progress](double f) { (*progress)(0.7 + 0.3 * f); };
  std::string problem = readAny(in, opt, out, fill ? &readPart : progress);
  try
  {
    std::vector<unsigned char> inside; // geographic: the source's footprint, when filling
    if (problem.empty() && out.geographic)
    {
      problem = geoGrid(out, progress != nullptr, fill ? &inside : nullptr);
    }
    if (problem.empty() && fill)
    {
      problem = fillNodata(out.z, out.nx, out.ny, opt.fillSearchDistance,
        opt.fillSmoothingIterations, out.geographic ? &inside : nullptr, out.filled, fillPart);
    }
  }
  catch (const std::bad_alloc&)
  {
    out.z.clear();
    out.filled = std::vector<unsigned char>();
    problem = "needs more memory than is available";
  }
  return problem;
}

} // namespace

std::string readTerrainHeader(
  const std::string& path, const TerrainReadOptions& opt, TerrainRaster& out)
{
  return readAndGrid(Input{ path }, opt, out, nullptr);
}

std::string readTerrain(const std::string& path, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>& progress)
{
  return readAndGrid(Input{ path }, opt, out, &progress);
}

std::string readTerrainHeader(
  const TerrainBytes& bytes, const TerrainReadOptions& opt, TerrainRaster& out)
{
  return readAndGrid(Input{ bytes.name, true, bytes.data, bytes.size }, opt, out, nullptr);
}

std::string readTerrain(const TerrainBytes& bytes, const TerrainReadOptions& opt,
  TerrainRaster& out, const std::function<void(double)>& progress)
{
  return readAndGrid(Input{ bytes.name, true, bytes.data, bytes.size }, opt, out, &progress);
}

} // namespace gmm
