#include "Terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gmm
{

std::string buildTerrain(Heightfield hf, int maxBlockQuads, int threads,
  std::shared_ptr<const Terrain>& out, const ProgressFn& progress)
{
  out.reset();
  std::string err = validateHeightfield(hf);
  if (err.empty())
  {
    err = validateBlockSize(maxBlockQuads);
  }
  if (!err.empty())
  {
    return err;
  }
  infinitiesToNodata(hf);
  auto t = std::make_shared<Terrain>();
  t->hf = std::move(hf);
  t->maxBlockQuads = maxBlockQuads;
  t->qt = buildQuadtree(t->hf, maxBlockQuads);
  t->table = buildErrorTable(t->hf, t->qt, threads, progress);
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
