// libFuzzer target: the engine's tessellation on random sizes, spacings, block sizes, nodata
// holes and level assignments / views, frame after frame on one Engine (so the per-block
// triangle cache is exercised too). After every frame the mesh is checked against invariants
// written independently of the engine (Testing/Core/CoreTestUtil.h): indices in range, no
// triangle touching nodata, no zero-area or duplicate triangle, watertight (every interior edge
// shared by two triangles of opposite orientation, no T-junction), counter-clockwise in world
// xy. A violation prints what failed and aborts, which libFuzzer reports as a crash.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "Tessellate.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace
{

[[noreturn]] void violation(const std::string& what, const gmm::Heightfield& hf, int maxQ)
{
  std::fprintf(stderr, "geomipmap engine invariant violated (%d x %d, dx %g, dy %g, block %d): %s\n",
    hf.nx, hf.ny, hf.dx, hf.dy, maxQ, what.c_str());
  std::abort();
}

// Heights: smooth ramp plus bytes from the input (so both flat and rough terrain occur), with
// NaN holes: single samples, or whole rectangles.
gmm::Heightfield makeHeightfield(FuzzedDataProvider& in, bool& hasNodata)
{
  gmm::Heightfield hf;
  // Mostly small grids (fast, many block-shape corner cases), sometimes up to 200 a side.
  const int maxSide = in.ConsumeIntegralInRange<int>(0, 3) == 0 ? 200 : 48;
  hf.nx = in.ConsumeIntegralInRange<int>(2, maxSide);
  hf.ny = in.ConsumeIntegralInRange<int>(2, maxSide);
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
    if (e.levels()[b] < 0 || (hasNodata && qt.blockHasNodata[b]))
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
    gmm::tessellate(hf, qt, e.levels(), fresh);
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

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzedDataProvider in(data, size);
  bool hasNodata = false;
  gmm::Heightfield hf = makeHeightfield(in, hasNodata);
  const int maxQ = in.ConsumeIntegralInRange<int>(0, 80);
  gmm::Engine e;
  const std::string err = e.setHeightfield(hf, maxQ, 1);
  if (!err.empty() && maxQ >= 4) // below 4 quads a block size is refused (Quadtree.h)
    violation("valid heightfield rejected: " + err, hf, maxQ);
  if (!err.empty())
    return 0;
  const int frames = in.ConsumeIntegralInRange<int>(1, 6);
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
        e.update(v, tau);
        if (!e.lastError().empty())
        {
          if (!e.indices().empty() || e.stats().triangles != 0)
            violation("refused view still produced triangles: " + e.lastError(), hf, maxQ);
          break;
        }
        checkFrame(e, hasNodata, maxQ, true);
        break;
      }
      default:
        e.updateForError(in.ConsumeIntegralInRange<int>(0, 1000) * 0.5);
        checkFrame(e, hasNodata, maxQ, true);
    }
  }
  return 0;
}
