// The engine fuzzer's per-frame invariants (FuzzEngineChecks.h), against
// Testing/Core/CoreTestUtil.h's checks, which are written independently of the engine.
#include "FuzzEngineChecks.h"

#include "CoreTestUtil.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace gmmfuzz
{

void violation(const std::string& what, const gmm::Heightfield& hf, int maxQ)
{
  std::fprintf(stderr, "geomipmap engine invariant violated (%d x %d, dx %g, dy %g, block %d): %s\n",
    hf.nx, hf.ny, hf.dx, hf.dy, maxQ, what.c_str());
  std::abort();
}

void checkFrame(const gmm::Engine& e, bool hasNodata, int maxQ, bool compareFresh)
{
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  const std::vector<uint32_t>& idx = e.indices();
  if (e.stats().triangles * 3 != idx.size())
    violation("stats().triangles does not match the index count", hf, maxQ);
  const std::size_t n = hf.z.size();
  for (uint32_t k : idx)
  {
    if (k >= n)
      violation("index " + std::to_string(k) + " out of range", hf, maxQ);
    if (!std::isfinite(hf.z[k]))
      violation("triangle touches nodata sample " + std::to_string(k), hf, maxQ);
  }
  gmmtest::MeshCheckOptions opt;
  opt.drawn.assign(qt.blockCount(), true);
  for (int b = 0; b < qt.blockCount(); ++b)
    if (!gmm::drawnLevel(e.levels()[b]) || (hasNodata && qt.blockHasNodata[b]))
      opt.drawn[b] = false;
  opt.allowNodataHoles = hasNodata;
  opt.checkArea = !hasNodata; // without nodata the drawn blocks are covered exactly
  const gmmtest::MeshCheckResult r = gmmtest::checkMesh(hf, qt.colStart, qt.rowStart, idx, opt);
  if (!r.error.empty())
    violation(r.error, hf, maxQ);
  if (compareFresh)
  {
    // the per-block cache must give the same triangle set as a fresh tessellation
    std::vector<uint32_t> fresh;
    gmm::tessellate(hf, qt, e.levels(), fresh, e.mergedNodeList(), &e.mergedNodeDepths());
    auto canon = [](const std::vector<uint32_t>& v) {
      std::vector<std::array<uint32_t, 3>> t;
      for (std::size_t i = 0; i + 2 < v.size(); i += 3)
      {
        std::array<uint32_t, 3> a{ v[i], v[i + 1], v[i + 2] };
        std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
        t.push_back(a);
      }
      std::sort(t.begin(), t.end());
      return t;
    };
    if (canon(fresh) != canon(idx))
      violation("cached triangles differ from a fresh tessellation", hf, maxQ);
  }
}

} // namespace gmmfuzz
