// libFuzzer target: the reader's byte front ends (Filters/TerrainIO.cxx: GDAL and OpenImageIO
// open paths, header and size checks, nodata, terrain-RGB decoding), through the in-memory
// gmm::readTerrainHeader / gmm::readTerrain (TerrainBytes): no file is written, GDAL reads the
// bytes from /vsimem/ and tries only the one-file drivers the reader knows, OpenImageIO reads
// them through an IOMemReader. The first input byte picks the file name the bytes stand for
// (which picks GDAL or OpenImageIO and, for .hgt, the SRTM driver) and the options; the rest
// is the file. TerrainIO.cxx is compiled into this target, so our code is instrumented; GDAL
// and OpenImageIO are the system's (not instrumented).
//
// Checked: a read either fails with a message, or returns a raster whose size, spacing and
// height count agree (and the header-only read agrees with the full read). The option byte's
// top bit turns void filling on: then the valid samples must be those of the read without
// filling, bit for bit, and the filled mask must mark exactly the samples it filled.
#include "TerrainIO.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{

[[noreturn]] void violation(const std::string& what, const std::string& path)
{
  std::fprintf(stderr, "geomipmap reader invariant violated (%s): %s\n", path.c_str(), what.c_str());
  std::abort();
}

// Names as users have them: GDAL picks most drivers from content, SRTMHGT needs the tile name,
// OpenImageIO is chosen by the image extension.
const char* const kNames[] = { "dem.tif", "dem.asc", "N42E001.hgt", "terrain.png", "dem.png",
  "dem.pgm", "dem.dem", "dem.bin" };

void checkRaster(const gmm::TerrainRaster& r, bool withHeights, const std::string& path)
{
  if (r.nx < 1 || r.ny < 1)
    violation("success with size " + std::to_string(r.nx) + " x " + std::to_string(r.ny), path);
  if (!(std::isfinite(r.dx) && r.dx > 0 && std::isfinite(r.dy) && r.dy > 0))
    violation("success with non-positive or non-finite spacing", path);
  if (!std::isfinite(r.x0) || !std::isfinite(r.y0))
    violation("success with non-finite origin", path);
  const std::size_t n = static_cast<std::size_t>(r.nx) * static_cast<std::size_t>(r.ny);
  if (withHeights && r.z.size() != n)
    violation("height count " + std::to_string(r.z.size()) + " != nx * ny", path);
  if (withHeights)
    for (float z : r.z)
      if (std::isinf(z))
        violation("infinite height (nodata must be NaN)", path);
}

// A filled read against the same read without filling: every valid sample keeps its bits,
// the mask marks exactly the samples that were NaN and are not any more.
void checkFill(const gmm::TerrainBytes& file, gmm::TerrainReadOptions opt,
  const gmm::TerrainRaster& filled, const std::string& path)
{
  opt.fillNodata = false;
  gmm::TerrainRaster plain;
  if (!gmm::readTerrain(file, opt, plain, [](double) {}).empty())
    violation("the read succeeds with filling but fails without", path);
  if (plain.z.size() != filled.z.size() || filled.filled.size() != filled.z.size())
    violation("filled read: heights or mask of another size", path);
  for (std::size_t k = 0; k < plain.z.size(); ++k)
  {
    const float a = plain.z[k], b = filled.z[k];
    if (!std::isnan(a) && std::memcmp(&a, &b, sizeof a) != 0)
      violation("filling changed a valid sample", path);
    if (filled.filled[k] != (std::isnan(a) && !std::isnan(b) ? 1 : 0))
      violation("the filled mask disagrees with the heights", path);
  }
}

} // namespace

// Bytes that are no image of the format their name says: OpenImageIO would then open them
// with every other format plugin in turn (LibRaw's and OpenJPEG's set up megabytes each
// time, which under ASan costs more than reading a small image). Those are OpenImageIO's
// plugins, not our code, and the extension's own plugin is still fuzzed: only it is tried.
extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  OIIO::attribute("try_all_readers", 0);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size < 2)
    return 0;
  const uint8_t sel = data[0];
  gmm::TerrainBytes file;
  file.data = data + 1;
  file.size = size - 1;
  file.name = kNames[sel % (sizeof(kNames) / sizeof(kNames[0]))];
  const std::string& path = file.name;

  gmm::TerrainReadOptions opt;
  opt.terrainRGB = (sel >> 3) & 1;
  opt.heightScale = ((sel >> 4) & 1) ? -0.5 : 1.0;
  opt.heightOffset = ((sel >> 5) & 1) ? 100.0 : 0.0;
  opt.spacing = ((sel >> 6) & 1) ? 30.0 : 1.0;
  opt.fillNodata = (sel >> 7) & 1;
  opt.fillSearchDistance = 8.0;
  opt.fillSmoothingIterations = 1;

  gmm::TerrainRaster header;
  const std::string headerErr = gmm::readTerrainHeader(file, opt, header);
  if (headerErr.empty())
    checkRaster(header, false, path);
  gmm::TerrainRaster full;
  const std::string err = gmm::readTerrain(file, opt, full, [&](double p) {
    if (!(p >= 0.0 && p <= 1.0))
      violation("progress outside [0, 1]", path);
  });
  if (err.empty())
  {
    checkRaster(full, true, path);
    if (!headerErr.empty())
      violation("header read failed (" + headerErr + ") but the full read succeeded", path);
    if (header.nx != full.nx || header.ny != full.ny)
      violation("header and full read disagree on the size", path);
    if (opt.fillNodata)
      checkFill(file, opt, full, path);
  }
  return 0;
}
