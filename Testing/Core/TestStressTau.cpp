// Error thresholds and explicit levels (issue #6): tau for update(), maxError for
// updateForError() and level lists for updateWithLevels(), from 0 to absurd. Valid values
// render within their bound; NaN, negative and infinite thresholds and out-of-range levels
// are refused with a clear message, zero triangles and no stale indices (Engine.h).
#include "StressUtil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

using namespace gmmtest;

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

struct Fixture
{
  gmm::Engine e;
  gmm::View v;
  Fixture()
  {
    EXPECT_EQ(e.setHeightfield(hillsDem(129, 111), 16, 1), "");
    v = overview(e.heightfield(), 1500.0);
  }
  bool allCoarsest() const
  {
    const gmm::Quadtree& qt = e.quadtree();
    for (int b = 0; b < qt.blockCount(); ++b)
      if (e.levels()[b] >= 0 && e.levels()[b] != refTopLevel(qt.blockWidth(b), qt.blockHeight(b)))
        return false;
    return true;
  }
  // A good frame, then the refused one: it must leave nothing drawn.
  void expectRefused(const gmm::FrameStats& s, const std::string& expect, const std::string& what)
  {
    EXPECT_NE(e.lastError().find(expect), std::string::npos) << what << ": \"" << e.lastError() << "\"";
    EXPECT_EQ(s.triangles, 0u) << what;
    EXPECT_TRUE(e.indices().empty()) << what;
    for (int8_t l : e.levels())
      ASSERT_EQ(l, -1) << what;
  }
};
} // namespace

TEST(StressTau, ValidTauRendersWithinBound)
{
  Fixture f;
  std::size_t previous = SIZE_MAX;
  for (double tau : { 0.0, 1e-6, 0.5, 4.0, 1e9, DBL_MAX })
  {
    const gmm::FrameStats s = f.e.update(f.v, tau);
    expectGoodFrame(f.e, &f.v, tau, "tau " + std::to_string(tau));
    EXPECT_LE(s.triangles, previous) << "a larger tau must not add triangles";
    previous = s.triangles;
    if (tau == 0.0)
    {
      EXPECT_EQ(s.maxScreenError, 0.0); // only error-free simplification (the plane)
    }
    if (tau >= 1e9)
    {
      EXPECT_TRUE(f.allCoarsest()) << "tau " << tau;
    }
  }
}

TEST(StressTau, InvalidTauIsRefused)
{
  Fixture f;
  for (double tau : { -1.0, -1e-300, kNaN, kInf, -kInf })
  {
    ASSERT_GT(f.e.update(f.v, 1.0).triangles, 0u);
    f.expectRefused(f.e.update(f.v, tau), "must be finite and >= 0", "tau " + std::to_string(tau));
  }
}

TEST(StressTau, UpdateForErrorRange)
{
  Fixture f;
  for (double err : { 0.0, 1e-30, 0.5, 30.0, 1e30, DBL_MAX })
  {
    const gmm::FrameStats s = f.e.updateForError(err);
    expectGoodFrame(f.e, nullptr, 0.0, "maxError " + std::to_string(err));
    EXPECT_LE(s.maxGeometricError, err);
    if (err == 0.0)
    {
      EXPECT_LT(s.triangles, 2u * 128 * 110) << "the plane and plateau need no full resolution";
    }
    if (err >= 1e30)
    {
      EXPECT_TRUE(f.allCoarsest());
      EXPECT_EQ(s.triangles, coarsestTriangles(f.e.quadtree()));
    }
  }
  for (double err : { -1.0, kNaN, kInf, -kInf })
  {
    ASSERT_GT(f.e.updateForError(1.0).triangles, 0u);
    f.expectRefused(f.e.updateForError(err), "must be finite and >= 0", "maxError " + std::to_string(err));
  }
}

TEST(StressTau, UpdateWithLevelsOutOfRange)
{
  Fixture f;
  const gmm::Quadtree& qt = f.e.quadtree();
  const int blocks = qt.blockCount(); // 8 x 8 blocks of 16 x 13..14 quads: top level 4
  ASSERT_EQ(refTopLevel(qt.blockWidth(9), qt.blockHeight(9)), 4);
  for (int8_t bad : { int8_t(5), int8_t(30), int8_t(127), int8_t(-2), int8_t(-128) })
  {
    std::vector<int8_t> lv(blocks, 1);
    lv[9] = bad;
    ASSERT_GT(f.e.updateForError(1.0).triangles, 0u);
    f.expectRefused(f.e.updateWithLevels(lv), "level " + std::to_string(bad) + " is not valid for block 9",
      "level " + std::to_string(bad));
  }
  for (std::size_t n : { std::size_t(0), std::size_t(blocks - 1), std::size_t(blocks + 1) })
  {
    ASSERT_GT(f.e.updateForError(1.0).triangles, 0u);
    f.expectRefused(f.e.updateWithLevels(std::vector<int8_t>(n, 0)),
      "levels for " + std::to_string(blocks) + " blocks", "list of " + std::to_string(n));
  }
  // the extremes that are valid: nothing drawn, everything finest, everything coarsest
  EXPECT_EQ(f.e.updateWithLevels(std::vector<int8_t>(blocks, -1)).triangles, 0u);
  EXPECT_EQ(f.e.lastError(), "");
  f.e.updateWithLevels(std::vector<int8_t>(blocks, 0));
  expectGoodFrame(f.e, nullptr, 0.0, "all level 0");
  EXPECT_EQ(f.e.stats().triangles, 2u * 128 * 110);
  f.e.updateWithLevels(std::vector<int8_t>(blocks, 4));
  expectGoodFrame(f.e, nullptr, 0.0, "all level 4");
  EXPECT_EQ(f.e.stats().triangles, 2u * blocks);
}

// tau / factor overflows to +inf for a huge tau (or a far camera): the budget must stay
// finite, else "+inf <= +inf" admits the levels the error table marks as not allowed
// (+inf), e.g. coarse levels of blocks with nodata, which would draw over the holes.
namespace
{
// Nodata samples that a triangle of `idx` covers or touches (edges and vertices included),
// found from the heights by an integer point-in-triangle test over the grid.
std::size_t nodataUnderTriangles(const gmm::Heightfield& hf, const std::vector<uint32_t>& idx)
{
  std::size_t found = 0;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
  {
    long long I[3], J[3];
    for (int k = 0; k < 3; ++k)
    {
      I[k] = idx[t + k] % hf.nx;
      J[k] = idx[t + k] / hf.nx;
    }
    const long long area = (I[1] - I[0]) * (J[2] - J[0]) - (I[2] - I[0]) * (J[1] - J[0]);
    const long long sign = area < 0 ? -1 : 1;
    for (long long j = std::min({ J[0], J[1], J[2] }); j <= std::max({ J[0], J[1], J[2] }); ++j)
      for (long long i = std::min({ I[0], I[1], I[2] }); i <= std::max({ I[0], I[1], I[2] }); ++i)
      {
        bool inside = true;
        for (int k = 0; k < 3; ++k)
        {
          const int p = (k + 1) % 3, q = (k + 2) % 3;
          inside = inside && sign * ((I[q] - I[p]) * (j - J[p]) - (J[q] - J[p]) * (i - I[p])) >= 0;
        }
        if (inside && std::isnan(hf.height(static_cast<int>(i), static_cast<int>(j))))
          ++found;
      }
  }
  return found;
}
} // namespace

TEST(StressTau, HugeTauNeverDrawsOverNodata)
{
  // Scattered single nodata samples: at a huge tau every block takes its coarsest level
  // that draws nothing over them (HoleCells.h: cells around them at full resolution), so
  // some blocks with nodata are drawn coarse (those whose nodata is away from their
  // border), and no drawn triangle covers or touches nodata (checked from the heights).
  gmm::Heightfield hf = hillsDem(129, 111);
  for (int k = 0; k < 30; ++k)
    hf.z[(k * 7919) % hf.z.size()] = std::numeric_limits<float>::quiet_NaN();
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 16, 1), "");
  for (double tau : { 1e300, DBL_MAX })
  {
    const gmm::View v = overview(e.heightfield(), 1500.0);
    e.update(v, tau);
    expectGoodFrame(e, &v, tau, "nodata, tau " + std::to_string(tau));
    EXPECT_EQ(nodataUnderTriangles(e.heightfield(), e.indices()), 0u) << "tau " << tau;
    const gmm::Quadtree& qt = e.quadtree();
    int coarse = 0;
    for (int b = 0; b < qt.blockCount(); ++b)
      coarse += qt.blockHasNodata[b] && e.levels()[b] > 0;
    EXPECT_GT(coarse, 0) << "no block with nodata drawn coarse";
  }
}
