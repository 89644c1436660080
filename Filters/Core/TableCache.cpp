#include "TableCache.h"

#include "CoarsePerimeter.h"
#include "HugePages.h"
#include "Levels.h"
#include "Parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <utility>
#include <vector>

namespace gmm
{

namespace
{
namespace fs = std::filesystem;

constexpr char kMagic[8] = { 'G', 'M', 'M', 'T', 'A', 'B', 'L', 'E' };
// Version 1: the table of the four-side-strip tessellation (ErrorTable.h). Any change of
// the table's meaning or layout changes it, and older files are then rebuilt.
// 2: merged-node errors; 3: merged nodes up to kExactMergedQuads wide have exact errors
// (a version 2 file holds bounds there, which would make a small block size draw a finer
// far field when its table comes from an old cache than when it is built); 4: one-quad
// blocks split along oneQuadAntiDiagonal's diagonal and merged fans centred on
// mergedCentre (Tessellate.h), which changes those errors; 5: nodata collars have their
// own bands (nodataCollar, Quadtree.h), which moves the blocks of a DEM with nodata along
// a border, and the header holds a hash of the band starts (hashBands); 6: blocks with
// nodata have finite errors at coarse levels (HoleCells.h); 7: blocks with nodata are
// cells over their whole extent and every side beside nodata is at full resolution
// (Quadtree::sideAtFullResolution), which changes their errors and their neighbours'; 8:
// fanned cells from a corner between two coarse sides (HoleCells.h, coarseCorner); 9: cells
// holding nodata split towards it instead of drawn at full resolution (HoleCells.h); 10:
// cells with vertices on opposite sides drawn between them instead of from their centre;
// 11: a block with nodata draws side strips where its level's border row holds none, and
// such a side follows the edge levels, as one-quad blocks' sides beside nodata do
// (Quadtree::sideAtFullResolutionAt), which changes their errors and their neighbours';
// 12: triangle counts leave out what nodata drops, which changes which levels of a block
// with nodata draw fewer triangles than a finer one, so are allowed; 13: ring blocks split
// their cells by the union-jack rule (cellAntiDiagonal, Levels.h), which changes their
// errors at every level above 0, and bands start on even samples (splitBands); 14: bands
// of the block width from the DEM's first sample (splitBands) instead of halves; 15: a
// strip toward a coarser block's edge draws the block's own cells, its edge samples glided
// onto the edge's polyline (Tessellate.h, BlockConfig::sampleLevel); 16: quadtree nodes
// split their band ranges at a power of two (splitBand), which changes the merged nodes;
// 17: the fan morph's three per-node errors (FanMorph.h) after the merged nodes'; 18: the
// coarse perimeters' errors and changes (CoarsePerimeter.h) after those.
constexpr uint32_t kFormatVersion = 18;
constexpr uint32_t kByteOrderMark = 0x01020304u;
constexpr const char* kExtension = ".gmmtable";

// A 64-bit multiply-rotate hash over 8-byte words in four independent lanes (so that the
// multiplications overlap): fast enough that hashing a 1 GiB DEM costs a fraction of a
// second, and a changed bit anywhere changes the result. Not cryptographic: it detects
// changed data and corruption, not a forged file.
constexpr uint64_t kP1 = 0x9E3779B185EBCA87ull, kP2 = 0xC2B2AE3D27D4EB4Full, kP3 = 0x165667B19E3779F9ull;

uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
uint64_t round64(uint64_t lane, uint64_t word) { return rotl(lane + word * kP2, 31) * kP1; }
uint64_t avalanche(uint64_t h)
{
  h ^= h >> 33;
  h *= kP2;
  h ^= h >> 29;
  h *= kP3;
  h ^= h >> 32;
  return h;
}

uint64_t hashBytes(const unsigned char* p, std::size_t n, uint64_t seed)
{
  uint64_t lane[4] = { seed + kP1 + kP2, seed + kP2, seed, seed - kP1 };
  std::size_t k = 0;
  for (; k + 32 <= n; k += 32)
  {
    for (int l = 0; l < 4; ++l)
    {
      uint64_t w;
      std::memcpy(&w, p + k + 8 * l, 8);
      lane[l] = round64(lane[l], w);
    }
  }
  uint64_t h = rotl(lane[0], 1) + rotl(lane[1], 7) + rotl(lane[2], 12) + rotl(lane[3], 18);
  h += static_cast<uint64_t>(n);
  for (; k < n; ++k)
  {
    h = rotl(h ^ (p[k] * kP3), 11) * kP1;
  }
  return avalanche(h);
}

// Combines chunk hashes in order.
uint64_t combine(uint64_t h, uint64_t chunk) { return avalanche(rotl(h ^ round64(0, chunk), 27) * kP1 + kP3); }

#pragma pack(push, 1)
struct FileHeader
{
  char magic[8];
  uint32_t version;
  uint32_t byteOrder;
  uint64_t heightsHash;
  int32_t nx, ny, maxBlockQuads, levels, pairs, blocks;
  uint32_t nodes;     // quadtree nodes (mergedError entries)
  uint64_t bandsHash; // the quadtree's band starts (hashBands)
};
#pragma pack(pop)

// The arrays a file stores, in order: per block and level (two), per strip, per node
// (four), then per node and perimeter depth (two). The one list the writer, the reader and
// the checksum follow.
template <typename Table>
std::array<decltype(&std::declval<Table&>().ownError), 9> storedArrays(Table& t)
{
  return { &t.ownError, &t.ownErrorExact, &t.stripError, &t.mergedError, &t.fanResidual, &t.fanMovedError,
    &t.fanChildrenError, &t.perimeterError, &t.perimeterPop };
}

// The checksum a file stores after its data: the header, then the arrays in order.
uint64_t checksum(const FileHeader& h, const ErrorTable& t)
{
  uint64_t sum = hashBytes(reinterpret_cast<const unsigned char*>(&h), sizeof h, 1);
  for (const std::vector<float>* v : storedArrays(t))
  {
    sum = combine(sum, hashBytes(reinterpret_cast<const unsigned char*>(v->data()), v->size() * sizeof(float), 2));
  }
  return sum;
}

// A hash of the quadtree's column and row band starts. The bands follow from the heights
// and the block size by a rule (Quadtree.h), but a table is only valid for the very blocks
// it was built over, so the file says which: a rule changed without a format change, or
// two builds with different rules sharing a cache, then rebuild instead of trusting
// errors of other blocks (the sizes alone can match: a collar one quad wider moves no count).
uint64_t hashBands(const Quadtree& qt)
{
  const uint64_t cols = hashBytes(reinterpret_cast<const unsigned char*>(qt.colStart.data()),
    qt.colStart.size() * sizeof(int), 3);
  const uint64_t rows = hashBytes(reinterpret_cast<const unsigned char*>(qt.rowStart.data()),
    qt.rowStart.size() * sizeof(int), 4);
  return combine(cols, rows);
}

// The table's level count for a quadtree, as buildErrorTable derives it.
int tableLevels(const Quadtree& qt)
{
  int maxTop = 0;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    maxTop = std::max(maxTop, topLevel(qt.blockWidth(b), qt.blockHeight(b)));
  }
  return maxTop + 1;
}

bool tableValue(float v) { return v >= 0.0f; } // false for NaN and negatives; +inf passes

std::string hex(uint64_t v)
{
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}
} // namespace

uint64_t hashHeights(const Heightfield& hf, int threads)
{
  const float* z = hf.heights();
  const std::size_t count = hf.sampleCount();
  constexpr std::size_t kChunk = std::size_t(1) << 20; // samples per chunk (4 MiB)
  const std::size_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<uint64_t> chunkHash(chunks, 0);
  parallelChunks(count, kChunk, threads, [&](std::size_t begin, std::size_t end) {
    const std::size_t c = begin / kChunk;
    chunkHash[c] = hashBytes(reinterpret_cast<const unsigned char*>(z + begin), (end - begin) * sizeof(float), c);
  });
  uint64_t h = combine(static_cast<uint64_t>(hf.nx), static_cast<uint64_t>(hf.ny));
  for (uint64_t c : chunkHash)
  {
    h = combine(h, c);
  }
  return h;
}

std::string tableCachePath(const std::string& directory, const TableCacheKey& key)
{
  const std::string name = hex(key.heightsHash) + "-" + std::to_string(key.nx) + "x" +
    std::to_string(key.ny) + "-b" + std::to_string(key.maxBlockQuads) + "-v" +
    std::to_string(kFormatVersion) + kExtension;
  return (fs::path(directory) / name).string();
}

std::string readTableCache(const std::string& path, const TableCacheKey& key, const Quadtree& qt,
  ErrorTable& out)
{
  out = ErrorTable();
  std::error_code ec;
  if (!fs::exists(path, ec))
  {
    return "no file";
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return "cannot open " + path;
  }
  FileHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h))
  {
    return path + ": truncated header";
  }
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
  {
    return path + ": not an error table file";
  }
  if (h.version != kFormatVersion)
  {
    return path + ": format version " + std::to_string(h.version) + ", expected " +
      std::to_string(kFormatVersion);
  }
  if (h.byteOrder != kByteOrderMark)
  {
    return path + ": written with another byte order";
  }
  if (h.heightsHash != key.heightsHash || h.nx != key.nx || h.ny != key.ny ||
    h.maxBlockQuads != key.maxBlockQuads)
  {
    return path + ": stale (made for other heights or another block size)";
  }
  const int levels = tableLevels(qt);
  const int pairs = levels * (levels - 1) / 2;
  if (h.blocks != qt.blockCount() || h.levels != levels || h.pairs != pairs ||
    h.nodes != qt.nodes.size())
  {
    return path + ": sizes do not match the quadtree";
  }
  if (h.bandsHash != hashBands(qt))
  {
    return path + ": made for other blocks (another band layout)";
  }
  const std::size_t blocks = static_cast<std::size_t>(h.blocks);
  const std::size_t own = blocks * levels, strips = blocks * 4 * std::max(1, pairs);
  const std::size_t nodes = h.nodes;
  perimeterOffsets(qt, out.perimeterFirst); // derived from the quadtree, not stored
  const std::size_t depths = out.perimeterFirst.back();
  const std::size_t dataBytes = (2 * own + strips + 4 * nodes + 2 * depths) * sizeof(float);
  const uintmax_t expected = sizeof h + dataBytes + sizeof(uint64_t);
  if (fs::file_size(path, ec) != expected || ec)
  {
    return path + ": wrong size (truncated or padded)";
  }
  out.levels = levels;
  out.pairs = pairs;
  const std::array<std::size_t, 9> counts{ own, own, strips, nodes, nodes, nodes, nodes, depths, depths };
  const std::array<std::vector<float>*, 9> arrays = storedArrays(out);
  for (std::size_t k = 0; k < arrays.size(); ++k)
  {
    resizeOnHugePages(*arrays[k], counts[k]);
    in.read(reinterpret_cast<char*>(arrays[k]->data()), counts[k] * sizeof(float));
  }
  uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(&stored), sizeof stored);
  if (!in)
  {
    out = ErrorTable();
    return path + ": read failed";
  }
  if (checksum(h, out) != stored)
  {
    out = ErrorTable();
    return path + ": checksum mismatch (corrupt)";
  }
  for (const std::vector<float>* v : storedArrays(out))
  {
    if (!std::all_of(v->begin(), v->end(), tableValue))
    {
      out = ErrorTable();
      return path + ": holds values no table can hold";
    }
  }
  fillCellTriangles(qt, out); // derived from the quadtree, not stored; only for a table kept
  return std::string();
}

uint32_t tableCacheFormatVersion()
{
  return kFormatVersion;
}

std::string writeTableCache(
  const std::string& path, const TableCacheKey& key, const Quadtree& qt, const ErrorTable& table)
{
  std::error_code ec;
  const fs::path target(path);
  if (target.has_parent_path())
  {
    fs::create_directories(target.parent_path(), ec);
    if (ec)
    {
      return "cannot create " + target.parent_path().string() + ": " + ec.message();
    }
  }
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kFormatVersion;
  h.byteOrder = kByteOrderMark;
  h.heightsHash = key.heightsHash;
  h.nx = key.nx;
  h.ny = key.ny;
  h.maxBlockQuads = key.maxBlockQuads;
  h.levels = table.levels;
  h.pairs = table.pairs;
  h.blocks = table.levels > 0 ? static_cast<int32_t>(table.ownError.size() / table.levels) : 0;
  h.nodes = static_cast<uint32_t>(table.mergedError.size());
  h.bandsHash = hashBands(qt);
  const uint64_t sum = checksum(h, table);
  // A private temporary name in the same directory, then an atomic rename.
  std::random_device rd;
  const std::string tmp = path + ".tmp" + hex((static_cast<uint64_t>(rd()) << 32) ^ rd());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f)
    {
      return "cannot write " + tmp;
    }
    f.write(reinterpret_cast<const char*>(&h), sizeof h);
    for (const std::vector<float>* v : storedArrays(table))
    {
      f.write(reinterpret_cast<const char*>(v->data()), v->size() * sizeof(float));
    }
    f.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    f.close();
    if (!f)
    {
      fs::remove(tmp, ec);
      return "cannot write " + tmp + " (disk full?)";
    }
  }
  fs::rename(tmp, target, ec);
  if (ec)
  {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    return "cannot rename " + tmp + " to " + path + ": " + why;
  }
  return std::string();
}

void trimTableCache(const std::string& directory, uint64_t maxBytes)
{
  struct Entry
  {
    fs::path path;
    fs::file_time_type time;
    uintmax_t bytes;
  };
  std::vector<Entry> files;
  uintmax_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec))
  {
    // Its own error code: a file that another process removes between the listing and
    // these queries is skipped, and does not end the listing (the loop's `ec`).
    std::error_code entry;
    const fs::path& p = it->path();
    if (p.extension() != kExtension || !it->is_regular_file(entry))
    {
      continue;
    }
    // One query at a time: a query that succeeds clears `entry`, so checking only after
    // both would miss the first one's failure.
    const fs::file_time_type time = it->last_write_time(entry);
    if (entry)
    {
      continue;
    }
    const uintmax_t bytes = it->file_size(entry);
    if (entry)
    {
      continue;
    }
    total += bytes;
    files.push_back(Entry{ p, time, bytes });
  }
  std::sort(files.begin(), files.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (std::size_t k = 0; k < files.size() && total > maxBytes; ++k)
  {
    std::error_code removed;
    if (fs::remove(files[k].path, removed))
    {
      total -= files[k].bytes;
    }
  }
}

} // namespace gmm
