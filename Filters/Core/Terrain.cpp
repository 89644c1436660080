#include "Terrain.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <limits>
#include <vector>

namespace gmm
{

std::string buildTerrain(Heightfield hf, int maxBlockQuads, int threads,
  std::shared_ptr<const Terrain>& out, const ProgressFn& progress,
  const TableCacheOptions& cache, TableCacheReport* report)
{
  TableCacheReport unused;
  TableCacheReport& r = report ? *report : unused;
  r = TableCacheReport();
  out.reset();
  std::string err = validateHeightfield(hf, threads);
  if (err.empty())
  {
    err = validateBlockSize(maxBlockQuads);
  }
  if (!err.empty())
  {
    return err;
  }
  infinitiesToNodata(hf, threads);
  auto t = std::make_shared<Terrain>();
  t->hf = std::move(hf);
  t->maxBlockQuads = maxBlockQuads;
  t->qt = buildQuadtree(t->hf, maxBlockQuads, threads);
  r.used = !cache.directory.empty() && t->hf.sampleCount() >= cache.minSamples;
  TableCacheKey key;
  if (r.used)
  {
    const auto start = std::chrono::steady_clock::now();
    key.heightsHash = hashHeights(t->hf, threads);
    key.nx = t->hf.nx;
    key.ny = t->hf.ny;
    key.maxBlockQuads = maxBlockQuads;
    r.hashSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.path = tableCachePath(cache.directory, key);
    const std::string why = readTableCache(r.path, key, t->qt, t->table);
    r.hit = why.empty();
    if (r.hit)
    {
      // Refresh its time: trimming removes the least recently used tables first.
      std::error_code ec;
      std::filesystem::last_write_time(r.path, std::filesystem::file_time_type::clock::now(), ec);
    }
    else if (why != "no file")
    {
      r.problem = why; // corrupt, stale or unreadable: rebuilt below, and replaced
    }
  }
  if (!r.hit)
  {
    t->table = buildErrorTable(t->hf, t->qt, threads, progress);
    if (r.used)
    {
      const std::string why = writeTableCache(r.path, key, t->qt, t->table);
      r.written = why.empty();
      if (!why.empty())
      {
        r.problem += (r.problem.empty() ? "" : "; ") + why;
      }
      else
      {
        trimTableCache(cache.directory, cache.maxBytes);
      }
    }
  }
  else if (progress)
  {
    progress(1.0);
  }
  out = std::move(t);
  return std::string();
}

bool validSampleBounds(const Terrain& t, double xy[4])
{
  const Heightfield& hf = t.hf;
  std::vector<uint8_t> colValid(hf.nx, 0), rowValid(hf.ny, 0);
  bool any = false;
  for (int b = 0; b < t.qt.blockCount(); ++b)
  {
    const int c = b % t.qt.blockCols, r = b / t.qt.blockCols;
    const int i0 = t.qt.colStart[c], i1 = t.qt.colStart[c + 1];
    const int j0 = t.qt.rowStart[r], j1 = t.qt.rowStart[r + 1];
    if (!t.qt.blockHasNodata[b])
    {
      std::fill(colValid.begin() + i0, colValid.begin() + i1 + 1, 1);
      std::fill(rowValid.begin() + j0, rowValid.begin() + j1 + 1, 1);
      any = true;
      continue;
    }
    for (int j = j0; j <= j1; ++j)
    {
      for (int i = i0; i <= i1; ++i)
      {
        if (!std::isnan(hf.height(i, j)))
        {
          colValid[i] = rowValid[j] = 1;
          any = true;
        }
      }
    }
  }
  xy[0] = xy[2] = std::numeric_limits<double>::max();
  xy[1] = xy[3] = -std::numeric_limits<double>::max();
  for (int i = 0; i < hf.nx; ++i)
  {
    if (colValid[i])
    {
      xy[0] = std::min(xy[0], hf.worldX(i));
      xy[1] = std::max(xy[1], hf.worldX(i));
    }
  }
  for (int j = 0; j < hf.ny; ++j)
  {
    if (rowValid[j])
    {
      xy[2] = std::min(xy[2], hf.worldY(j));
      xy[3] = std::max(xy[3], hf.worldY(j));
    }
  }
  return any;
}
} // namespace gmm
