// TableCache: the error table of a DEM saved to a file and read back on the next open, so
// that the table (the one pass over every sample that a terrain needs before its first
// frame) is built once per DEM and block size, not at every open.
//
// A cache file is found by its key: a content hash of the heights (their bits, nodata
// included, and the grid size) and the block size; its name is derived from the key, so a
// changed DEM looks for another file. The file is trusted only after every check passes:
// magic, format version, byte order, the full key stored inside, sizes and band layout
// that match the quadtree the table is for, a checksum over header and data, and values that a table can
// hold (>= 0 or +inf, never NaN). Anything else is reported and the caller rebuilds; a
// rebuilt table replaces the file. Files are written to a temporary name and renamed, so
// a reader never sees half a file, and concurrent writers of one key do no harm.
//
// Format (native byte order, checked): "GMMTABLE", u32 version, u32 byte-order mark,
// u64 heights hash, i32 nx, ny, block size, levels, pairs, blocks, u32 nodes, u64 hash of
// the band starts, f32 ownError[blocks * levels], f32 ownErrorExact[...], f32 stripError[blocks * 4 * pairs],
// f32 mergedError[nodes], u64 checksum of everything before it. Version 2 added the
// merged-node errors, version 3 made more of them exact (ErrorTable.h), version 4 follows
// the one-quad diagonals and fan centres of Tessellate.h, version 5 the nodata collars'
// bands (Quadtree.h) and the band hash, version 6 the coarse levels of blocks with nodata
// (HoleCells.h), 7 - 10 their cells (up to the border, fans from a corner, split towards
// the nodata, drawn between opposite sides); an older file is reported as such and rebuilt.
#pragma once

#include "ErrorTable.h"
#include "Heightfield.h"
#include "Quadtree.h"

#include <cstdint>
#include <string>

namespace gmm
{

struct TableCacheKey
{
  uint64_t heightsHash = 0;
  int nx = 0, ny = 0;
  int maxBlockQuads = 0;
};

// Where the cache goes and when it is used. An empty directory turns the cache off.
struct TableCacheOptions
{
  std::string directory;
  // Smaller DEMs are not cached: their tables build in well under 0.1 s (1025^2: 67 ms
  // against 3 ms to read), not worth a file each in the user's cache.
  uint64_t minSamples = kTableCacheMinSamples;
  // After a write, the oldest files are removed until the directory's tables fit.
  uint64_t maxBytes = kTableCacheMaxBytes;

  static constexpr uint64_t kTableCacheMinSamples = 1u << 20;
  static constexpr uint64_t kTableCacheMaxBytes = 2ull << 30; // 2 GiB: ~80 tables of 16385^2
};

// What happened to the cache during one terrain build.
struct TableCacheReport
{
  bool used = false;    // the cache applied (directory set, DEM large enough)
  bool hit = false;     // the table was read from the file
  bool written = false; // a built table was saved
  std::string path;     // the file looked for
  std::string problem;  // why a file present was not used, or why saving failed ("" if none)
  double hashSeconds = 0.0;
};

// Content hash of the heights' bits and the grid size, with up to `threads` workers
// (0 = hardware concurrency); the value does not depend on the thread count.
uint64_t hashHeights(const Heightfield& hf, int threads = 0);

// The file for `key` in `directory`.
std::string tableCachePath(const std::string& directory, const TableCacheKey& key);

// Reads the table for `key` and `qt` from `path`. Returns "" and fills `out`, or why the
// file cannot be used ("no file" when it does not exist); `out` is then left empty.
std::string readTableCache(const std::string& path, const TableCacheKey& key, const Quadtree& qt,
  ErrorTable& out);

// Writes `table`, built over `qt`, for `key` to `path` (creating the directory when
// needed). Returns "" or why it could not (e.g. a read-only location).
std::string writeTableCache(
  const std::string& path, const TableCacheKey& key, const Quadtree& qt, const ErrorTable& table);

// The format version files are written with and read back at (TableCache.cpp). It changes
// whenever the tables' meaning does: what Tessellate draws, how ErrorTable measures it, the
// band layout. TableCache.FormatVersionFollowsTheTables holds the version and a hash of a
// reference table, and fails when one changes without the other.
uint32_t tableCacheFormatVersion();

// Removes the least recently written table files of `directory` until the rest take at
// most `maxBytes`; other files are never touched.
void trimTableCache(const std::string& directory, uint64_t maxBytes);

} // namespace gmm
