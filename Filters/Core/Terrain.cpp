#include "Terrain.h"

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

} // namespace gmm
