// The error table's fast paths against the general rasteriser they replace, and its
// independence from the thread count. (The table's values themselves are checked against
// an independent measure in TestErrorCertification, TestViewIndependent and TestHandChecked.)
#include "CoreTestUtil.h"
#include "ErrorTable.h"
#include "RasterError.h"
#include "Levels.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

using namespace gmmtest;

namespace
{

// Rasterises the inner grid exactly as emitted and compares the direct walk with it.
void expectInnerAreasMatch(const gmm::Heightfield& hf, int maxBlockQuads, int& compared)
{
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, maxBlockQuads);
  gmm::EmitScratch scratch;
  std::vector<gmm::GridTriangle> tris;
  std::vector<int> C, R;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    for (int m = 1; m <= gmm::topLevel(w, h); ++m)
    {
      if (gmm::blockShape(w, h, m) != gmm::BlockShape::Ring)
        continue;
      gmm::BlockConfig cfg;
      cfg.level = m;
      cfg.edgeLevel = { m, m, m, m };
      tris.clear();
      gmm::emitBlockGrid(qt, b, cfg, gmm::BlockPart::Inner, tris, scratch);
      const int c = b % qt.blockCols, r = b / qt.blockCols;
      gmm::edgeSamples(qt.colStart[c], qt.colStart[c + 1], m, C);
      gmm::edgeSamples(qt.rowStart[r], qt.rowStart[r + 1], m, R);
      const float fast = gmm::innerAreaError(hf, C, R);
      const float reference = gmm::trianglesError(hf, tris, true);
      // Bit-identical: the same integers and the same operations per sample; a sample on a
      // cell border is evaluated by one cell instead of two, which interpolate alike.
      ASSERT_EQ(fast, reference) << "block " << b << " (" << w << "x" << h << ") level " << m
                                 << ", " << hf.nx << "x" << hf.ny;
      ++compared;
    }
  }
}

} // namespace

TEST(ErrorTable, InnerAreaWalkEqualsRasterisedInnerGrid)
{
  Rng rng(20261130);
  int compared = 0;
  for (int k = 0; k < 60; ++k)
  {
    const int nx = randInt(rng, 5, 160), ny = randInt(rng, 5, 160);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, randReal(rng, 0.5, 50.0), randReal(rng, 0.5, 50.0));
    if (k % 4 == 1)
      hf.dx = -hf.dx; // mirrored: the emitter keeps grid order, the error must not care
    if (k % 5 == 2)
      for (float& z : hf.z)
        z = std::round(z / 50.0f) * 50.0f; // plateaus and cliffs: exact zeros and large steps
    expectInnerAreasMatch(hf, 4 << randInt(rng, 0, 5), compared);
  }
  EXPECT_GT(compared, 500);
}

TEST(ErrorTable, InnerAreaSeesNodata)
{
  Rng rng(7);
  gmm::Heightfield hf = roughTerrain(40, 40, rng);
  hf.z[hf.index(17, 23)] = std::numeric_limits<float>::quiet_NaN(); // inside the inner grid
  std::vector<int> C, R;
  gmm::edgeSamples(0, 39, 2, C);
  gmm::edgeSamples(0, 39, 2, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
  gmm::edgeSamples(0, 39, 1, C);
  gmm::edgeSamples(0, 39, 1, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
  // A corner of a cell (sample 20, 24 is a vertex at level 2).
  hf.z[hf.index(17, 23)] = 1.0f;
  hf.z[hf.index(20, 24)] = std::numeric_limits<float>::quiet_NaN();
  gmm::edgeSamples(0, 39, 2, C);
  gmm::edgeSamples(0, 39, 2, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
}

TEST(ErrorTable, SameTableWithAnyThreadCount)
{
  Rng rng(11);
  gmm::Heightfield hf = roughTerrain(301, 173, rng);
  hf.z[hf.index(100, 50)] = std::numeric_limits<float>::quiet_NaN();
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  const gmm::ErrorTable one = gmm::buildErrorTable(hf, qt, 1);
  for (int threads : { 2, 3, 7 })
  {
    const gmm::ErrorTable t = gmm::buildErrorTable(hf, qt, threads);
    EXPECT_EQ(t.levels, one.levels);
    EXPECT_TRUE(t.ownError == one.ownError) << threads << " threads";
    EXPECT_TRUE(t.ownErrorExact == one.ownErrorExact) << threads << " threads";
    EXPECT_TRUE(t.stripError == one.stripError) << threads << " threads";
  }
}

namespace
{
// Independent of the engine's rasteriser: every sample of the triangle's box tested with
// cross products, the surface from the plane through the three vertices, in long double.
// sawNodata, when given, is set when a covered sample is nodata.
// A block side whose vertices are drawn on a coarser polyline (a glided edge): row j = line
// (rows) or column i = line, the polyline through that line's samples first, first + 2^level,
// ..., last; its height at a sample by hand (long double).
struct GlideLine
{
  bool rows = true;
  int line = -1, first = 0, last = 0, level = 0;
  long double at(const gmm::Heightfield& hf, const gmm::GridPoint& p) const
  {
    const int s = rows ? p.i : p.j;
    auto h = [&](int k) { return static_cast<long double>(rows ? hf.height(k, line) : hf.height(line, k)); };
    const int step = 1 << level, lo = first + (s - first) / step * step, hi = std::min(lo + step, last);
    return lo == s ? h(s) : h(lo) + (h(hi) - h(lo)) * (s - lo) / static_cast<long double>(hi - lo);
  }
  bool on(const gmm::GridPoint& p) const { return line >= 0 && (rows ? p.j == line : p.i == line); }
};

double bruteTriangleError(const gmm::Heightfield& hf, const gmm::GridTriangle& t, bool* sawNodata = nullptr,
  const GlideLine& glide = GlideLine())
{
  const auto& a = t.v[0];
  const auto& b = t.v[1];
  const auto& c = t.v[2];
  auto vertex = [&](const gmm::GridPoint& p) {
    return glide.on(p) ? glide.at(hf, p) : static_cast<long double>(hf.height(p.i, p.j));
  };
  const long double za = vertex(a), zb = vertex(b), zc = vertex(c);
  const long long area = static_cast<long long>(b.i - a.i) * (c.j - a.j) - static_cast<long long>(b.j - a.j) * (c.i - a.i);
  double worst = 0.0;
  for (int j = std::min({ a.j, b.j, c.j }); j <= std::max({ a.j, b.j, c.j }); ++j)
    for (int i = std::min({ a.i, b.i, c.i }); i <= std::max({ a.i, b.i, c.i }); ++i)
    {
      auto cross = [&](const gmm::GridPoint& p, const gmm::GridPoint& q) {
        return static_cast<long long>(q.i - p.i) * (j - p.j) - static_cast<long long>(q.j - p.j) * (i - p.i);
      };
      const long long e0 = cross(a, b), e1 = cross(b, c), e2 = cross(c, a);
      const bool inside = area > 0 ? (e0 >= 0 && e1 >= 0 && e2 >= 0) : (e0 <= 0 && e1 <= 0 && e2 <= 0);
      if (!inside)
        continue;
      if (sawNodata && std::isnan(hf.height(i, j)))
        *sawNodata = true;
      // Barycentric weights of b and c: e2 / area and e0 / area.
      const long double surface = za + (zb - za) * e2 / area + (zc - za) * e0 / area;
      worst = std::max(worst, static_cast<double>(std::fabs(hf.height(i, j) - surface)));
    }
  return worst;
}
} // namespace

namespace
{
// The edge levels that side `side` of block b at level m is drawn with (blockConfigOf) over
// every state of the block across it: not drawn, covered by a merged node, or at any of
// its levels. Sorted.
std::vector<int> possibleEdges(const gmm::Quadtree& qt, int b, int m, int side)
{
  std::vector<int8_t> levels(static_cast<std::size_t>(qt.blockCount()), -1);
  levels[b] = static_cast<int8_t>(m);
  const int nb = qt.blockNeighbours(b)[side];
  std::vector<int> states{ -1 };
  if (nb >= 0)
  {
    states.push_back(gmm::kCoveredLevel);
    for (int l = 0; l <= gmm::topLevel(qt.blockWidth(nb), qt.blockHeight(nb)); ++l)
      if (gmm::blockShape(qt.blockWidth(nb), qt.blockHeight(nb), l) != gmm::BlockShape::Invalid)
        states.push_back(l);
  }
  std::vector<int> out;
  for (int l : states)
  {
    if (nb >= 0)
      levels[nb] = static_cast<int8_t>(l);
    const int e = gmm::blockConfigOf(qt, levels, b).edgeLevel[side];
    if (std::find(out.begin(), out.end(), e) == out.end())
      out.push_back(e);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The own edges of block b at level m: m, or every sample (0) on a side that is never
// drawn at m there (beside nodata, Quadtree::sideAtFullResolutionAt).
std::array<int, 4> ownEdges(const gmm::Quadtree& qt, int b, int m)
{
  std::array<int, 4> e{};
  for (int side = 0; side < 4; ++side)
  {
    const std::vector<int> edges = possibleEdges(qt, b, m, side);
    e[side] = std::find(edges.begin(), edges.end(), m) != edges.end() ? m : 0;
  }
  return e;
}

// The triangles of one side strip of block b at level m whose edge is sampled at level n
// (the other edges its own), replacing `tris`; with `glided`, the edge's samples at m drawn
// on its polyline at n instead (BlockConfig::sampleLevel: a coarser block across).
void emitStrip(const gmm::Quadtree& qt, int b, int m, int side, int n,
  std::vector<gmm::GridTriangle>& tris, gmm::EmitScratch& scratch, bool glided = false)
{
  gmm::BlockConfig cfg;
  cfg.level = m;
  cfg.edgeLevel = ownEdges(qt, b, m);
  cfg.edgeLevel[side] = n;
  cfg.sampleLevel[side] = glided && n > m ? m : -1;
  tris.clear();
  gmm::emitBlockGrid(qt, b, cfg, static_cast<gmm::BlockPart>(static_cast<int>(gmm::BlockPart::StripSouth) + side),
    tris, scratch);
}
} // namespace

TEST(ErrorTable, StripAndFanErrorsEqualBruteForce)
{
  // Every side strip at every level towards every coarser edge level, on blocks whose
  // sides the steps divide and do not (spans walked by shifts, and the box-scan fallback).
  Rng rng(99);
  int compared = 0;
  for (int k = 0; k < 12; ++k)
  {
    const int nx = randInt(rng, 20, 140), ny = randInt(rng, 20, 140);
    const gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, 8 << randInt(rng, 0, 3));
    gmm::EmitScratch scratch;
    std::vector<gmm::GridTriangle> tris;
    for (int bIndex = 0; bIndex < qt.blockCount(); bIndex += 1 + qt.blockCount() / 6)
    {
      const int w = qt.blockWidth(bIndex), h = qt.blockHeight(bIndex), top = gmm::topLevel(w, h);
      for (int m = 0; m <= top; ++m)
      {
        if (gmm::blockShape(w, h, m) != gmm::BlockShape::Ring)
          continue;
        for (int side = 0; side < 4; ++side)
          for (int n = m; n <= top; ++n)
          {
            emitStrip(qt, bIndex, m, side, n, tris, scratch);
            for (const gmm::GridTriangle& t : tris)
            {
              const double brute = bruteTriangleError(hf, t);
              const double got = gmm::trianglesError(hf, { t }, true);
              // Rounded up to float, never below the exact value by more than rounding.
              ASSERT_GE(got, brute * (1 - 1e-12)) << "block " << bIndex << " m " << m << " n " << n << " side " << side;
              ASSERT_LE(got, brute * (1 + 1e-6) + 1e-9) << "block " << bIndex << " m " << m << " n " << n << " side " << side;
              ++compared;
            }
          }
      }
    }
  }
  EXPECT_GT(compared, 1000);
}

// The table's strip and own entries against the brute force over the very triangles
// Tessellate emits: every side strip of every ring level towards every coarser edge level
// (made monotone in the edge level, as the table documents) and every block's error with
// its own edges (every sample on a side beside nodata). A block with nodata is drawn cell
// by cell at its coarse levels (HoleCells.h): its error then skips only the triangles that
// touch nodata, which full resolution drops too. The table measures a strip's samples on
// its two lines as polylines and rasterises only the rows between them; this checks that
// nothing is lost by it, on blocks whose sides the steps divide and do not.
TEST(ErrorTable, StripAndOwnEntriesEqualBruteForceOverTheirTriangles)
{
  Rng rng(4242);
  int compared = 0, withNodata = 0;
  // Brute force with nodata: +inf when a covered sample (vertices included) is nodata.
  auto bruteStrict = [](const gmm::Heightfield& hf, const std::vector<gmm::GridTriangle>& tris,
                       const GlideLine& glide = GlideLine()) {
    double worst = 0.0;
    for (const gmm::GridTriangle& t : tris)
    {
      bool nodata = false;
      const double e = bruteTriangleError(hf, t, &nodata, glide);
      if (nodata)
        return static_cast<double>(INFINITY);
      worst = std::max(worst, e);
    }
    return worst;
  };
  // Without nodata's holes: triangles touching nodata count nothing.
  auto bruteHoles = [](const gmm::Heightfield& hf, const std::vector<gmm::GridTriangle>& tris) {
    double worst = 0.0;
    for (const gmm::GridTriangle& t : tris)
    {
      bool nodata = false;
      const double e = bruteTriangleError(hf, t, &nodata);
      if (!nodata)
        worst = std::max(worst, e);
    }
    return worst;
  };
  for (int k = 0; k < 14; ++k)
  {
    const int nx = randInt(rng, 12, 110), ny = randInt(rng, 12, 110);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    if (k % 3 == 1)
      for (int h = 0; h < 6; ++h)
        hf.z[hf.index(randInt(rng, 0, nx - 1), randInt(rng, 0, ny - 1))] = NAN;
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, 4 << randInt(rng, 0, 3));
    const gmm::ErrorTable table = gmm::buildErrorTable(hf, qt, 1);
    gmm::EmitScratch scratch;
    std::vector<gmm::GridTriangle> tris;
    auto expectNear = [&](float got, double want, const char* what, int b, int m, int n, int side) {
      if (want == INFINITY)
      {
        ASSERT_EQ(got, INFINITY) << what << " block " << b << " m " << m << " n " << n << " side " << side;
        return;
      }
      ASSERT_GE(got, want * (1 - 1e-12)) << what << " block " << b << " m " << m << " n " << n << " side " << side;
      ASSERT_LE(got, want * (1 + 1e-6) + 1e-9) << what << " block " << b << " m " << m << " n " << n << " side " << side;
      ++compared;
    };
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      const int w = qt.blockWidth(b), h = qt.blockHeight(b), top = gmm::topLevel(w, h);
      for (int m = 0; m <= top; ++m)
      {
        if (gmm::blockShape(w, h, m) != gmm::BlockShape::Ring)
          continue;
        double own = 0.0; // level 0 with its own edges: every sample a vertex
        if (m > 0)
        {
          // Every side at each edge level up to m that it can be drawn with: its own level,
          // and full resolution where that depends on the neighbour's level.
          const bool cells = qt.blockHasNodata[b] != 0;
          for (int side = 0; side < 4; ++side)
          {
            for (int e : possibleEdges(qt, b, m, side))
            {
              if (e > m)
                continue;
              gmm::BlockConfig cfg;
              cfg.level = m;
              cfg.edgeLevel = ownEdges(qt, b, m);
              cfg.edgeLevel[side] = e;
              tris.clear();
              gmm::emitBlockGrid(qt, b, cfg, gmm::BlockPart::Whole, tris, scratch);
              own = std::max(own, cells ? bruteHoles(hf, tris) : bruteStrict(hf, tris));
            }
          }
          ASSERT_FALSE(cells && std::isinf(table.ownExact(b, m))) << "block " << b << " m " << m;
          expectNear(table.ownExact(b, m), own, "own", b, m, m, -1);
          withNodata += cells ? 1 : 0;
        }
        for (int side = 0; side < 4; ++side)
        {
          if (possibleEdges(qt, b, m, side).back() <= m)
            continue; // no coarser edge: its strip is part of the own error above
          double running = 0.0;
          if (m > 0)
          {
            emitStrip(qt, b, m, side, m, tris, scratch);
            running = bruteStrict(hf, tris);
          }
          // A coarser block across glides the edge (its samples at m on the polyline at n); a
          // merged node across has the block's corners only, at its top level, and the
          // strip fans to them.
          const int c = b % qt.blockCols, r = b / qt.blockCols;
          GlideLine glide;
          glide.rows = side == gmm::South || side == gmm::North;
          glide.line = side == gmm::South ? qt.rowStart[r] : side == gmm::North ? qt.rowStart[r + 1]
            : side == gmm::West ? qt.colStart[c] : qt.colStart[c + 1];
          glide.first = glide.rows ? qt.colStart[c] : qt.rowStart[r];
          glide.last = glide.rows ? qt.colStart[c + 1] : qt.rowStart[r + 1];
          for (int n = m + 1; n < table.levels; ++n)
          {
            glide.level = n;
            emitStrip(qt, b, m, side, n, tris, scratch, true);
            running = std::max(running, bruteStrict(hf, tris, glide));
            if (n == top)
            {
              emitStrip(qt, b, m, side, n, tris, scratch);
              running = std::max(running, bruteStrict(hf, tris));
            }
            expectNear(table.strip(b, side, m, n), running, "strip", b, m, n, side);
          }
        }
      }
    }
  }
  EXPECT_GT(compared, 5000);
  EXPECT_GT(withNodata, 20);
}

// A merged node's error, from the design alone: the fan from the sample at the node's
// centre (rounded down) to the perimeter through every block corner on its border (and
// every sample along a side beside a block with nodata), and
// the largest vertical distance of a sample of the node to it (brute force, long double).
// The emitted fan must be that fan, and the table's entry its error.
TEST(ErrorTable, MergedNodeErrorsEqualBruteForce)
{
  Rng rng(2024);
  int compared = 0, bounded = 0, exactByExtent = 0;
  for (int k = 0; k < 11; ++k)
  {
    // The last DEM is large enough at block size 4 for nodes whose entries are bounds (more
    // than kExactMergedHeight levels above the leaves and kExactMergedQuads wide).
    const int nx = k < 10 ? randInt(rng, 20, 120) : 1100, ny = k < 10 ? randInt(rng, 20, 120) : 600;
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    const bool hole = k % 3 == 0;
    if (hole)
      hf.z[hf.index(randInt(rng, 0, nx - 1), randInt(rng, 0, ny - 1))] = NAN;
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, k < 10 ? 4 << randInt(rng, 0, 2) : 4);
    const gmm::ErrorTable table = gmm::buildErrorTable(hf, qt, 1);
    ASSERT_EQ(table.mergedError.size(), qt.nodes.size());
    for (std::size_t n = 0; n < qt.nodes.size(); ++n)
    {
      const gmm::QuadtreeNode& node = qt.nodes[n];
      const bool mergeable = node.colEnd - node.colBegin >= 2 && node.rowEnd - node.rowBegin >= 2;
      if (!mergeable)
      {
        EXPECT_EQ(table.mergedError[n], INFINITY) << "node " << n;
        continue;
      }
      const int i0 = qt.colStart[node.colBegin], i1 = qt.colStart[node.colEnd];
      const int j0 = qt.rowStart[node.rowBegin], j1 = qt.rowStart[node.rowEnd];
      // Block (c, r) holds nodata, from the heights (false outside the DEM).
      auto holed = [&](int c, int r) {
        if (c < 0 || r < 0 || c >= qt.blockCols || r >= qt.blockRows)
          return false;
        for (int j = qt.rowStart[r]; j <= qt.rowStart[r + 1]; ++j)
          for (int i = qt.colStart[c]; i <= qt.colStart[c + 1]; ++i)
            if (std::isnan(hf.height(i, j)))
              return true;
        return false;
      };
      // Every sample along a border block's side when it or the block across holds nodata
      // (both then draw that side at full resolution), else the block corners.
      std::vector<gmm::GridPoint> ring;
      for (int c = node.colBegin; c < node.colEnd; ++c)
      {
        const bool fine = holed(c, node.rowBegin) || holed(c, node.rowBegin - 1);
        for (int i = qt.colStart[c]; i < qt.colStart[c + 1]; i = fine ? i + 1 : qt.colStart[c + 1])
          ring.push_back({ i, j0 });
      }
      for (int r = node.rowBegin; r < node.rowEnd; ++r)
      {
        const bool fine = holed(node.colEnd - 1, r) || holed(node.colEnd, r);
        for (int j = qt.rowStart[r]; j < qt.rowStart[r + 1]; j = fine ? j + 1 : qt.rowStart[r + 1])
          ring.push_back({ i1, j });
      }
      for (int c = node.colEnd; c > node.colBegin; --c)
      {
        const bool fine = holed(c - 1, node.rowEnd - 1) || holed(c - 1, node.rowEnd);
        for (int i = qt.colStart[c]; i > qt.colStart[c - 1]; i = fine ? i - 1 : qt.colStart[c - 1])
          ring.push_back({ i, j1 });
      }
      for (int r = node.rowEnd; r > node.rowBegin; --r)
      {
        const bool fine = holed(node.colBegin, r - 1) || holed(node.colBegin - 1, r - 1);
        for (int j = qt.rowStart[r]; j > qt.rowStart[r - 1]; j = fine ? j - 1 : qt.rowStart[r - 1])
          ring.push_back({ i0, j });
      }
      // the apex: the corner the node's children share (their ranges meet there)
      int cSplit = node.colEnd, rSplit = node.rowEnd;
      for (int k = 0; k < node.childCount; ++k)
      {
        const gmm::QuadtreeNode& child = qt.nodes[node.firstChild + k];
        if (child.colBegin > node.colBegin)
          cSplit = std::min(cSplit, child.colBegin);
        if (child.rowBegin > node.rowBegin)
          rSplit = std::min(rSplit, child.rowBegin);
      }
      const gmm::GridPoint centre{ qt.colStart[cSplit], qt.rowStart[rSplit] };
      std::vector<gmm::GridTriangle> fan;
      for (std::size_t p = 0; p < ring.size(); ++p)
        fan.push_back({ { centre, ring[p], ring[(p + 1) % ring.size()] } });
      std::vector<gmm::GridTriangle> emitted;
      gmm::emitMergedNodeGrid(qt, static_cast<int>(n), emitted);
      ASSERT_EQ(emitted.size(), fan.size()) << "node " << n;
      for (std::size_t t = 0; t < fan.size(); ++t)
        for (int v = 0; v < 3; ++v)
          ASSERT_TRUE(emitted[t].v[v].i == fan[t].v[v].i && emitted[t].v[v].j == fan[t].v[v].j)
            << "node " << n << " triangle " << t;
      bool nodata = false;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          nodata = nodata || std::isnan(hf.height(i, j));
      if (nodata)
      {
        EXPECT_EQ(table.mergedError[n], INFINITY) << "node " << n << " over nodata";
        continue;
      }
      double brute = 0.0;
      for (const gmm::GridTriangle& t : fan)
        brute = std::max(brute, bruteTriangleError(hf, t));
      EXPECT_GE(table.mergedError[n], brute * (1 - 1e-12)) << "node " << n;
      if (gmm::mergedErrorIsExact(qt, static_cast<int>(n)))
      {
        EXPECT_LE(table.mergedError[n], brute * (1 + 1e-6) + 1e-9) << "node " << n;
        ++compared;
        // Exact by its extent, not its height: small blocks merge as widely as large ones.
        exactByExtent += node.height > gmm::kExactMergedHeight;
      }
      else
        ++bounded; // a bound: never below the exact error (checked above)
    }
  }
  EXPECT_GT(compared, 50);
  EXPECT_GT(bounded, 0);
  EXPECT_GT(exactByExtent, 0);
}
