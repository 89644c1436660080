// libFuzzer target: the engine's tessellation on random sizes, spacings, block sizes, nodata
// holes and level assignments / views, frame after frame on one Engine (so the per-block
// triangle cache is exercised too). After every frame the mesh is checked against invariants
// written independently of the engine (Testing/Core/CoreTestUtil.h): indices in range, no
// triangle touching nodata, no zero-area or duplicate triangle, watertight (every interior edge
// shared by two triangles of opposite orientation, no T-junction), counter-clockwise in world
// xy. A violation prints what failed and aborts, which libFuzzer reports as a crash.
#include "Engine.h"
#include "FuzzEngineChecks.h"
#include "Levels.h"
#include "Morph.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace
{

using gmmfuzz::checkFrame;
using gmmfuzz::violation;

// At most one sample per kBytesPerSample input bytes. The work per input (error table,
// frames, checks) grows with the grid, so the grid must grow with the input: before, 3
// bytes could name a 200 x 200 grid (40 000 samples, 0.3 s under ASan + UBSan), and
// libFuzzer's short inputs cost as much as its longest (robustness.md has the figures).
// With 4 bytes a sample, fuzz.sh's -max_len=16384 still reaches every block shape (blocks
// up to 80 quads and level 7: grids up to 64 x 64 or 200 x 20).
constexpr std::size_t kBytesPerSample = 4;

// Heights: smooth ramp plus bytes from the input (so both flat and rough terrain occur), with
// NaN holes: single samples, or whole rectangles. inputSize: the whole input's length.
gmm::Heightfield makeHeightfield(FuzzedDataProvider& in, std::size_t inputSize, bool& hasNodata)
{
  gmm::Heightfield hf;
  // Mostly small grids (fast, many block-shape corner cases), sometimes up to 200 a side,
  // and never more than one sample per kBytesPerSample input bytes (at least 2 x 2).
  const int maxSide = in.ConsumeIntegralInRange<int>(0, 3) == 0 ? 200 : 48;
  const std::size_t samples = std::max<std::size_t>(4, inputSize / kBytesPerSample);
  hf.nx = in.ConsumeIntegralInRange<int>(2, static_cast<int>(std::min<std::size_t>(maxSide, samples / 2)));
  hf.ny = in.ConsumeIntegralInRange<int>(2, static_cast<int>(std::min<std::size_t>(maxSide, samples / hf.nx)));
  const double sx = in.ConsumeIntegralInRange<int>(1, 1000) * 0.25;
  const double sy = in.ConsumeIntegralInRange<int>(1, 1000) * 0.25;
  hf.dx = in.ConsumeBool() ? sx : -sx;
  hf.dy = in.ConsumeBool() ? sy : -sy;
  hf.x0 = in.ConsumeIntegralInRange<int>(-100000, 100000);
  hf.y0 = in.ConsumeIntegralInRange<int>(-100000, 100000);
  const double slope = in.ConsumeIntegralInRange<int>(-50, 50) * 0.1;
  const double rough = in.ConsumeIntegralInRange<int>(0, 100);
  const std::vector<uint8_t> noise = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange<int>(0, 256));
  hf.z.resize(static_cast<std::size_t>(hf.nx) * hf.ny);
  for (std::size_t k = 0; k < hf.z.size(); ++k)
  {
    const double n = noise.empty() ? 0.0 : (noise[k % noise.size()] - 128.0) / 128.0;
    hf.z[k] = static_cast<float>(slope * static_cast<double>(k % hf.nx) + rough * n);
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int holes = in.ConsumeIntegralInRange<int>(0, 12);
  hasNodata = false;
  for (int h = 0; h < holes; ++h)
  {
    const int i0 = in.ConsumeIntegralInRange<int>(0, hf.nx - 1);
    const int j0 = in.ConsumeIntegralInRange<int>(0, hf.ny - 1);
    const int w = in.ConsumeIntegralInRange<int>(1, in.ConsumeBool() ? 1 : 40);
    const int hh = in.ConsumeIntegralInRange<int>(1, in.ConsumeBool() ? 1 : 40);
    for (int j = j0; j < std::min(hf.ny, j0 + hh); ++j)
      for (int i = i0; i < std::min(hf.nx, i0 + w); ++i)
      {
        // infinities are nodata too (Heightfield.h); the engine must treat them alike
        hf.z[hf.index(i, j)] = in.ConsumeIntegralInRange<int>(0, 7) == 0
          ? std::numeric_limits<float>::infinity()
          : nan;
        hasNodata = true;
      }
  }
  return hf;
}

// A valid level per block (or -1 = not drawn), chosen by the input.
std::vector<int8_t> makeLevels(FuzzedDataProvider& in, const gmm::Quadtree& qt)
{
  std::vector<int8_t> lv(qt.blockCount(), -1);
  const int undrawnChance = in.ConsumeIntegralInRange<int>(0, 4);
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    if (in.ConsumeIntegralInRange<int>(0, 7) < undrawnChance)
      continue;
    std::vector<int> valid;
    for (int m = 0; m <= gmm::topLevel(w, h); ++m)
      if (gmm::blockShape(w, h, m) != gmm::BlockShape::Invalid)
        valid.push_back(m);
    lv[b] = static_cast<int8_t>(valid[in.ConsumeIntegralInRange<std::size_t>(0, valid.size() - 1)]);
  }
  return lv;
}

gmm::View makeView(FuzzedDataProvider& in, const gmm::Heightfield& hf)
{
  gmm::View v;
  const double w = hf.worldX(hf.nx - 1) - hf.x0, h = hf.worldY(hf.ny - 1) - hf.y0;
  v.eye = { hf.x0 + w * in.ConsumeIntegralInRange<int>(-50, 150) / 100.0,
    hf.y0 + h * in.ConsumeIntegralInRange<int>(-50, 150) / 100.0,
    in.ConsumeIntegralInRange<int>(-200, 5000) };
  v.forward = { in.ConsumeIntegralInRange<int>(-10, 10), in.ConsumeIntegralInRange<int>(-10, 10),
    in.ConsumeIntegralInRange<int>(-10, 2) };
  if (v.forward == glm::dvec3(0.0))
    v.forward = { 0.0, 1.0, -1.0 };
  v.up = in.ConsumeBool() ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  v.fovYDegrees = in.ConsumeIntegralInRange<int>(5, 120);
  v.parallel = in.ConsumeIntegralInRange<int>(0, 5) == 0;
  v.parallelScale = in.ConsumeIntegralInRange<int>(1, 2000);
  v.nearDistance = 0.1;
  v.farDistance = 1e6;
  v.viewportWidth = in.ConsumeIntegralInRange<int>(1, 2000);
  v.viewportHeight = in.ConsumeIntegralInRange<int>(1, 2000);
  return v;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzedDataProvider in(data, size);
  bool hasNodata = false;
  gmm::Heightfield hf = makeHeightfield(in, size, hasNodata);
  const int maxQ = in.ConsumeIntegralInRange<int>(0, 80);
  gmm::Engine e;
  const std::string err = e.setHeightfield(hf, maxQ, 1);
  if (!err.empty() && maxQ >= 4) // below 4 quads a block size is refused (Quadtree.h)
    violation("valid heightfield rejected: " + err, hf, maxQ);
  if (!err.empty())
    return 0;
  const int frames = in.ConsumeIntegralInRange<int>(1, 6);
  gmm::MorphCache morphCache;
  gmm::MorphFrame morph;
  for (int f = 0; f < frames; ++f)
  {
    switch (in.ConsumeIntegralInRange<int>(0, 2))
    {
      case 0:
      {
        const std::vector<int8_t> lv = makeLevels(in, e.quadtree());
        e.updateWithLevels(lv);
        if (!e.lastError().empty() || e.levels() != lv)
          violation("valid level list refused: " + e.lastError(), hf, maxQ);
        checkFrame(e, hasNodata, maxQ, true);
        break;
      }
      case 1:
      {
        const gmm::View v = makeView(in, e.heightfield());
        const double tau = in.ConsumeIntegralInRange<int>(1, 400) * 0.05;
        // Geomorphing's level path (any range, none included), merged nodes on or off, and
        // now and then a triangle budget (budgeted frames never follow the path).
        e.setMorphRange(in.ConsumeIntegralInRange<int>(0, 4) * 0.75);
        e.setMergedNodes(in.ConsumeIntegralInRange<int>(0, 3) != 0);
        const std::size_t budget = in.ConsumeIntegralInRange<int>(0, 3) == 0
          ? static_cast<std::size_t>(in.ConsumeIntegralInRange<int>(1, 20000))
          : 0;
        e.update(v, tau, budget);
        if (!e.lastError().empty())
        {
          if (!e.indices().empty() || e.stats().triangles != 0)
            violation("refused view still produced triangles: " + e.lastError(), hf, maxQ);
          break;
        }
        checkFrame(e, hasNodata, maxQ, true);
        // Morph factors (with the path and the rise limit across frames): the morphed
        // surface's bound stays within tau in a tau-driven frame.
        gmm::computeMorph(e.heightfield(), e.quadtree(), e.levels(), e.pixelFactors(), tau,
          morphCache, morph, e.morphRamp());
        if (budget == 0 && !(morph.maxBoundPixels <= tau * (1 + 1e-9)))
          violation("morph bound " + std::to_string(morph.maxBoundPixels) + " px over tau", hf, maxQ);
        break;
      }
      default:
        e.updateForError(in.ConsumeIntegralInRange<int>(0, 1000) * 0.5);
        checkFrame(e, hasNodata, maxQ, true);
    }
  }
  return 0;
}
