// Watertightness of gmm::tessellate over many random sizes, block sizes, flipped axes and
// random valid level assignments (any neighbour difference), with and without undrawn
// blocks. Every invariant is checked in exact integer grid arithmetic (CoreTestUtil.h):
// manifold edges with opposite orientation, boundary edges only on the drawn region's border,
// no T-junction, no zero-area or duplicate triangle, CCW in world, exact area sum.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <iostream>
#include <set>
#include <utility>

using namespace gmmtest;

namespace
{
std::vector<int> validLevels(int w, int h)
{
  std::vector<int> v;
  for (int m = 0; m <= gmm::topLevel(w, h); ++m)
    if (gmm::blockShape(w, h, m) != gmm::BlockShape::Invalid)
      v.push_back(m);
  return v;
}

// mode 0: uniform random valid level; 1: all finest; 2: all coarsest; 3: random walk (small
// neighbour differences); 4: extreme checkerboard (finest/coarsest alternating)
std::vector<int8_t> randomLevels(const gmm::Quadtree& qt, Rng& rng, int mode, double undrawnP)
{
  std::vector<int8_t> lv(qt.blockCount());
  for (int r = 0; r < qt.blockRows; ++r)
    for (int c = 0; c < qt.blockCols; ++c)
    {
      const int w = qt.colStart[c + 1] - qt.colStart[c], h = qt.rowStart[r + 1] - qt.rowStart[r];
      std::vector<int> v = validLevels(w, h);
      int pick = 0;
      switch (mode)
      {
        case 0: pick = randInt(rng, 0, static_cast<int>(v.size()) - 1); break;
        case 1: pick = 0; break;
        case 2: pick = static_cast<int>(v.size()) - 1; break;
        case 3: pick = std::min<int>(static_cast<int>(v.size()) - 1, (c + r) / 2 % 3); break;
        default: pick = ((c + r) % 2) ? static_cast<int>(v.size()) - 1 : 0; break;
      }
      lv[qt.blockIndex(c, r)] = static_cast<int8_t>(v[pick]);
      if (undrawnP > 0 && randReal(rng, 0, 1) < undrawnP)
        lv[qt.blockIndex(c, r)] = -1;
    }
  return lv;
}

int randomSide(Rng& rng)
{
  const double u = randReal(rng, 0, 1);
  if (u < 0.15)
    return 2 + randInt(rng, 0, 1); // 2 or 3 samples: 1- or 2-quad-wide DEMs
  if (u < 0.75)
    return randInt(rng, 2, 40);
  if (u < 0.95)
    return randInt(rng, 2, 130);
  return randInt(rng, 2, 300);
}

// What the assignments of runCase exercised (so that a test can tell that it checked
// something: triangles drawn, coarse blocks next to fine ones).
struct CaseTally
{
  int withTriangles = 0;
  int mixed = 0;
};

// Pairs of side-by-side drawn blocks whose levels differ: (pairs, largest difference).
std::pair<int, int> mixedNeighbours(const gmm::Quadtree& qt, const std::vector<int8_t>& lv)
{
  int pairs = 0, worst = 0;
  for (int r = 0; r < qt.blockRows; ++r)
    for (int c = 0; c < qt.blockCols; ++c)
    {
      const int a = lv[qt.blockIndex(c, r)];
      for (const auto& [nc, nr] : { std::pair{ c + 1, r }, std::pair{ c, r + 1 } })
      {
        if (nc >= qt.blockCols || nr >= qt.blockRows)
          continue;
        const int b = lv[qt.blockIndex(nc, nr)];
        if (a >= 0 && b >= 0 && a != b)
        {
          ++pairs;
          worst = std::max(worst, std::abs(a - b));
        }
      }
    }
  return { pairs, worst };
}

std::vector<int> bandWidths(const std::vector<int>& starts)
{
  std::vector<int> w;
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
    w.push_back(starts[k + 1] - starts[k]);
  return w;
}

void runCase(Rng& rng, int nx, int ny, int maxQ, bool withUndrawn, int& cases,
  CaseTally* tally = nullptr)
{
  gmm::Heightfield hf = roughTerrain(nx, ny, rng, randInt(rng, 0, 1) ? 2.0 : -2.0,
    randInt(rng, 0, 1) ? 3.0 : -3.0);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, maxQ);
  std::vector<uint32_t> out;
  for (int mode = 0; mode < 5; ++mode)
  {
    std::vector<int8_t> lv = randomLevels(qt, rng, mode, withUndrawn ? randReal(rng, 0.1, 0.6) : 0.0);
    gmm::tessellate(hf, qt, lv, out);
    MeshCheckOptions opt;
    if (withUndrawn)
    {
      opt.drawn.resize(lv.size());
      for (std::size_t b = 0; b < lv.size(); ++b)
        opt.drawn[b] = lv[b] >= 0;
    }
    MeshCheckResult res = checkMesh(hf, qt.colStart, qt.rowStart, out, opt);
    ++cases;
    if (tally)
    {
      tally->withTriangles += res.triangles > 0;
      tally->mixed += mixedNeighbours(qt, lv).first > 0;
    }
    if (!res.error.empty())
    {
      std::ostringstream s;
      s << nx << "x" << ny << " block " << maxQ << " dx " << hf.dx << " dy " << hf.dy
        << " mode " << mode << " levels (" << qt.blockCols << "x" << qt.blockRows << "):";
      for (int8_t l : lv)
        s << " " << int(l);
      ADD_FAILURE() << s.str() << "\n  -> " << res.error;
      return;
    }
  }
}
} // namespace

TEST(Watertight, RandomSizesAllDrawn)
{
  Rng rng(12345);
  int cases = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 500 && !HasFailure(); ++k)
  {
    const int maxQ = randInt(rng, 0, 9) == 0 ? 4 : randInt(rng, 5, 64);
    runCase(rng, randomSide(rng), randomSide(rng), maxQ, false, cases);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "[ watertight ] " << cases << " level assignments checked in " << s << " s\n";
}

TEST(Watertight, SpecialShapesAllDrawn)
{
  Rng rng(99);
  int cases = 0;
  // thin DEMs, primes, powers of two +-1, block-size boundaries
  const int sides[] = { 2, 3, 4, 5, 9, 16, 17, 31, 33, 64, 65, 66, 97, 129, 257 };
  for (int a : sides)
    for (int b : { 2, 3, 17, 66 })
      for (int maxQ : { 4, 5, 16, 32, 64 })
      {
        runCase(rng, a, b, maxQ, false, cases);
        if (HasFailure())
          return;
      }
}

TEST(Watertight, RandomSizesWithUndrawnBlocks)
{
  Rng rng(777);
  int cases = 0;
  for (int k = 0; k < 400 && !HasFailure(); ++k)
  {
    const int maxQ = randInt(rng, 0, 9) == 0 ? 4 : randInt(rng, 5, 64);
    runCase(rng, randomSide(rng), randomSide(rng), maxQ, true, cases);
  }
}

// The same through the Engine (updateWithLevels), which caches per-block triangles: a
// sequence of random assignments must give exactly what a fresh tessellate gives.
TEST(Watertight, EngineUpdateWithLevelsMatchesFreshTessellation)
{
  Rng rng(4242);
  for (int k = 0; k < 25; ++k)
  {
    const int nx = randInt(rng, 2, 120), ny = randInt(rng, 2, 120), maxQ = randInt(rng, 4, 32);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, randInt(rng, 0, 1) ? 2.0 : -2.0, 3.0);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    const gmm::Quadtree& qt = e.quadtree();
    for (int f = 0; f < 8; ++f)
    {
      std::vector<int8_t> lv = randomLevels(qt, rng, randInt(rng, 0, 4), f % 2 ? 0.3 : 0.0);
      const gmm::FrameStats& st = e.updateWithLevels(lv);
      EXPECT_EQ(e.levels(), lv);
      std::vector<uint32_t> fresh;
      gmm::tessellate(hf, qt, lv, fresh);
      ASSERT_EQ(st.triangles * 3, e.indices().size());
      // same triangle set (order may differ with caching)
      auto canon = [](const std::vector<uint32_t>& v) {
        std::vector<std::array<uint32_t, 3>> t;
        for (std::size_t i = 0; i < v.size(); i += 3)
        {
          std::array<uint32_t, 3> a{ v[i], v[i + 1], v[i + 2] };
          std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
          t.push_back(a);
        }
        std::sort(t.begin(), t.end());
        return t;
      };
      ASSERT_EQ(canon(e.indices()), canon(fresh)) << nx << "x" << ny << " frame " << f;
      MeshCheckOptions opt;
      opt.drawn.resize(lv.size());
      for (std::size_t b = 0; b < lv.size(); ++b)
        opt.drawn[b] = lv[b] >= 0;
      MeshCheckResult res = checkMesh(hf, qt.colStart, qt.rowStart, e.indices(), opt);
      ASSERT_EQ(res.error, "") << nx << "x" << ny << " frame " << f;
    }
  }
}

// The minimum block size is 4 quads (Quadtree.h raises anything smaller to 4; Engine.h
// refuses it). Halving then gives bands of 2, 3 or 4 quads, so the narrowest blocks (2 quads:
// levels 0 and 1 only) sit next to 3- and 4-quad blocks (bands of 2 or 4, a remainder of 3). Block size 2 used to give a 1-quad
// band inside a wider DEM (a Thin block next to ring/one-quad blocks) whose shared edge was
// not stitched: 4x3 DEM, blocks 1x2 and 2x2 quads at levels 0 and 1 gave a T-junction at
// (1,1). These cases check the real minimum, and that they really exercise stitching: the
// assignments must draw triangles and put coarse and fine blocks side by side.

// 16 x 9 quads at block size 4: column bands 4,4,4,4 and row bands 2,2,2,3 (9 quads take
// bands of 2, the last one quad joining the band before). Every valid level of every block, in random combinations: watertight, triangles
// drawn, coarse next to fine.
TEST(Watertight, MinimumBlockSizeNarrowBands)
{
  Rng rng(1);
  gmm::Heightfield hf = roughTerrain(17, 10, rng, 2.0, 3.0);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 4);
  ASSERT_EQ(bandWidths(qt.colStart), (std::vector<int>{ 4, 4, 4, 4 }));
  ASSERT_EQ(bandWidths(qt.rowStart), (std::vector<int>{ 2, 2, 2, 3 }));
  // below the minimum, the size is raised to it: the same bands
  for (int small : { 0, 1, 2, 3 })
  {
    const gmm::Quadtree q2 = gmm::buildQuadtree(hf, small);
    EXPECT_EQ(q2.colStart, qt.colStart) << "block size " << small;
    EXPECT_EQ(q2.rowStart, qt.rowStart) << "block size " << small;
  }
  int mixed = 0, worstDiff = 0, checked = 0;
  for (int k = 0; k < 600 && !HasFailure(); ++k)
  {
    std::vector<int8_t> lv = randomLevels(qt, rng, k % 5, k % 3 == 2 ? 0.3 : 0.0);
    std::vector<uint32_t> out;
    gmm::tessellate(hf, qt, lv, out);
    MeshCheckOptions opt;
    opt.drawn.resize(lv.size());
    for (std::size_t b = 0; b < lv.size(); ++b)
      opt.drawn[b] = lv[b] >= 0;
    const MeshCheckResult res = checkMesh(hf, qt.colStart, qt.rowStart, out, opt);
    EXPECT_EQ(res.error, "") << "assignment " << k;
    if (std::count(opt.drawn.begin(), opt.drawn.end(), true) > 0)
      EXPECT_GT(res.triangles, 0u) << "assignment " << k;
    const auto [pairs, diff] = mixedNeighbours(qt, lv);
    mixed += pairs > 0;
    worstDiff = std::max(worstDiff, diff);
    ++checked;
  }
  std::cout << "[ minimum block size ] " << checked << " assignments, " << mixed
            << " with coarse/fine neighbours, largest level difference " << worstDiff << "\n";
  EXPECT_GT(mixed, checked / 2);
  EXPECT_GE(worstDiff, 2); // 4-quad blocks reach level 2, 2-quad blocks stop at 1
}

TEST(Watertight, MinimumBlockSizeRandomSizes)
{
  Rng rng(2222);
  int cases = 0;
  CaseTally tally;
  for (int k = 0; k < 200 && !HasFailure(); ++k)
    runCase(rng, randomSide(rng), randomSide(rng), 4, k % 2 == 1, cases, &tally);
  std::cout << "[ minimum block size ] " << cases << " assignments, " << tally.withTriangles
            << " drew triangles, " << tally.mixed << " had coarse/fine neighbours\n";
  EXPECT_GT(tally.withTriangles, cases * 9 / 10);
  EXPECT_GT(tally.mixed, cases / 3);
}

// Pairs of side neighbours where one block is drawn by itself and the other by a merged
// node: the borders that merged-node stitching must keep closed.
static int mergedBorders(const gmm::Quadtree& qt, const std::vector<int8_t>& levels)
{
  int n = 0;
  for (int r = 0; r < qt.blockRows; ++r)
    for (int c = 0; c < qt.blockCols; ++c)
    {
      const int b = qt.blockIndex(c, r);
      const int right = c + 1 < qt.blockCols ? b + 1 : -1, up = r + 1 < qt.blockRows ? b + qt.blockCols : -1;
      for (int nb : { right, up })
        if (nb >= 0 && ((levels[b] >= 0 && levels[nb] == gmm::kCoveredLevel) ||
                         (levels[nb] >= 0 && levels[b] == gmm::kCoveredLevel)))
          ++n;
    }
  return n;
}

// End to end: the levels Engine::update selects for random cameras give watertight meshes
// (culled blocks count as undrawn). The minimum block size has its own case below. Many
// frames must join merged nodes to blocks drawn by themselves, or the test proves little.
TEST(Watertight, EngineUpdateFramesAreWatertight)
{
  Rng rng(8080);
  int frames = 0, mergedFrames = 0;
  for (int t = 0; t < 30 && !HasFailure(); ++t)
  {
    const int nx = randInt(rng, 2, 160), ny = randInt(rng, 2, 160);
    const int maxQ = t % 5 == 0 ? 4 : randInt(rng, 4, 64);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, randInt(rng, 0, 1) ? 10.0 : -10.0,
      randInt(rng, 0, 1) ? 10.0 : -10.0, 400.0, 0.01);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    for (int c = 0; c < 10; ++c)
    {
      gmm::View v;
      const double ext = 10.0 * std::max(nx, ny);
      v.eye = { hf.worldX(randReal(rng, -0.2, 1.2) * (nx - 1)), hf.worldY(randReal(rng, -0.2, 1.2) * (ny - 1)),
        randReal(rng, 450, 450 + 2 * ext) };
      const double az = randReal(rng, 0, 6.283), pitch = -randReal(rng, 0.1, 1.2);
      v.forward = { std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch) };
      v.fovYDegrees = randReal(rng, 20, 90);
      const double tau = std::vector<double>{ 0.5, 1, 2, 4, 16 }[randInt(rng, 0, 4)];
      const gmm::FrameStats& st = e.update(v, tau);
      ASSERT_EQ(e.lastError(), "");
      MeshCheckOptions opt;
      opt.drawn.resize(e.levels().size());
      for (std::size_t b = 0; b < e.levels().size(); ++b)
        opt.drawn[b] = gmm::drawnLevel(e.levels()[b]);
      MeshCheckResult res = checkMesh(hf, e.quadtree().colStart, e.quadtree().rowStart, e.indices(), opt);
      EXPECT_EQ(res.error, "") << nx << "x" << ny << " block " << maxQ << " tau " << tau;
      EXPECT_EQ(st.triangles, res.triangles);
      ++frames;
      mergedFrames += mergedBorders(e.quadtree(), e.levels()) > 0;
      if (HasFailure())
        return;
    }
  }
  std::cout << "[ engine frames ] " << frames << " frames, " << mergedFrames
            << " with merged nodes beside single blocks\n";
  EXPECT_GT(mergedFrames, frames / 30); // rough terrain: few merges; the next case has more
}

// The engine at the minimum block size: the levels its own selection picks
// (updateForError and update) are watertight, draw triangles and do put coarse blocks next
// to fine ones. Sizes below the minimum are refused with a reason, leaving the engine empty.
TEST(Watertight, EngineUpdateMinimumBlockSize)
{
  Rng rng(5);
  int frames = 0, mixedFrames = 0, mergedFrames = 0;
  for (int t = 0; t < 40 && !HasFailure(); ++t)
  {
    const int nx = randInt(rng, 6, 60), ny = randInt(rng, 6, 60);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, 10.0, 10.0, 100.0, 0.0);
    for (int small : { 2, 3 })
    {
      gmm::Engine refused;
      const std::string err = refused.setHeightfield(hf, small, 1);
      EXPECT_NE(err.find("minimum of 4"), std::string::npos) << "block size " << small << ": " << err;
      EXPECT_TRUE(refused.empty());
    }
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 4, 1), "");
    for (int k = 0; k < 7; ++k)
    {
      if (k < 4)
        e.updateForError(std::vector<double>{ 0.0, 1.0, 10.0, 1e9 }[k]);
      else
      {
        // looking at the DEM's centre from outside its south edge
        const double ext = 10.0 * std::max(nx, ny);
        const glm::dvec3 centre{ hf.worldX(0.5 * (nx - 1)), hf.worldY(0.5 * (ny - 1)), 50.0 };
        gmm::View v;
        v.eye = centre + glm::dvec3{ randReal(rng, -0.5, 0.5) * ext, -0.8 * ext, randReal(rng, 0.2, 0.8) * ext };
        v.forward = centre - v.eye;
        v.fovYDegrees = 60;
        e.update(v, std::vector<double>{ 0.5, 2, 8 }[k - 4]);
        ASSERT_EQ(e.lastError(), "");
      }
      MeshCheckOptions opt;
      opt.drawn.resize(e.levels().size());
      for (std::size_t b = 0; b < e.levels().size(); ++b)
        opt.drawn[b] = gmm::drawnLevel(e.levels()[b]);
      const MeshCheckResult res = checkMesh(hf, e.quadtree().colStart, e.quadtree().rowStart, e.indices(), opt);
      EXPECT_EQ(res.error, "") << nx << "x" << ny << " frame " << k;
      EXPECT_GT(res.triangles, 0u) << nx << "x" << ny << " frame " << k;
      EXPECT_EQ(res.triangles, e.stats().triangles);
      ++frames;
      mixedFrames += mixedNeighbours(e.quadtree(), e.levels()).first > 0;
      mergedFrames += mergedBorders(e.quadtree(), e.levels()) > 0;
      if (HasFailure())
        return;
    }
  }
  std::cout << "[ minimum block size ] engine: " << frames << " frames, " << mixedFrames
            << " with coarse/fine neighbours, " << mergedFrames << " with merged nodes beside single blocks\n";
  EXPECT_GT(mixedFrames, frames / 4);
  EXPECT_GT(mergedFrames, frames / 10);
}

namespace
{
// A triangle as a key independent of which vertex is listed first (orientation kept).
std::array<int, 6> triangleKey(const gmm::GridTriangle& t)
{
  int first = 0;
  for (int k = 1; k < 3; ++k)
  {
    const gmm::GridPoint& a = t.v[k];
    const gmm::GridPoint& b = t.v[first];
    if (a.j < b.j || (a.j == b.j && a.i < b.i))
    {
      first = k;
    }
  }
  std::array<int, 6> key{};
  for (int k = 0; k < 3; ++k)
  {
    key[2 * k] = t.v[(first + k) % 3].i;
    key[2 * k + 1] = t.v[(first + k) % 3].j;
  }
  return key;
}
} // namespace

// Merging a node of 2 x 2 one-quad blocks must not change the surface (geomorphing merges
// on its path relies on it): the node's fan is exactly its four blocks at their top level,
// on quadtrees of equal and unequal bands.
TEST(Watertight, TwoByTwoFanIsItsOneQuadBlocks)
{
  Rng rng(11);
  const int sizes[][2] = { { 65, 65 }, { 66, 67 }, { 131, 97 }, { 300, 211 }, { 257, 129 } };
  int checked = 0;
  for (auto& s : sizes)
    for (int maxQ : { 4, 7, 16, 32 })
    {
      const gmm::Heightfield hf = roughTerrain(s[0], s[1], rng);
      const gmm::Quadtree qt = gmm::buildQuadtree(hf, maxQ);
      for (int node = 0; node < static_cast<int>(qt.nodes.size()); ++node)
      {
        const gmm::QuadtreeNode& n = qt.nodes[node];
        if (n.colEnd - n.colBegin != 2 || n.rowEnd - n.rowBegin != 2)
        {
          continue;
        }
        std::vector<gmm::GridTriangle> fan, blocks;
        gmm::emitMergedNodeGrid(qt, node, fan);
        gmm::EmitScratch scratch;
        for (int r = n.rowBegin; r < n.rowEnd; ++r)
          for (int c = n.colBegin; c < n.colEnd; ++c)
          {
            const int b = qt.blockIndex(c, r);
            gmm::BlockConfig cfg;
            cfg.level = gmm::topLevel(qt.blockWidth(b), qt.blockHeight(b));
            cfg.edgeLevel = { cfg.level, cfg.level, cfg.level, cfg.level };
            gmm::emitBlockGrid(qt, b, cfg, gmm::BlockPart::Whole, blocks, scratch);
          }
        std::set<std::array<int, 6>> a, b;
        for (const auto& t : fan)
          a.insert(triangleKey(t));
        for (const auto& t : blocks)
          b.insert(triangleKey(t));
        ASSERT_EQ(a, b) << s[0] << " x " << s[1] << ", block " << maxQ << ", node " << node;
        ++checked;
      }
    }
  EXPECT_GT(checked, 50);
}
