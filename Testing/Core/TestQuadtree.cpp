// Quadtree bands, leaves and boxes (Quadtree.h), and the level rules (Levels.h) checked
// against a restatement of the header's rules.
#include "CoreTestUtil.h"
#include "Levels.h"
#include "Quadtree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace gmmtest;

TEST(Quadtree, SplitBandsCoverAndRespectMax)
{
  for (int maxQ = 2; maxQ <= 70; ++maxQ)
    for (int q = 1; q <= 600; ++q)
    {
      std::vector<int> b = gmm::splitBands(q, maxQ);
      ASSERT_GE(b.size(), 2u);
      EXPECT_EQ(b.front(), 0);
      EXPECT_EQ(b.back(), q);
      for (std::size_t k = 0; k + 1 < b.size(); ++k)
      {
        EXPECT_GT(b[k + 1], b[k]) << "q=" << q << " max=" << maxQ;
        EXPECT_LE(b[k + 1] - b[k], maxQ) << "q=" << q << " max=" << maxQ;
      }
      // bands of a power of two quads from the DEM's first sample, the remainder after
      // them; every band starts on an even sample
      ASSERT_EQ(b, refSplitBands(q, maxQ)) << "q=" << q << " max=" << maxQ;
      for (std::size_t k = 0; k + 1 < b.size(); ++k)
        EXPECT_EQ(b[k] % 2, 0) << "q=" << q << " max=" << maxQ;
    }
  EXPECT_EQ(gmm::splitBands(64, 64), (std::vector<int>{ 0, 64 }));
  EXPECT_EQ(gmm::splitBands(65, 64), (std::vector<int>{ 0, 32, 65 })) << "one quad left joins the band before";
  EXPECT_EQ(gmm::splitBands(129, 64), (std::vector<int>{ 0, 32, 64, 96, 129 }));
  EXPECT_EQ(gmm::splitBands(7, 3), (std::vector<int>{ 0, 2, 4, 7 }));
  EXPECT_EQ(gmm::splitBands(33, 33), (std::vector<int>{ 0, 33 }));
  EXPECT_EQ(gmm::splitBands(70, 33), (std::vector<int>{ 0, 16, 32, 48, 64, 70 })) << "70 / 4 = 17.5: 16";
  EXPECT_EQ(gmm::splitBands(4096, 32).size(), 129u) << "a 4097^2 DEM: blocks of 32";
  EXPECT_EQ(gmm::splitBands(66, 32), (std::vector<int>{ 0, 16, 32, 48, 64, 66 }));
  // 33 quads at block 16: halving would reach 8.25, so bands of 8, the one quad left
  // joining the last (9 quads, within the maximum)
  EXPECT_EQ(gmm::splitBands(33, 16), (std::vector<int>{ 0, 8, 16, 24, 33 }));
  EXPECT_EQ(gmm::bandWidth(4096, 32), 32);
  EXPECT_EQ(gmm::bandWidth(4095, 32), 16);
  EXPECT_EQ(gmm::bandWidth(3600, 32), 16) << "3600 / 128 = 28.1";
  EXPECT_EQ(gmm::bandWidth(20, 32), 20) << "within the maximum: one band";
  // An SRTM3 tile's 1200 quads: halving would reach 18.75, so 75 blocks of 16.
  const std::vector<int> srtm3 = gmm::splitBands(1200, 32);
  ASSERT_EQ(srtm3.size(), 76u);
  EXPECT_EQ(std::vector<int>(srtm3.begin(), srtm3.begin() + 4), (std::vector<int>{ 0, 16, 32, 48 }));
  EXPECT_EQ(srtm3.back(), 1200);
}

namespace
{
bool boxContains(const gmm::Box& outer, const gmm::Box& inner)
{
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
    outer.hi.x >= inner.hi.x && outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}
bool boxContainsPoint(const gmm::Box& b, double x, double y, double z)
{
  return b.lo.x <= x && x <= b.hi.x && b.lo.y <= y && y <= b.hi.y && b.lo.z <= z && z <= b.hi.z;
}

void checkTree(const gmm::Heightfield& hf, int maxQ)
{
  SCOPED_TRACE(std::to_string(hf.nx) + "x" + std::to_string(hf.ny) + " max " +
    std::to_string(maxQ) + " dx " + std::to_string(hf.dx) + " dy " + std::to_string(hf.dy));
  gmm::Quadtree qt = gmm::buildQuadtree(hf, maxQ);
  // Quadtree.h: a block size below 4 is raised to 4 (no 1-quad band inside a wider DEM)
  const int effMax = std::max(4, maxQ);
  // nodata along a border takes its own band (the collar rule is checked by hand in
  // NodataCollarBandsByHand)
  const gmm::NodataCollar c = gmm::nodataCollar(hf, effMax);
  ASSERT_EQ(qt.colStart, refSplitBands(hf.nx - 1, effMax, c.west, c.east));
  ASSERT_EQ(qt.rowStart, refSplitBands(hf.ny - 1, effMax, c.south, c.north));
  for (std::size_t k = 0; k + 1 < qt.colStart.size(); ++k)
    EXPECT_TRUE(qt.colStart[k + 1] - qt.colStart[k] >= 2 || hf.nx == 2) << "1-quad column band";
  for (std::size_t k = 0; k + 1 < qt.rowStart.size(); ++k)
    EXPECT_TRUE(qt.rowStart[k + 1] - qt.rowStart[k] >= 2 || hf.ny == 2) << "1-quad row band";
  ASSERT_EQ(qt.blockCols + 1, static_cast<int>(qt.colStart.size()));
  ASSERT_EQ(qt.blockRows + 1, static_cast<int>(qt.rowStart.size()));
  ASSERT_EQ(static_cast<int>(qt.blockBox.size()), qt.blockCount());
  ASSERT_EQ(static_cast<int>(qt.blockHasNodata.size()), qt.blockCount());
  ASSERT_FALSE(qt.nodes.empty());

  // every block: its box contains its samples (borders included), z tight over valid ones
  for (int r = 0; r < qt.blockRows; ++r)
    for (int c = 0; c < qt.blockCols; ++c)
    {
      const int b = qt.blockIndex(c, r);
      // The per-block sizes every frame reads, against the bands they come from.
      ASSERT_EQ(qt.blockWidth(b), qt.colStart[c + 1] - qt.colStart[c]);
      ASSERT_EQ(qt.blockHeight(b), qt.rowStart[r + 1] - qt.rowStart[r]);
      // And the level rules looked up per block, against the shape rules themselves.
      ASSERT_EQ(qt.blockTopLevel(b), gmm::topLevel(qt.blockWidth(b), qt.blockHeight(b)));
      for (int m = -1; m <= 32; ++m)
      {
        ASSERT_EQ(qt.blockIsRingAt(b, m),
          gmm::blockShape(qt.blockWidth(b), qt.blockHeight(b), m) == gmm::BlockShape::Ring)
          << "block " << b << ", level " << m;
      }
      const gmm::Box& box = qt.blockBox[b];
      bool anyNaN = false;
      double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
      for (int j = qt.rowStart[r]; j <= qt.rowStart[r + 1]; ++j)
        for (int i = qt.colStart[c]; i <= qt.colStart[c + 1]; ++i)
        {
          const float z = hf.height(i, j);
          const double x = hf.worldX(i), y = hf.worldY(j);
          EXPECT_TRUE(box.lo.x <= x && x <= box.hi.x && box.lo.y <= y && y <= box.hi.y)
            << "block " << b << " sample " << i << "," << j;
          if (std::isnan(z))
          {
            anyNaN = true;
            continue;
          }
          zlo = std::min(zlo, double(z));
          zhi = std::max(zhi, double(z));
          EXPECT_TRUE(boxContainsPoint(box, x, y, z)) << "block " << b << " sample " << i << "," << j;
        }
      EXPECT_EQ(qt.blockHasNodata[b] != 0, anyNaN) << "block " << b;
      if (zlo <= zhi)
      {
        EXPECT_EQ(box.lo.z, zlo) << "block " << b << " box z not tight";
        EXPECT_EQ(box.hi.z, zhi) << "block " << b << " box z not tight";
      }
    }

  // nodes: each leaf names one block, each block has exactly one leaf, parents contain children
  std::vector<int> leafOf(qt.blockCount(), 0);
  std::vector<int> parentCount(qt.nodes.size(), 0);
  for (std::size_t n = 0; n < qt.nodes.size(); ++n)
  {
    const gmm::QuadtreeNode& node = qt.nodes[n];
    if (node.childCount == 0)
    {
      ASSERT_GE(node.block, 0);
      ASSERT_LT(node.block, qt.blockCount());
      ++leafOf[node.block];
      EXPECT_TRUE(boxContains(node.box, qt.blockBox[node.block])) << "leaf " << n;
      continue;
    }
    ASSERT_GT(node.firstChild, static_cast<int>(n));
    ASSERT_LE(node.firstChild + node.childCount, static_cast<int>(qt.nodes.size()));
    for (int k = 0; k < node.childCount; ++k)
    {
      ++parentCount[node.firstChild + k];
      EXPECT_TRUE(boxContains(node.box, qt.nodes[node.firstChild + k].box))
        << "node " << n << " child " << node.firstChild + k;
    }
  }
  for (int b = 0; b < qt.blockCount(); ++b)
    EXPECT_EQ(leafOf[b], 1) << "block " << b;
  EXPECT_EQ(parentCount[0], 0);
  for (std::size_t n = 1; n < qt.nodes.size(); ++n)
    EXPECT_EQ(parentCount[n], 1) << "node " << n;
}
} // namespace

TEST(Quadtree, LeavesTileAndBoxesContain)
{
  Rng rng(7);
  const int sizes[][2] = { { 2, 2 }, { 2, 40 }, { 40, 2 }, { 3, 3 }, { 65, 65 }, { 66, 67 },
    { 131, 17 }, { 300, 211 }, { 97, 101 } };
  for (auto& s : sizes)
    for (int maxQ : { 2, 3, 4, 7, 16, 64, 1000 })
    {
      gmm::Heightfield hf = roughTerrain(s[0], s[1], rng, 5.0, 7.0);
      checkTree(hf, maxQ);
      hf.dx = -hf.dx;
      checkTree(hf, maxQ);
      hf.dy = -3.0;
      // sprinkle some nodata
      for (int k = 0; k < 5; ++k)
        hf.z[randInt(rng, 0, static_cast<int>(hf.z.size()) - 1)] =
          std::numeric_limits<float>::quiet_NaN();
      checkTree(hf, maxQ);
    }
}

TEST(Quadtree, TinyAndOversizedBlocks)
{
  Rng rng(3);
  gmm::Heightfield hf = roughTerrain(2, 2, rng);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 64);
  EXPECT_EQ(qt.blockCount(), 1);
  EXPECT_EQ(qt.colStart, (std::vector<int>{ 0, 1 }));
  EXPECT_EQ(qt.rowStart, (std::vector<int>{ 0, 1 }));
  hf = roughTerrain(50, 33, rng);
  qt = gmm::buildQuadtree(hf, 64);
  EXPECT_EQ(qt.blockCount(), 1);
  EXPECT_EQ(qt.colStart, (std::vector<int>{ 0, 49 }));
  EXPECT_EQ(qt.rowStart, (std::vector<int>{ 0, 32 }));
}

TEST(Levels, ShapesAndTopLevelMatchRules)
{
  for (int w = 1; w <= 80; ++w)
    for (int h = 1; h <= 80; ++h)
    {
      EXPECT_EQ(gmm::topLevel(w, h), refTopLevel(w, h)) << w << "x" << h;
      for (int m = 0; m <= refTopLevel(w, h) + 1; ++m)
      {
        const long long s = 1LL << m;
        gmm::BlockShape expect = gmm::BlockShape::Invalid;
        if (s < w && s < h)
          expect = gmm::BlockShape::Ring;
        else if (s >= w && s >= h)
          expect = gmm::BlockShape::OneQuad;
        else if (m == 0 && (w == 1 || h == 1))
          expect = gmm::BlockShape::Thin;
        if (m > refTopLevel(w, h))
          continue; // above the top level: not specified
        EXPECT_EQ(gmm::blockShape(w, h, m), expect) << w << "x" << h << " level " << m;
      }
    }
  // topLevel has no loop (ceilLog2): around every power of two an int side reaches.
  for (int k = 1; k <= 30; ++k)
    for (int d : { -1, 0, 1 })
    {
      const int side = (1 << k) + d;
      EXPECT_EQ(gmm::topLevel(side, 1), refTopLevel(side, 1)) << side;
      EXPECT_EQ(gmm::topLevel(3, side), refTopLevel(3, side)) << side;
    }
  EXPECT_EQ(gmm::topLevel(0, 0), 0);
}

TEST(Levels, EdgeSamples)
{
  std::vector<int> out;
  for (int first = 0; first < 5; ++first)
    for (int len = 1; len <= 70; ++len)
      for (int m = 0; m <= 8; ++m)
      {
        const int last = first + len;
        std::vector<int> expect;
        for (int k = first; k < last; k += (1 << m))
          expect.push_back(k);
        expect.push_back(last);
        out.clear();
        gmm::edgeSamples(first, last, m, out);
        EXPECT_EQ(out, expect) << first << ".." << last << " level " << m;
        EXPECT_EQ(gmm::edgeSampleCount(first, last, m), static_cast<int>(expect.size()));
      }
}

TEST(Quadtree, UpperHalfBandsByHand)
{
  // [0, 5) splits at 4 (the largest power of two below 5); [0, 4) at 2; [0, 2) at 1 and
  // [2, 4) at 3.
  EXPECT_EQ(gmm::upperHalfBands(5), (std::vector<uint8_t>{ 0, 1, 0, 1, 1 }));
  // [0, 7) at 4, [4, 7) at 6, [4, 6) at 5.
  EXPECT_EQ(gmm::upperHalfBands(7), (std::vector<uint8_t>{ 0, 1, 0, 1, 0, 1, 1 }));
  EXPECT_EQ(gmm::upperHalfBands(4), (std::vector<uint8_t>{ 0, 1, 0, 1 }));
  EXPECT_EQ(gmm::upperHalfBands(1), (std::vector<uint8_t>{ 0 }));
  EXPECT_TRUE(gmm::upperHalfBands(0).empty());
}

TEST(Quadtree, NodataCollarBandsByHand)
{
  // splitBands with collars: the collars first (3 quads at the high end would start on
  // sample 97: widened to 4), the quads between in bands as without them, from the low
  // collar's end (84 -> 5 x 16 + 4; 98 -> 6 x 16 + 2).
  EXPECT_EQ(gmm::splitBands(100, 32, 12, 3), (std::vector<int>{ 0, 12, 28, 44, 60, 76, 92, 96, 100 }));
  EXPECT_EQ(gmm::splitBands(100, 32, 0, 2), (std::vector<int>{ 0, 16, 32, 48, 64, 80, 96, 98, 100 }));
  EXPECT_EQ(gmm::splitBands(10, 32, 4, 4), (std::vector<int>{ 0, 10 })) << "under 4 quads left";

  // A 101 x 81 plane with nodata wedges: row j starts with j % 12 nodata samples (widest
  // 11) and ends with 1; column i starts with (i % 3) nodata samples from the south; the
  // north has none (the west wedge's first columns, seen from the north, lie in the west
  // collar and do not count). Row 40 is all nodata and column 50 holds a void of 30 samples from the
  // north border: lines no thin band isolates, which the collars must ignore.
  gmm::Heightfield hf;
  hf.nx = 101;
  hf.ny = 81;
  hf.z.assign(static_cast<std::size_t>(hf.nx) * hf.ny, 5.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int j = 0; j < hf.ny; ++j)
  {
    for (int i = 0; i < j % 12; ++i)
      hf.z[hf.index(i, j)] = nan;
    hf.z[hf.index(hf.nx - 1, j)] = nan;
  }
  for (int i = 0; i < hf.nx; ++i)
    for (int j = 0; j < i % 3; ++j)
      hf.z[hf.index(i, j)] = nan;
  for (int i = 0; i < hf.nx; ++i)
    hf.z[hf.index(i, 40)] = nan;
  for (int j = hf.ny - 30; j < hf.ny; ++j)
    hf.z[hf.index(50, j)] = nan;

  // A collar is one more than the longest run shorter than the block size less 4.
  const gmm::NodataCollar c = gmm::nodataCollar(hf, 32);
  EXPECT_EQ(c.west, 12);
  EXPECT_EQ(c.east, 2);
  EXPECT_EQ(c.south, 3);
  EXPECT_EQ(c.north, 0);
  EXPECT_EQ(gmm::nodataCollar(hf, 12).west, 8) << "at block 12 only runs up to 7 count";
  EXPECT_EQ(gmm::nodataCollar(hf, 4).west, 0) << "the smallest block has no collars";

  // Columns: 86 quads between the collars, 5 x 16 + 6. Rows: the south collar of 3
  // widened to 4, then 76 quads, 4 x 16 + 12.
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 32);
  EXPECT_EQ(qt.colStart, (std::vector<int>{ 0, 12, 28, 44, 60, 76, 92, 98, 100 }));
  EXPECT_EQ(qt.rowStart, (std::vector<int>{ 0, 4, 20, 36, 52, 68, 80 }));
  // The wedges lie in the collar bands, with a valid line between them and the inner
  // blocks: scanned here from the heights, the inner blocks' nodata, and that of the
  // collar bands' last line but one, is row 40's and column 50's only.
  for (int r = 1; r + 1 < qt.blockRows; ++r)
    for (int cc = 1; cc + 1 < qt.blockCols; ++cc)
    {
      bool nodata = false;
      const int r0 = qt.rowStart[r] - (r == 1), r1 = qt.rowStart[r + 1] + (r + 2 == qt.blockRows);
      const int c0 = qt.colStart[cc] - (cc == 1), c1 = qt.colStart[cc + 1] + (cc + 2 == qt.blockCols);
      for (int j = r0; j <= r1; ++j)
        for (int i = c0; i <= c1; ++i)
          nodata |= std::isnan(hf.height(i, j)) && j != 40 && i != 50;
      EXPECT_FALSE(nodata) << "block column " << cc << " row " << r;
    }
}
