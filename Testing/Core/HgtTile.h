// An SRTM .hgt tile as a heightfield for the core tests and tools (no GDAL): raw big-endian
// int16, 1201^2 (3 arc-seconds) or 3601^2 (1 arc-second), -32768 nodata, rows north to south.
// Its samples go on a metric grid of the tile's spacing (90 or 30 m): the reader's geographic
// conversion changes the spacing a little, not what a flight over it shows.
#pragma once

#include "Heightfield.h"

#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace gmmtest
{

// "" on success, else why the file is not such a tile.
inline std::string readHgtTile(const std::string& path, gmm::Heightfield& hf)
{
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f)
  {
    return path + ": cannot open";
  }
  std::vector<unsigned char> bytes;
  unsigned char buf[1 << 16];
  for (std::size_t got; (got = std::fread(buf, 1, sizeof buf, f)) > 0;)
  {
    bytes.insert(bytes.end(), buf, buf + got);
  }
  std::fclose(f);
  const int n = bytes.size() == 2u * 1201 * 1201 ? 1201 : bytes.size() == 2u * 3601 * 3601 ? 3601 : 0;
  if (n == 0)
  {
    return path + ": " + std::to_string(bytes.size()) + " bytes is not a 1201^2 or 3601^2 tile";
  }
  hf = gmm::Heightfield();
  hf.nx = hf.ny = n;
  hf.dx = hf.dy = n == 1201 ? 90.0 : 30.0;
  hf.z.resize(static_cast<std::size_t>(n) * n);
  for (int row = 0; row < n; ++row) // rows run north to south; j runs south to north
  {
    for (int i = 0; i < n; ++i)
    {
      const std::size_t at = 2 * (static_cast<std::size_t>(row) * n + i);
      const int16_t v = static_cast<int16_t>((bytes[at] << 8) | bytes[at + 1]);
      hf.z[hf.index(i, n - 1 - row)] = v == -32768 ? std::numeric_limits<float>::quiet_NaN() : v;
    }
  }
  return "";
}

} // namespace gmmtest
