// frontToBack: blocks sorted by distance from the eye, checked against distances computed
// here by brute force over each block's samples.
#include "CoreTestUtil.h"
#include "DrawOrder.h"
#include "Quadtree.h"
#include "View.h"

#include <gtest/gtest.h>

using namespace gmmtest;

TEST(DrawOrder, NearestBlocksFirst)
{
  gmm::Heightfield hf;
  hf.nx = 129;
  hf.ny = 97;
  hf.dx = 10.0;
  hf.dy = -7.0; // mirrored rows: the order must not care
  hf.z.assign(static_cast<std::size_t>(hf.nx) * hf.ny, 120.0f);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  gmm::View v;
  v.eye = { hf.worldX(20), hf.worldY(70), 2000.0 };
  const glm::dmat4 toWorld = gmm::heightfieldToWorld(v, hf.z0, 1.0);
  std::vector<int> all(qt.blockCount());
  for (int b = 0; b < qt.blockCount(); ++b)
    all[b] = b;
  std::vector<int> order;
  gmm::frontToBack(qt, toWorld, v.eye, all, {}, order);
  ASSERT_EQ(order.size(), all.size());
  // Over a flat terrain every box has the same height, so the order is that of the
  // horizontal distance to each block's rectangle.
  auto planar = [&](int b) {
    const int c = b % qt.blockCols, r = b / qt.blockCols;
    const double xa = hf.worldX(qt.colStart[c]), xb = hf.worldX(qt.colStart[c + 1]);
    const double ya = hf.worldY(qt.rowStart[r]), yb = hf.worldY(qt.rowStart[r + 1]);
    const double x0 = std::min(xa, xb), x1 = std::max(xa, xb), y0 = std::min(ya, yb), y1 = std::max(ya, yb);
    const double dx = std::max({ x0 - v.eye.x, 0.0, v.eye.x - x1 });
    const double dy = std::max({ y0 - v.eye.y, 0.0, v.eye.y - y1 });
    return std::sqrt(dx * dx + dy * dy);
  };
  for (std::size_t k = 0; k + 1 < order.size(); ++k)
    EXPECT_LE(planar(order[k]), planar(order[k + 1]) + 1e-9) << "position " << k;
  // The block under the eye comes first.
  int col = 0, row = 0;
  while (qt.colStart[col + 1] < 20)
    ++col;
  while (qt.rowStart[row + 1] < 70)
    ++row;
  const int under = qt.blockIndex(col, row);
  EXPECT_EQ(order.front(), under);
}

// Merged nodes take their slots after the blocks' (blockCount() + node) and sort among the
// blocks by their own boxes: a node far away comes after a block under the eye, a node
// under the eye before a block far away.
TEST(DrawOrder, MergedNodesAmongBlocks)
{
  gmm::Heightfield hf;
  hf.nx = 129;
  hf.ny = 129;
  hf.z.assign(static_cast<std::size_t>(hf.nx) * hf.ny, 0.0f);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16); // 8 x 8 blocks
  gmm::View v;
  v.eye = { 4.0, 4.0, 50.0 }; // over block (0, 0)
  const glm::dmat4 toWorld = gmm::heightfieldToWorld(v, hf.z0, 1.0);
  // The root's children: the south-west quarter (under the eye) and the north-east one.
  int sw = -1, ne = -1;
  const gmm::QuadtreeNode& root = qt.nodes[0];
  for (int k = 0; k < root.childCount; ++k)
  {
    const gmm::QuadtreeNode& n = qt.nodes[root.firstChild + k];
    if (n.colBegin == 0 && n.rowBegin == 0)
      sw = root.firstChild + k;
    if (n.colEnd == qt.blockCols && n.rowEnd == qt.blockRows)
      ne = root.firstChild + k;
  }
  ASSERT_GE(sw, 0);
  ASSERT_GE(ne, 0);
  const int nearBlock = qt.blockIndex(0, 0), farBlock = qt.blockIndex(qt.blockCols - 1, qt.blockRows - 1);
  std::vector<int> order;
  gmm::frontToBack(qt, toWorld, v.eye, { farBlock }, { sw }, order);
  EXPECT_EQ(order, (std::vector<int>{ qt.blockCount() + sw, farBlock }));
  gmm::frontToBack(qt, toWorld, v.eye, { nearBlock }, { ne }, order);
  EXPECT_EQ(order, (std::vector<int>{ nearBlock, qt.blockCount() + ne }));
}
