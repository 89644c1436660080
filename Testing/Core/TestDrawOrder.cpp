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
  gmm::frontToBack(qt, toWorld, v.eye, all, order);
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
