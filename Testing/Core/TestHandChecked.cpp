// Small cases derived by hand. The diagonal direction inside a cell is not part of the
// contract, so each cell of the expected grid may be split by either diagonal: the emitted
// set of triangles (compared up to rotation) must equal one such choice per cell.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Morph.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <set>

using namespace gmmtest;

namespace
{
using Tri = std::array<uint32_t, 3>;
Tri canonical(uint32_t a, uint32_t b, uint32_t c)
{
  Tri t{ a, b, c };
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}
std::vector<Tri> trianglesOf(const std::vector<uint32_t>& idx)
{
  std::vector<Tri> t;
  for (std::size_t k = 0; k + 2 < idx.size(); k += 3)
    t.push_back(canonical(idx[k], idx[k + 1], idx[k + 2]));
  std::sort(t.begin(), t.end());
  return t;
}
std::string show(const std::vector<Tri>& ts, int nx)
{
  std::ostringstream s;
  for (const Tri& t : ts)
    s << " [(" << t[0] % nx << "," << t[0] / nx << ")(" << t[1] % nx << "," << t[1] / nx << ")("
      << t[2] % nx << "," << t[2] / nx << ")]";
  return s.str();
}

// Expects the triangles to be exactly the cells of cols x rows, each split by a diagonal,
// counter-clockwise in grid space (dx, dy > 0).
void expectCells(const std::vector<uint32_t>& idx, int nx, const std::vector<int>& cols, const std::vector<int>& rows)
{
  std::vector<Tri> got = trianglesOf(idx);
  std::set<Tri> gotSet(got.begin(), got.end());
  ASSERT_EQ(gotSet.size(), got.size()) << "duplicate triangles";
  ASSERT_EQ(got.size(), 2 * (cols.size() - 1) * (rows.size() - 1)) << show(got, nx);
  std::size_t matched = 0;
  for (std::size_t r = 0; r + 1 < rows.size(); ++r)
    for (std::size_t c = 0; c + 1 < cols.size(); ++c)
    {
      auto v = [&](int i, int j) { return static_cast<uint32_t>(j * nx + i); };
      const uint32_t a = v(cols[c], rows[r]), b = v(cols[c + 1], rows[r]), cc = v(cols[c + 1], rows[r + 1]),
                     d = v(cols[c], rows[r + 1]);
      const bool diag1 = gotSet.count(canonical(a, b, cc)) && gotSet.count(canonical(a, cc, d));
      const bool diag2 = gotSet.count(canonical(a, b, d)) && gotSet.count(canonical(b, cc, d));
      EXPECT_TRUE(diag1 || diag2) << "cell (" << cols[c] << "," << rows[r] << ")-(" << cols[c + 1] << ","
                                  << rows[r + 1] << ") not split by a diagonal; got" << show(got, nx);
      matched += (diag1 || diag2) ? 2 : 0;
    }
  EXPECT_EQ(matched, got.size());
}

gmm::Heightfield ramp(int nx, int ny)
{
  gmm::Heightfield hf;
  hf.nx = nx;
  hf.ny = ny;
  hf.z.resize(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      hf.z[hf.index(i, j)] = static_cast<float>((i * 7 + j * 13) % 5);
  return hf;
}
} // namespace

TEST(HandChecked, TwoByTwo)
{
  gmm::Heightfield hf = ramp(2, 2);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 64);
  std::vector<uint32_t> out;
  gmm::tessellate(hf, qt, { 0 }, out);
  expectCells(out, 2, { 0, 1 }, { 0, 1 });
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 64, 1), "");
  EXPECT_EQ(e.updateForError(0.0).triangles, 2u);
  EXPECT_EQ(e.updateForError(1e9).triangles, 2u);
}

TEST(HandChecked, FiveByFiveAllLevels)
{
  gmm::Heightfield hf = ramp(5, 5);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 64);
  ASSERT_EQ(qt.blockCount(), 1);
  std::vector<uint32_t> out;
  // level 0: 16 cells, 32 triangles
  gmm::tessellate(hf, qt, { 0 }, out);
  EXPECT_EQ(out.size(), 96u);
  expectCells(out, 5, { 0, 1, 2, 3, 4 }, { 0, 1, 2, 3, 4 });
  // level 1: ring (2 < 4): samples 0, 2, 4 -> 4 cells, 8 triangles
  gmm::tessellate(hf, qt, { 1 }, out);
  expectCells(out, 5, { 0, 2, 4 }, { 0, 2, 4 });
  // level 2: one quad (4 >= 4): 2 triangles over the corners
  gmm::tessellate(hf, qt, { 2 }, out);
  expectCells(out, 5, { 0, 4 }, { 0, 4 });
}

// 6 x 9 samples = 5 x 8 quads, level 1: columns 0,2,4 + last 5; rows 0,2,4,6,8.
TEST(HandChecked, SixByNineThinStripsLevel1)
{
  gmm::Heightfield hf = ramp(6, 9);
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 64);
  ASSERT_EQ(qt.blockCount(), 1);
  std::vector<uint32_t> out;
  gmm::tessellate(hf, qt, { 1 }, out);
  expectCells(out, 6, { 0, 2, 4, 5 }, { 0, 2, 4, 6, 8 });
  // level 2: 4 < 5 and 4 < 8: ring; columns 0,4,5; rows 0,4,8
  gmm::tessellate(hf, qt, { 2 }, out);
  expectCells(out, 6, { 0, 4, 5 }, { 0, 4, 8 });
  // level 3: 8 >= 5 and 8 >= 8: one quad
  gmm::tessellate(hf, qt, { 3 }, out);
  expectCells(out, 6, { 0, 5 }, { 0, 8 });
}

// Two blocks side by side at levels 0 and 1: the shared edge is glided. Both blocks use
// its samples at level 0 (the fine block's own cells reach it, the coarse block cuts its
// triangles there), and those between level 1's are drawn on the level-1 polyline.
TEST(HandChecked, TwoBlocksStitchedAtCoarserEdge)
{
  gmm::Heightfield hf = ramp(9, 5); // 8 x 4 quads, block size 4 -> two 4x4 blocks
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 9; ++i)
      hf.z[hf.index(i, j)] += static_cast<float>((i * 7 + j * 13) % 5); // not a plane
  gmm::Quadtree qt = gmm::buildQuadtree(hf, 4);
  ASSERT_EQ(qt.colStart, (std::vector<int>{ 0, 4, 8 }));
  std::vector<uint32_t> out;
  gmm::tessellate(hf, qt, { 0, 1 }, out);
  std::set<uint32_t> used(out.begin(), out.end());
  for (int j = 0; j < 5; ++j)
    EXPECT_EQ(used.count(static_cast<uint32_t>(j * 9 + 4)), 1u) << "sample (4," << j << ") on the shared edge";
  // the coarse block uses exactly its level-1 samples (and the shared edge's)
  for (int j = 0; j < 5; ++j)
    for (int i = 5; i < 9; ++i)
      EXPECT_EQ(used.count(static_cast<uint32_t>(j * 9 + i)), (i % 2 == 0 && j % 2 == 0) ? 1u : 0u) << i << "," << j;
  // the fine block uses all its samples
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(used.count(static_cast<uint32_t>(j * 9 + i)), 1u) << i << "," << j;
  // (4, 1) and (4, 3) drawn halfway between their level-1 neighbours on the edge; the
  // others at their own heights.
  gmm::MorphFrame f;
  const std::vector<int8_t> levels{ 0, 1 };
  gmm::drawnEdgeFrame(qt, levels, f);
  auto h = [&](int i, int j) { return static_cast<double>(hf.height(i, j)); };
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, qt, levels, f, 4, 1), 0.5 * (h(4, 0) + h(4, 2)));
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, qt, levels, f, 4, 3), 0.5 * (h(4, 2) + h(4, 4)));
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, qt, levels, f, 4, 2), h(4, 2));
  EXPECT_DOUBLE_EQ(gmm::morphedHeight(hf, qt, levels, f, 3, 1), h(3, 1));
  // the coarse block's triangles on the edge: cut at (4, 1) and (4, 3), 8 + 2 of them
  EXPECT_EQ(out.size() / 3, 32u + 10u);
  EXPECT_EQ(checkMesh(hf, qt.colStart, qt.rowStart, out, {}).error, "");
}
