// Geomorphing (Morph.h): where vertices move, and that the morphed surface keeps the
// certificate and stays watertight.
//
// - HandComputed: targets on a 9 x 9 block worked out by hand (cell diagonals, the ring's
//   south-east corner cell, an edge polyline).
// - TargetsLieOnCoarseLevel: every interior vertex of a block at level m moves to the surface
//   that Tessellate emits for the block at its next level (rasterised independently,
//   CoreTestUtil), and at factor 1 the morphed level-m surface equals that surface wherever
//   the two triangulations nest (counted and reported; see design.md for where they do not).
// - CertifiedWhileMorphing: random terrains and cameras; the morphed surface measured with
//   the independent screen-error measure stays within tau, every in-frustum sample is
//   covered, and triangles sharing a sample agree on its morphed height (no crack).
// - PartErrorsEqualTheMorphedSurfaceSampled: morphPartErrors' corner errors equal the
//   largest distance of each part's moved triangles, rasterised by CoreTestUtil, to the
//   samples they cover.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "EdgeHeights.h"
#include "Morph.h"
#include "MorphBounds.h"
#include "MorphTestUtil.h"
#include "SyntheticTerrain.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

using namespace gmmtest;

namespace
{
gmm::Heightfield handField()
{
  gmm::Heightfield hf;
  hf.nx = hf.ny = 9;
  hf.z.resize(81);
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i)
      hf.z[hf.index(i, j)] = static_cast<float>(i * i + 3 * j * j + i * j + ((i * 7 + j * 5) % 4));
  return hf;
}

gmm::View randomCamera(Rng& rng, const gmm::Heightfield& hf)
{
  const double ext = std::max(std::fabs(hf.dx) * (hf.nx - 1), std::fabs(hf.dy) * (hf.ny - 1));
  gmm::View v;
  v.viewportWidth = 1280;
  v.viewportHeight = 720;
  const double pi = 3.14159265358979323846;
  const int i = randInt(rng, 0, hf.nx - 1), j = randInt(rng, 0, hf.ny - 1);
  const double az = randReal(rng, 0, 2 * pi), pitch = -randReal(rng, 5, 60) * pi / 180;
  v.eye = { hf.worldX(i), hf.worldY(j), hf.height(i, j) + std::exp(randReal(rng, std::log(5.0), std::log(ext))) };
  v.forward = { std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch) };
  v.up = { 0, 0, 1 };
  v.fovYDegrees = randReal(rng, 30, 70);
  v.nearDistance = 0.5;
  v.farDistance = 1e6;
  return v;
}

// A random key of block b (MorphBlockState::key): a valid level, its next valid level as
// target or none, and per side an edge level from the block's level up to its top with a
// coarser edge target or none.
using MorphKey = std::array<int8_t, 10>;
MorphKey randomMorphKey(const gmm::Quadtree& qt, int b, Rng& rng)
{
  const int w = qt.blockWidth(b), h = qt.blockHeight(b), top = gmm::topLevel(w, h);
  std::vector<int> valid;
  for (int m = 0; m <= top; ++m)
    if (gmm::blockShape(w, h, m) != gmm::BlockShape::Invalid)
      valid.push_back(m);
  MorphKey k;
  k[0] = static_cast<int8_t>(valid[randInt(rng, 0, static_cast<int>(valid.size()) - 1)]);
  const int next = gmm::nextValidLevel(w, h, k[0]);
  k[5] = static_cast<int8_t>(next >= 0 && randInt(rng, 0, 3) > 0 ? next : -1);
  for (int s = 0; s < 4; ++s)
  {
    k[1 + s] = static_cast<int8_t>(randInt(rng, k[0], top));
    k[6 + s] = static_cast<int8_t>(k[1 + s] < top && randInt(rng, 0, 1) ? randInt(rng, k[1 + s] + 1, top) : -1);
    // An edge coarser than a ring block is glided (its own cells up to it) or not (fanned
    // to it, beside a merged node), as the part cache's keys say: 32 added when glided.
    if (k[1 + s] > k[0] && gmm::blockShape(w, h, k[0]) == gmm::BlockShape::Ring && randInt(rng, 0, 1))
      k[1 + s] = static_cast<int8_t>(k[1 + s] + 32);
  }
  return k;
}

// The configuration a MorphKey stands for (a glided edge's side field has 32 added).
gmm::BlockConfig configOfKey(const MorphKey& k)
{
  gmm::BlockConfig cfg;
  cfg.level = k[0];
  for (int s = 0; s < 4; ++s)
  {
    cfg.edgeLevel[s] = k[1 + s] & 31;
    cfg.sampleLevel[s] = k[1 + s] >= 32 ? k[0] : -1;
  }
  return cfg;
}
} // namespace

TEST(Morph, HandComputed)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(handField(), 8, 1), "");
  ASSERT_EQ(e.quadtree().blockCount(), 1);
  const gmm::Heightfield& hf = e.heightfield();
  auto h = [&](int i, int j) { return static_cast<double>(hf.height(i, j)); };
  e.updateWithLevels({ 0 });
  gmm::MorphFrame f;
  gmm::clearMorph(e.quadtree(), f);
  EXPECT_EQ(gmm::nextValidLevel(8, 8, 0), 1);
  EXPECT_EQ(gmm::nextValidLevel(8, 8, 3), -1);
  EXPECT_EQ(gmm::nextValidLevel(40, 12, 3), 6); // 2^4, 2^5 cover 12 but not 40: skipped
  f.blockTarget[0] = 1;
  f.blockT[0] = 1.0f;
  f.hEdges[0].level = 0; // south edge
  f.hEdges[0].target = 1;
  f.hEdges[0].t = 0.25f;
  double t = -1;
  // (1, 1): cell (0,0)-(2,2), on its (0,0)-(2,2) diagonal
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 1, 1, &t), 0.5 * (h(0, 0) + h(2, 2)));
  EXPECT_EQ(t, 1.0);
  // (3, 2): cell (2,2)-(4,4), point (0.5, 0) on its south side
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 3, 2, &t), 0.5 * (h(2, 2) + h(4, 2)));
  // (5, 3): cell (4,2)-(6,4) is cell (2, 1) of level 1: u + v odd, split along (6,2)-(4,4)
  // (the union-jack rule); fx = fy = 0.5 lies on that diagonal
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 5, 3, &t), 0.5 * (h(6, 2) + h(4, 4)));
  // (3, 5): cell (2,4)-(4,6) is cell (1, 2): split along (2,4)-(4,6) as well
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 3, 5, &t), 0.5 * (h(4, 4) + h(2, 6)));
  // (5, 5): cell (4,4)-(6,6) is cell (2, 2): u + v even, split along (4,4)-(6,6)
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 5, 5, &t), 0.5 * (h(4, 4) + h(6, 6)));
  // (7, 1): the south-east corner cell (6,0)-(8,2) is split along (8,0)-(6,2)
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 7, 1, &t), 0.5 * (h(8, 0) + h(6, 2)));
  // (1, 7): the north-west corner cell (0,6)-(2,8), along (2,6)-(0,8)
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 1, 7, &t), 0.5 * (h(2, 6) + h(0, 8)));
  // (4, 4): a level-1 sample does not move
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 4, 4, &t), h(4, 4));
  // (3, 0): south edge, between edge samples 2 and 4 of level 1, edge factor 0.25
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 3, 0, &t), 0.5 * (h(2, 0) + h(4, 0)));
  EXPECT_EQ(t, 0.25);
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, e.quadtree(), e.levels(), f, 3, 0),
    h(3, 0) + 0.25 * (0.5 * (h(2, 0) + h(4, 0)) - h(3, 0)));
  // (3, 8): north edge has no morph data: stays
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, e.quadtree(), e.levels(), f, 3, 8), h(3, 8));
  // corners never move
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, e.quadtree(), e.levels(), f, 8, 0), h(8, 0));
  // level 2 (step 4) as the target: (5, 5) in cell (4,4)-(8,8), which is a ring's north-east
  // corner cell (main diagonal), fx = fy = 0.25
  f.blockTarget[0] = 2;
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 5, 5, &t), h(4, 4) + 0.25 * (h(8, 8) - h(4, 4)));
  // (2, 6) in the north-west corner cell (0,4)-(4,8): fx 0.5, fy 0.5, on the (4,4)-(0,8) diagonal
  EXPECT_DOUBLE_EQ(gmm::morphTarget(hf, e.quadtree(), e.levels(), f, 2, 6, &t), 0.5 * (h(4, 4) + h(0, 8)));
}

// Interior targets against the next level's own triangles, rasterised by CoreTestUtil; and
// the fully morphed level-m surface against that level everywhere in the block.
TEST(Morph, TargetsLieOnCoarseLevel)
{
  Rng rng(77);
  std::size_t vertices = 0, samples = 0, samplesEqual = 0, differThin = 0, differElsewhere = 0;
  for (int t = 0; t < 40; ++t)
  {
    const int nx = randInt(rng, 9, 90), ny = randInt(rng, 9, 90);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    const int maxQ = 1 << randInt(rng, 2, 5);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    const gmm::Quadtree& qt = e.quadtree();
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      const int w = qt.blockWidth(b), h = qt.blockHeight(b);
      for (int m = 0; m <= gmm::topLevel(w, h); ++m)
      {
        const int next = gmm::nextValidLevel(w, h, m);
        if (!refLevelValid(w, h, m) || next < 0)
          continue;
        ASSERT_TRUE(refLevelValid(w, h, next));
        std::vector<int8_t> levels(qt.blockCount(), -1);
        levels[b] = static_cast<int8_t>(m);
        ASSERT_EQ(e.updateWithLevels(levels).triangles > 0, true);
        const std::vector<uint32_t> fine = e.indices();
        levels[b] = static_cast<int8_t>(next);
        e.updateWithLevels(levels);
        const SurfaceSample coarse = sampleSurface(hf, e.indices());
        levels[b] = static_cast<int8_t>(m);
        e.updateWithLevels(levels);
        gmm::MorphFrame f;
        gmm::clearMorph(qt, f);
        f.blockTarget[b] = static_cast<int8_t>(next);
        f.blockT[b] = 1.0f;
        const int c = b % qt.blockCols, r = b / qt.blockCols;
        // its four edges follow it to the next level too, as they do when it sets them
        for (gmm::MorphEdge* edge : { &f.hEdges[static_cast<std::size_t>(r) * qt.blockCols + c],
               &f.hEdges[static_cast<std::size_t>(r + 1) * qt.blockCols + c],
               &f.vEdges[static_cast<std::size_t>(r) * (qt.blockCols + 1) + c],
               &f.vEdges[static_cast<std::size_t>(r) * (qt.blockCols + 1) + c + 1] })
          *edge = gmm::MorphEdge{ static_cast<int8_t>(m), static_cast<int8_t>(next), 1.0f };
        std::vector<double> z = morphedHeights(e, f);
        std::vector<uint8_t> used(hf.sampleCount(), 0);
        for (uint32_t v : fine)
          used[v] = 1;
        const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
          {
            const std::size_t k = hf.index(i, j);
            if (!used[k])
              continue;
            ++vertices;
            ASSERT_NEAR(z[k], coarse.z[k], 1e-9 * (1 + std::fabs(coarse.z[k])))
              << nx << "x" << ny << " block " << b << " (" << w << "x" << h << ") level " << m
              << " -> " << next << " vertex (" << i << "," << j << ")";
          }
        const SurfaceSample morphed = sampleSurface(hf, fine, z.data());
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
          {
            const std::size_t k = hf.index(i, j);
            ++samples;
            if (std::fabs(morphed.z[k] - coarse.z[k]) <= 1e-9 * (1 + std::fabs(coarse.z[k])))
            {
              ++samplesEqual;
              continue;
            }
            // Where they may differ: in a thin last interval of the coarse grid (a coarse cell
            // split on one axis only has no fine vertex on its diagonals). Everywhere else the
            // union-jack cells nest, the ring's corner cells included.
            const int s = 1 << next;
            const bool thinI = (w % s) && i >= i0 + (w / s) * s;
            const bool thinJ = (h % s) && j >= j0 + (h / s) * s;
            if (thinI || thinJ)
              ++differThin;
            else
            {
              ++differElsewhere;
              ADD_FAILURE() << nx << "x" << ny << " block " << b << " (" << w << "x" << h << ") level "
                            << m << " -> " << next << ": morphed surface differs at (" << i << "," << j << ")";
              return;
            }
          }
      }
    }
  }
  std::printf("[ morph ] %zu vertices on the next level's surface; at factor 1 the "
              "level-m surface equals the next level at %.2f%% of %zu block samples\n",
    vertices, 100.0 * samplesEqual / std::max<std::size_t>(1, samples), samples);
  std::printf("[ morph ] differing samples: %zu in thin last intervals, %zu elsewhere\n", differThin,
    differElsewhere);
  EXPECT_GT(vertices, 10000u);
}

TEST(Morph, CertifiedWhileMorphing)
{
  Rng rng(4242);
  std::size_t checked = 0, partial = 0, framesMoved = 0;
  double worst = 0.0;
  for (int t = 0; t < 12; ++t)
  {
    const int nx = randInt(rng, 65, 200), ny = randInt(rng, 65, 160);
    gmm::Heightfield hf = t % 2 ? roughTerrain(nx, ny, rng, 10.0, t % 4 == 1 ? -12.0 : 12.0, 400.0, 0.02)
                               : gmm::makeSyntheticTerrain(nx, ny, 20.0, 100 + t, 800.0, 1);
    const int maxQ = 1 << randInt(rng, 3, 5);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    gmm::MorphCache cache;
    for (int c = 0; c < 6; ++c)
    {
      const gmm::View v = randomCamera(rng, e.heightfield());
      for (double tau : { 1.0, 2.0, 4.0 })
      {
        e.update(v, tau);
        ASSERT_EQ(e.lastError(), "");
        gmm::MorphFrame f;
        gmm::computeMorph(e.heightfield(), e.quadtree(), e.levels(), e.pixelFactors(), tau, cache, f);
        const std::vector<double> z = morphedHeights(e, f);
        bool moved = false;
        for (std::size_t k = 0; k < z.size(); ++k)
          moved = moved || z[k] != e.heightfield().heights()[k];
        framesMoved += moved;
        for (float bt : f.blockT)
          partial += bt > 0.0f && bt < 1.0f;
        const ScreenMeasure m = measureScreenError(e.heightfield(), e.indices(), &v, tau, MeasureTransform(), z.data());
        const SurfaceSample s = sampleSurface(e.heightfield(), e.indices(), z.data());
        checked += m.inFrustum;
        worst = std::max(worst, m.maxDist / tau);
        EXPECT_EQ(m.uncovered, 0u) << m.first;
        EXPECT_EQ(m.violations, 0u) << "tau " << tau << ": " << m.first;
        EXPECT_LE(f.maxBoundPixels, tau * (1 + 1e-9));
        EXPECT_LE(s.maxDisagreement, 1e-9 * 2000) << "triangles disagree on a shared sample";
        if (::testing::Test::HasFailure())
          return;
      }
    }
  }
  std::printf("[ morph ] %zu in-frustum samples, %zu frames with moved vertices, %zu blocks "
              "part-way morphed; worst measured/tau %.4f\n",
    checked, framesMoved, partial, worst);
  EXPECT_GT(framesMoved, 100u); // the campaign really morphed
  EXPECT_GT(partial, 1000u);
}

// Holes and degenerate shapes: a DEM with nodata, one a single quad wide, and the smallest
// DEM. Drawn vertices keep finite heights, blocks touching nodata do not morph, and the
// morphed frame still measures within tau with every in-frustum sample covered.
TEST(Morph, NodataAndThinDEMs)
{
  Rng rng(99);
  std::vector<gmm::Heightfield> fields;
  gmm::Heightfield holes = roughTerrain(120, 90, rng);
  for (int j = 30; j < 45; ++j)
    for (int i = 50; i < 70; ++i)
      holes.z[holes.index(i, j)] = std::numeric_limits<float>::quiet_NaN();
  holes.z[holes.index(5, 80)] = std::numeric_limits<float>::quiet_NaN();
  fields.push_back(holes);
  fields.push_back(roughTerrain(2, 200, rng));
  fields.push_back(roughTerrain(150, 2, rng));
  fields.push_back(roughTerrain(2, 2, rng));
  for (const gmm::Heightfield& hf : fields)
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 16, 1), "");
    gmm::MorphCache cache;
    for (int c = 0; c < 8; ++c)
    {
      const gmm::View v = randomCamera(rng, e.heightfield());
      for (double tau : { 2.0, 8.0 })
      {
        e.update(v, tau);
        ASSERT_EQ(e.lastError(), "");
        gmm::MorphFrame f;
        gmm::computeMorph(e.heightfield(), e.quadtree(), e.levels(), e.pixelFactors(), tau, cache, f);
        const std::vector<double> z = morphedHeights(e, f);
        for (uint32_t k : e.indices())
          ASSERT_TRUE(std::isfinite(z[k])) << hf.nx << "x" << hf.ny << " vertex " << k;
        const ScreenMeasure m = measureScreenError(e.heightfield(), e.indices(), &v, tau, MeasureTransform(), z.data());
        EXPECT_EQ(m.violations, 0u) << hf.nx << "x" << hf.ny << ": " << m.first;
        EXPECT_EQ(m.uncovered, 0u) << hf.nx << "x" << hf.ny << ": " << m.first;
        const gmm::Quadtree& qt = e.quadtree();
        for (int b = 0; b < qt.blockCount(); ++b)
          if (qt.blockHasNodata[b])
            EXPECT_EQ(f.blockT[b], 0.0f) << "block " << b << " has nodata";
        if (::testing::Test::HasFailure())
          return;
      }
    }
  }
}

TEST(Morph, NextValidLevelIsTheFirstLevelWithAShape)
{
  // The closed form against its definition: the first level above m that blockShape allows.
  for (int w = 1; w <= 70; ++w)
    for (int h = 1; h <= 70; ++h)
    {
      const int top = gmm::topLevel(w, h);
      for (int m = 0; m <= top; ++m)
      {
        int want = -1;
        for (int n = m + 1; n <= top && want < 0; ++n)
          if (gmm::blockShape(w, h, n) != gmm::BlockShape::Invalid)
            want = n;
        ASSERT_EQ(gmm::nextValidLevel(w, h, m), want) << w << " x " << h << ", level " << m;
      }
    }
}

TEST(Morph, DiagonalReachIsTheFirstCrossing)
{
  // The closed form against a bisection of its definition (the largest t with the strip's
  // bound within the limit on all of [0, t]) over random corner errors and limits: the
  // bound holds on [0, t] (checked with stripBound itself), and t is not more than 1e-9
  // below the bisection's.
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int partial = 0;
  for (int trial = 0; trial < 50000; ++trial)
  {
    double e[4];
    for (double& x : e)
      x = u(rng) < 0.1 ? 0.0 : std::exp(8.0 * u(rng) - 4.0);
    const double limit = e[0] + (u(rng) < 0.05 ? 0.0 : std::exp(8.0 * u(rng) - 5.0));
    // The definition on 65 points of [0, t], exactly (the reference) or up to rounding
    // (stripBound and the parabola round differently).
    auto within = [&](double t, double slack) {
      for (int k = 0; k <= 64; ++k)
        if (gmm::stripBound(e, t * k / 64.0, t * k / 64.0) > limit * (1.0 + slack))
          return false;
      return true;
    };
    // The reference: the definition bisected with the parabola and its vertex (what the
    // engine did before the closed form).
    const double c = e[0], b = e[1] + e[2] - 2.0 * e[0], a = e[0] - e[1] - e[2] + e[3];
    auto q = [&](double x) { return c + x * (b + x * a); };
    const double vertex = a < 0.0 ? -b / (2.0 * a) : -1.0;
    auto ok = [&](double x) { return q(x) <= limit && !(vertex > 0.0 && vertex < x && q(vertex) > limit); };
    double lo = 0.0, hi = 1.0;
    if (ok(1.0))
      lo = 1.0;
    else
      for (int n = 0; n < 60; ++n)
      {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
      }
    const double t = gmm::diagonalReach(e, limit);
    ASSERT_TRUE(within(t, 1e-12)) << "trial " << trial << ": t " << t << " breaks the bound";
    ASSERT_GE(t, lo - 1e-9) << "trial " << trial;
    partial += t > 0.0 && t < 1.0;
  }
  EXPECT_GT(partial, 5000);
}

TEST(Morph, PartErrorsEqualTheMorphedSurfaceSampled)
{
  // morphPartErrors' corner errors against the surface they bound, sampled independently:
  // for each part and each corner (edge vertices as drawn or at their targets, ring
  // vertices likewise, toward targets that follow the other edges at each of their
  // extremes), the part's triangles (emitBlock) with their vertices moved so
  // (blockVertexTarget, checked by HandComputed) are rasterised by sampleSurface
  // (CoreTestUtil: every lattice point of the bounding box, its own barycentric weights),
  // and the largest |drawn - sample| over the samples they cover is the corner's error.
  // Random blocks, keys and block shapes (blocks of 4 to 16 quads, thin ones at the border).
  Rng rng(2024);
  const gmm::Heightfield hf = roughTerrain(87, 70, rng, 20.0, 20.0, 400.0, 0.05);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  gmm::MorphPartScratch scratch;
  std::vector<double> drawnZ(hf.z.size());
  std::vector<uint32_t> idx;
  int compared = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const int b = randInt(rng, 0, qt.blockCount() - 1);
    // Half the edges coarser than the block glided (its own cells up to them, their
    // samples on the edge's polyline), half fanned (as beside a merged node).
    const MorphKey k = randomMorphKey(qt, b, rng);
    const gmm::BlockConfig cfg = configOfKey(k);
    const std::array<int, 4> edgeTarget{ k[6], k[7], k[8], k[9] };
    const gmm::PartErrors pe = gmm::morphPartErrors(hf, qt, b, cfg, k[5], edgeTarget, scratch);
    const int c = b % qt.blockCols, r = b / qt.blockCols;
    const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
    for (int p = 0; p < 5; ++p)
    {
      const gmm::BlockPart part = p == 0 ? gmm::BlockPart::Inner
                                         : static_cast<gmm::BlockPart>(static_cast<int>(gmm::BlockPart::StripSouth) + p - 1);
      idx.clear();
      gmm::emitBlock(hf, qt, b, cfg, part, idx);
      for (int corner = 0; corner < 4; ++corner)
      {
        const int e = corner / 2, rr = corner % 2; // PartErrors::side's e * 2 + r
        if (p == 0 && e == 1)
          continue; // the inner grid has no edge vertex
        // The ring vertices' targets follow the edges' factors: the strip's own edge at e,
        // every other edge at 0 or 1, the worst of them (MorphBounds.h).
        double expected = 0.0;
        double atMask[16] = {}; // the inner grid at its targets, per corner of the edges' factors
        for (int mask = 0; mask < 16; ++mask)
        {
          std::array<double, 4> factor{};
          for (int s = 0; s < 4; ++s)
            factor[s] = s == p - 1 ? e : (mask >> s) & 1;
          for (uint32_t v : idx)
          {
            const int i = static_cast<int>(v % hf.nx), j = static_cast<int>(v / hf.nx);
            // Edge vertices start on their edge's polyline (its own samples are on it).
            const bool onEdge = i == i0 || i == i1 || j == j0 || j == j1;
            const double h = onEdge ? gmm::sideBaseHeight(hf, i0, i1, j0, j1, cfg.edgeLevel, i, j) : hf.height(i, j);
            const double target = gmm::blockVertexTarget(hf, qt, b, k[5], edgeTarget, cfg.edgeLevel, i, j, factor);
            drawnZ[v] = h + (onEdge ? e : rr) * (target - h);
          }
          const SurfaceSample surf = sampleSurface(hf, idx, drawnZ.data());
          for (std::size_t s = 0; s < hf.z.size(); ++s)
            if (surf.covered[s])
              atMask[mask] = std::max(atMask[mask], std::fabs(surf.z[s] - hf.z[s]));
          expected = std::max(expected, atMask[mask]);
        }
        if (p == 0 && rr == 1)
        {
          // PartErrors::innerAt: each corner's error, the largest over its sub-masks, rounded
          // up to float.
          for (int mask = 0; mask < 16; ++mask)
          {
            double want = 0.0;
            for (int sub = 0; sub < 16; ++sub)
              if ((sub & mask) == sub)
                want = std::max(want, atMask[sub]);
            ASSERT_GE(double(pe.innerAt[mask]), want - 1e-9 * (1.0 + want))
              << "trial " << trial << " block " << b << " mask " << mask;
            ASSERT_LE(double(pe.innerAt[mask]), want + 1e-6 * (1.0 + want))
              << "trial " << trial << " block " << b << " mask " << mask;
            ++compared;
          }
        }
        const double got = p == 0 ? pe.inner[rr] : pe.side[p - 1][corner];
        ASSERT_NEAR(got, expected, 1e-9 * (1.0 + expected))
          << "trial " << trial << " block " << b << " part " << p << " corner " << corner;
        ++compared;
      }
    }
  }
  std::printf("[ morph parts ] %d part corners equal the sampled surface's\n", compared);
  EXPECT_GT(compared, 5000);
}

TEST(Morph, PartErrorsRecomputedPartByPartEqualFreshOnes)
{
  // The morph cache recomputes only the parts a key change invalidates (changedMorphParts,
  // updateMorphPartErrors). Over random blocks and random pairs of keys (level, edge levels,
  // target, edge targets): the errors of the first key updated with that mask equal the
  // second key's computed from scratch, every field exactly. This checks the dependency
  // claim (a strip reads its own edge's level and target, not the other sides') as well as
  // the mask.
  Rng rng(77);
  const gmm::Heightfield hf = roughTerrain(131, 101, rng, 20.0, 20.0, 400.0, 0.05);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  gmm::MorphPartScratch scratch;
  using Key = MorphKey;
  auto randomKey = [&](int b) { return randomMorphKey(qt, b, rng); };
  auto errorsOf = [&](int b, const Key& k, unsigned parts, gmm::PartErrors& e) {
    gmm::updateMorphPartErrors(hf, qt, b, configOfKey(k), k[5], { k[6], k[7], k[8], k[9] }, parts, e, scratch);
  };
  int partial = 0, strips = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    const int b = randInt(rng, 0, qt.blockCount() - 1);
    const Key was = randomKey(b);
    Key now = was;
    const Key other = randomKey(b);
    switch (randInt(rng, 0, 3))
    {
      case 0: // a neighbour changed one edge's level (glided or not) and/or target
      {
        const int s = randInt(rng, 0, 3);
        const int edge = std::max(other[1 + s] & 31, static_cast<int>(was[0]));
        now[1 + s] = static_cast<int8_t>(edge + (other[1 + s] >= 32 && edge > was[0] ? 32 : 0));
        now[6 + s] = (now[1 + s] & 31) < other[6 + s] ? other[6 + s] : -1;
        break;
      }
      case 1: // one edge's target alone
      {
        const int s = randInt(rng, 0, 3);
        now[6 + s] = (now[1 + s] & 31) < other[6 + s] ? other[6 + s] : -1;
        break;
      }
      case 2: // the block's own target
        now[5] = now[5] >= 0 ? -1 : static_cast<int8_t>(gmm::nextValidLevel(qt.blockWidth(b), qt.blockHeight(b), now[0]));
        break;
      default: // anything
        now = other;
        break;
    }
    gmm::PartErrors updated;
    errorsOf(b, was, gmm::kAllMorphParts, updated);
    const unsigned parts = gmm::changedMorphParts(was, now);
    errorsOf(b, now, parts, updated);
    gmm::PartErrors fresh;
    errorsOf(b, now, gmm::kAllMorphParts, fresh);
    partial += parts != gmm::kAllMorphParts && parts != 0;
    strips += parts != 0 && !(parts & 1u);
    ASSERT_EQ(std::memcmp(updated.inner, fresh.inner, sizeof fresh.inner), 0) << "trial " << trial;
    ASSERT_EQ(std::memcmp(updated.innerAt, fresh.innerAt, sizeof fresh.innerAt), 0) << "trial " << trial;
    ASSERT_EQ(std::memcmp(updated.side, fresh.side, sizeof fresh.side), 0) << "trial " << trial << " parts " << parts;
    ASSERT_EQ(updated.innerFrozen, fresh.innerFrozen) << "trial " << trial;
    ASSERT_EQ(updated.sideFrozen, fresh.sideFrozen) << "trial " << trial;
  }
  std::printf("[ morph parts ] 3000 key changes, %d recomputed some strips only\n", strips);
  EXPECT_GT(partial, 500);
}
