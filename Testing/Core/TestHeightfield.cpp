// Heightfield validation and Inf -> nodata conversion (Heightfield.h), and that the engine
// refuses what validation refuses.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Heightfield.h"
#include "Quadtree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
gmm::Heightfield flat(int nx, int ny, double dx = 1.0, double dy = 1.0)
{
  gmm::Heightfield hf;
  hf.nx = nx;
  hf.ny = ny;
  hf.dx = dx;
  hf.dy = dy;
  if (nx > 0 && ny > 0)
    hf.z.assign(static_cast<std::size_t>(nx) * ny, 1.0f);
  return hf;
}
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
} // namespace

TEST(Heightfield, RejectsTooSmall)
{
  EXPECT_FALSE(gmm::validateHeightfield(flat(1, 5)).empty());
  EXPECT_FALSE(gmm::validateHeightfield(flat(5, 1)).empty());
  EXPECT_FALSE(gmm::validateHeightfield(flat(0, 5)).empty());
  EXPECT_FALSE(gmm::validateHeightfield(flat(5, 0)).empty());
  EXPECT_FALSE(gmm::validateHeightfield(flat(1, 1)).empty());
  EXPECT_FALSE(gmm::validateHeightfield(flat(0, 0)).empty());
  gmm::Heightfield neg = flat(3, 3);
  neg.nx = -3; // negative size with a (wrong) count
  EXPECT_FALSE(gmm::validateHeightfield(neg).empty());
}

TEST(Heightfield, RejectsMismatchedHeightCount)
{
  gmm::Heightfield hf = flat(4, 5);
  hf.z.pop_back();
  EXPECT_FALSE(gmm::validateHeightfield(hf).empty());
  hf = flat(4, 5);
  hf.z.push_back(0.f);
  EXPECT_FALSE(gmm::validateHeightfield(hf).empty());
  hf = flat(4, 5);
  hf.z.clear();
  EXPECT_FALSE(gmm::validateHeightfield(hf).empty());
}

TEST(Heightfield, RejectsBadSpacingAndOrigin)
{
  for (double bad : { 0.0, -0.0, kNaN, kInf, -kInf })
  {
    EXPECT_FALSE(gmm::validateHeightfield(flat(3, 3, bad, 1.0)).empty()) << "dx=" << bad;
    EXPECT_FALSE(gmm::validateHeightfield(flat(3, 3, 1.0, bad)).empty()) << "dy=" << bad;
  }
  for (double bad : { kNaN, kInf, -kInf })
  {
    gmm::Heightfield hf = flat(3, 3);
    hf.x0 = bad;
    EXPECT_FALSE(gmm::validateHeightfield(hf).empty()) << "x0=" << bad;
    hf = flat(3, 3);
    hf.y0 = bad;
    EXPECT_FALSE(gmm::validateHeightfield(hf).empty()) << "y0=" << bad;
  }
}

TEST(Heightfield, AcceptsArbitrarySizes)
{
  const int sizes[][2] = { { 2, 2 }, { 2, 17 }, { 17, 2 }, { 2, 1000 }, { 1000, 37 }, { 37, 1000 },
    { 3, 3 }, { 7, 13 }, { 97, 101 }, { 257, 2 }, { 65, 65 }, { 64, 64 } };
  for (auto& s : sizes)
    EXPECT_TRUE(gmm::validateHeightfield(flat(s[0], s[1])).empty()) << s[0] << "x" << s[1];
  // negative spacing flips an axis and is fine
  EXPECT_TRUE(gmm::validateHeightfield(flat(5, 4, -2.0, 3.0)).empty());
  EXPECT_TRUE(gmm::validateHeightfield(flat(5, 4, -2.0, -3.0)).empty());
  // nodata is allowed, also everywhere
  gmm::Heightfield hf = flat(5, 4);
  for (float& z : hf.z)
    z = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(gmm::validateHeightfield(hf).empty());
}

TEST(Heightfield, EngineReturnsValidationError)
{
  gmm::Engine e;
  EXPECT_FALSE(e.setHeightfield(flat(1, 9)).empty());
  EXPECT_TRUE(e.empty());
  EXPECT_FALSE(e.setHeightfield(flat(3, 3, 0.0, 1.0)).empty());
  EXPECT_TRUE(e.empty());
  gmm::Heightfield bad = flat(4, 4);
  bad.z.resize(15);
  EXPECT_FALSE(e.setHeightfield(bad).empty());
  EXPECT_TRUE(e.empty());
  // block size below 2 is refused too (Engine.h: >= 2)
  EXPECT_FALSE(e.setHeightfield(flat(9, 9), 1).empty());
  EXPECT_TRUE(e.empty());
  EXPECT_FALSE(e.setHeightfield(flat(9, 9), 0).empty());
  EXPECT_TRUE(e.empty());
  // a good one, then a bad one empties the engine
  EXPECT_TRUE(e.setHeightfield(flat(9, 9), 4).empty());
  EXPECT_FALSE(e.empty());
  EXPECT_FALSE(e.setHeightfield(flat(0, 9)).empty());
  EXPECT_TRUE(e.empty());
  // an empty engine survives frames
  gmm::View v;
  v.eye = { 4, -10, 5 };
  const gmm::FrameStats& s = e.update(v, 1.0);
  EXPECT_EQ(s.triangles, 0u);
  EXPECT_TRUE(e.indices().empty());
  EXPECT_EQ(e.updateForError(0.0).triangles, 0u);
}

TEST(Heightfield, InfinitiesBecomeNodata)
{
  gmm::Heightfield hf = flat(4, 3);
  hf.z[1] = std::numeric_limits<float>::infinity();
  hf.z[5] = -std::numeric_limits<float>::infinity();
  hf.z[7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(gmm::infinitiesToNodata(hf), 2u);
  EXPECT_TRUE(std::isnan(hf.z[1]));
  EXPECT_TRUE(std::isnan(hf.z[5]));
  EXPECT_TRUE(std::isnan(hf.z[7]));
  for (int k : { 0, 2, 3, 4, 6, 8, 9, 10, 11 })
    EXPECT_EQ(hf.z[k], 1.0f);
  EXPECT_EQ(gmm::infinitiesToNodata(hf), 0u);
}

// Heightfield.h: "+-Inf is treated as nodata too": the engine must never emit a triangle
// that references an infinite sample.
TEST(Heightfield, EngineTreatsInfinityAsNodata)
{
  gmm::Heightfield hf = flat(9, 9);
  const int infAt = 4 * 9 + 4, negInfAt = 1 * 9 + 7;
  hf.z[infAt] = std::numeric_limits<float>::infinity();
  hf.z[negInfAt] = -std::numeric_limits<float>::infinity();
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 4), "");
  for (int pass = 0; pass < 2; ++pass)
  {
    if (pass == 0)
      e.updateForError(0.0);
    else
    {
      gmm::View v;
      v.eye = { 4, -20, 20 };
      v.forward = { 0, 1, -0.5 };
      e.update(v, 1.0);
    }
    EXPECT_GT(e.indices().size(), 0u);
    for (uint32_t k : e.indices())
    {
      EXPECT_NE(k, static_cast<uint32_t>(infAt));
      EXPECT_NE(k, static_cast<uint32_t>(negInfAt));
    }
    for (uint32_t k : e.indices())
      ASSERT_TRUE(std::isfinite(e.heightfield().z[k]));
  }
}

// The scans of the samples run on several threads in chunks of 2^20 samples: whatever the
// thread count, the message names the first offending sample, an infinity in any chunk is
// found (and only there), and the quadtree's boxes are the one-thread boxes.
TEST(Heightfield, ParallelScansAgreeWithOneThread)
{
  const int nx = 1500, ny = 2100; // 3.15 M samples: 4 chunks
  gmm::Heightfield hf = flat(nx, ny);
  for (std::size_t k = 0; k < hf.z.size(); ++k)
    hf.z[k] = static_cast<float>((k * 2654435761u) % 1000) * 0.5f;
  hf.z[3 * nx + 5] = std::numeric_limits<float>::quiet_NaN();
  const std::string clean = gmm::validateHeightfield(hf, 1);
  EXPECT_EQ(clean, "");
  for (int threads : { 0, 2, 3 })
    EXPECT_EQ(gmm::validateHeightfield(hf, threads), clean) << threads << " threads";

  // Two offenders in different chunks; the later one is found by another thread first
  // unless the smallest index is kept.
  gmm::Heightfield bad = hf;
  bad.z[2900000] = 3e38f;
  bad.z[1200000] = -2e38f;
  const std::string first = gmm::validateHeightfield(bad, 1);
  EXPECT_NE(first.find("sample (" + std::to_string(1200000 % nx) + ", " + std::to_string(1200000 / nx) + ")"),
    std::string::npos) << first;
  for (int threads : { 0, 2, 3, 4 })
    EXPECT_EQ(gmm::validateHeightfield(bad, threads), first) << threads << " threads";

  // An infinity only in the last chunk, heights held externally: copied, then replaced.
  std::vector<float> external = hf.z;
  external[3100000] = std::numeric_limits<float>::infinity();
  gmm::Heightfield ext = hf;
  ext.z.clear();
  ext.external = external.data();
  EXPECT_EQ(gmm::infinitiesToNodata(ext, 2), 1u);
  EXPECT_EQ(ext.external, nullptr);
  EXPECT_TRUE(std::isnan(ext.z[3100000]));
  EXPECT_TRUE(std::isinf(external[3100000])) << "external heights must never be written";
  gmm::Heightfield none = hf;
  EXPECT_EQ(gmm::infinitiesToNodata(none, 0), 0u);

  const gmm::Quadtree one = gmm::buildQuadtree(hf, 32, 1);
  for (int threads : { 0, 2, 3 })
  {
    const gmm::Quadtree many = gmm::buildQuadtree(hf, 32, threads);
    ASSERT_EQ(many.blockBox.size(), one.blockBox.size());
    for (std::size_t b = 0; b < one.blockBox.size(); ++b)
    {
      ASSERT_EQ(many.blockBox[b].lo, one.blockBox[b].lo) << "block " << b;
      ASSERT_EQ(many.blockBox[b].hi, one.blockBox[b].hi) << "block " << b;
    }
    EXPECT_EQ(many.blockHasNodata, one.blockHasNodata);
    EXPECT_EQ(many.nodes.size(), one.nodes.size());
  }
}

TEST(Heightfield, SampleSlopeByHand)
{
  // 4 x 3 samples, spacing 2 (x) and 0.5 (y). Heights 3 i + 10 j except a quadratic bump at
  // (1, 1) and nodata at (2, 2).
  gmm::Heightfield hf;
  hf.nx = 4;
  hf.ny = 3;
  hf.dx = 2.0;
  hf.dy = 0.5;
  for (int j = 0; j < hf.ny; ++j)
  {
    for (int i = 0; i < hf.nx; ++i)
    {
      hf.z.push_back(static_cast<float>(3 * i + 10 * j));
    }
  }
  hf.z[hf.index(1, 1)] = 20.0f; // was 13
  hf.z[hf.index(2, 2)] = std::numeric_limits<float>::quiet_NaN();
  // Central: (h(2, 0) - h(0, 0)) / (2 dx) = 6 / 4; along y at (0, 1): (20 - 0) / (2 dy) = 20.
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 1, 0, true), 1.5);
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 0, 1, false), 20.0);
  // The bump's own slopes do not use its height: (16 - 10) / 4 and (23 - 3) / 1.
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 1, 1, true), 1.5);
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 1, 1, false), 20.0);
  // Borders: one-sided. (3 - 0) / 2 at (0, 0); (9 - 6) / 2 at (3, 0); (29 - 19) / 0.5 at
  // (3, 2) along y.
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 0, 0, true), 1.5);
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 3, 0, true), 1.5);
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 3, 2, false), 20.0);
  // Beside nodata: one-sided away from it. At (2, 1) along y: (16 - 6) / 0.5; at (1, 2)
  // along x: (23 - 20) / 2, away from the nodata at (2, 2).
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 2, 1, false), 20.0);
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 1, 2, true), 1.5);
  // Nodata itself with valid neighbours: their central difference, (29 - 23) / 4.
  EXPECT_DOUBLE_EQ(gmm::sampleSlope(hf, 2, 2, true), 1.5);
  // Neither neighbour valid, the sample itself nodata: 0 (a 2 x 2 of nodata but one).
  gmm::Heightfield holes;
  holes.nx = holes.ny = 2;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  holes.z = { nan, 1.0f, nan, nan };
  EXPECT_EQ(gmm::sampleSlope(holes, 0, 0, true), 0.0);
  EXPECT_EQ(gmm::sampleSlope(holes, 0, 0, false), 0.0);
  EXPECT_EQ(gmm::sampleSlope(holes, 1, 1, false), 0.0);
}
