// Terrain: everything the engine derives from a heightfield once, before any frame: the
// heightfield itself, its quadtree and its exact error table. It does not change per frame,
// so one Terrain is shared (read-only) by every consumer of the same DEM: several engines,
// the mapper and the filter, the picker.
//
//   std::shared_ptr<const Terrain> t;
//   std::string err = buildTerrain(hf, 64, 0, t);   // "" on success
//   Engine a, b;  a.setTerrain(t);  b.setTerrain(t); // no second table build
#pragma once

#include "ErrorTable.h"
#include "Heightfield.h"
#include "Quadtree.h"
#include "TableCache.h"

#include <functional>
#include <memory>
#include <string>

namespace gmm
{

struct Terrain
{
  Heightfield hf;
  Quadtree qt;
  ErrorTable table;
  int maxBlockQuads = 0; // the block size it was built with
};

// Progress of a long build: fraction in [0, 1]. Called from the building thread only.
using ProgressFn = std::function<void(double)>;

// Validates `hf` (validateHeightfield) and the block size (validateBlockSize), turns +-Inf
// into nodata (infinitiesToNodata: external heights are shared as they are, or copied first
// when they hold an infinity), builds the quadtree and the error table with up to `threads`
// workers (0 = hardware concurrency). Returns "" and sets `out`, or the reason (out reset).
// A DEM that is all nodata is accepted and draws nothing: a void tile is valid data.
// With a cache directory (TableCache.h) the table is read from its file when one is there
// and passes every check, else built and saved; `report` (may be null) says which, and why
// a file was not used or could not be written. The cache never makes the build fail.
std::string buildTerrain(Heightfield hf, int maxBlockQuads, int threads,
  std::shared_ptr<const Terrain>& out, const ProgressFn& progress = nullptr,
  const TableCacheOptions& cache = TableCacheOptions(), TableCacheReport* report = nullptr);

// x, y bounds (xmin, xmax, ymin, ymax) of the rows and columns of `t` that hold a valid
// (non-NaN) sample; false when none does. Blocks without nodata are taken whole, only
// blocks with nodata are scanned.
bool validSampleBounds(const Terrain& t, double xy[4]);

} // namespace gmm
