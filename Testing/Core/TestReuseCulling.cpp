// Frame-to-frame reuse and frustum culling (Engine.h, SelectLevels.h).
#include "CoreTestUtil.h"
#include "Engine.h"
#include "SyntheticTerrain.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{
gmm::Heightfield terrain()
{
  return gmm::makeSyntheticTerrain(257, 193, 30.0, 7, 1500.0, 1);
}
gmm::View lookingAcross(const gmm::Heightfield& hf, double back)
{
  gmm::View v;
  v.eye = { hf.worldX(128), hf.worldY(0) - back, 2500.0 };
  v.forward = { 0, 1, -0.35 };
  v.fovYDegrees = 60;
  v.viewportWidth = 1280;
  v.viewportHeight = 720;
  return v;
}
} // namespace

TEST(Reuse, SameViewReusesIdenticalIndices)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(terrain(), 32, 1), "");
  const gmm::View v = lookingAcross(e.heightfield(), 500);
  const gmm::FrameStats first = e.update(v, 1.0);
  EXPECT_FALSE(first.reused);
  EXPECT_GT(first.triangles, 0u);
  const std::vector<uint32_t> idx1 = e.indices();
  const std::vector<int8_t> lv1 = e.levels();
  const gmm::FrameStats second = e.update(v, 1.0);
  EXPECT_TRUE(second.reused);
  EXPECT_EQ(second.blocksRetessellated, 0);
  EXPECT_EQ(e.indices(), idx1);
  EXPECT_EQ(e.levels(), lv1);
  EXPECT_EQ(second.triangles, first.triangles);
}

TEST(Reuse, LevelChangeIsNotReused)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(terrain(), 32, 1), "");
  const gmm::View far = lookingAcross(e.heightfield(), 3000);
  e.update(far, 1.0);
  const std::vector<int8_t> lvFar = e.levels();
  const std::vector<uint32_t> idxFar = e.indices();
  gmm::View nearer = far;
  nearer.eye.y += 2500;
  nearer.eye.z = 1800;
  const gmm::FrameStats st = e.update(nearer, 1.0);
  ASSERT_NE(e.levels(), lvFar) << "test setup: the move should change levels";
  EXPECT_FALSE(st.reused);
  EXPECT_GT(st.blocksRetessellated, 0);
  EXPECT_NE(e.indices(), idxFar);
  // the cached result equals a fresh tessellation of the same levels
  std::vector<uint32_t> fresh;
  gmm::tessellate(e.heightfield(), e.quadtree(), e.levels(), fresh, e.mergedNodeList());
  auto sorted = [](std::vector<uint32_t> v) {
    std::vector<std::array<uint32_t, 3>> t;
    for (std::size_t k = 0; k < v.size(); k += 3)
    {
      std::array<uint32_t, 3> a{ v[k], v[k + 1], v[k + 2] };
      std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
      t.push_back(a);
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  EXPECT_EQ(sorted(e.indices()), sorted(fresh));
  // going back gives the first frame's triangles again
  e.update(far, 1.0);
  EXPECT_EQ(e.levels(), lvFar);
  EXPECT_EQ(sorted(e.indices()), sorted(idxFar));
  // a tau change that changes levels is not reused either
  const std::vector<int8_t> lvTau1 = e.levels();
  const gmm::FrameStats st8 = e.update(far, 8.0);
  if (e.levels() != lvTau1)
    EXPECT_FALSE(st8.reused);
}

TEST(Culling, LookingAwaySeesNothing)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(terrain(), 32, 1), "");
  const gmm::Heightfield& hf = e.heightfield();
  gmm::View v;
  v.eye = { hf.worldX(128), hf.worldY(0) - 100, 1000.0 };
  v.forward = { 0, -1, 0.2 }; // away from the terrain, slightly up
  v.fovYDegrees = 60;
  const gmm::FrameStats& st = e.update(v, 1.0);
  EXPECT_EQ(e.lastError(), "");
  EXPECT_EQ(st.visibleBlocks, 0);
  EXPECT_EQ(st.culledBlocks, e.quadtree().blockCount());
  EXPECT_EQ(st.triangles, 0u);
  EXPECT_TRUE(e.indices().empty());
  // straight up from above the highest point
  v.eye.z = 5000;
  v.forward = { 0.01, 0, 1 };
  v.up = { 1, 0, 0 };
  EXPECT_EQ(e.update(v, 1.0).triangles, 0u);
}

TEST(Culling, CornerViewCullsAndStaysConservative)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(terrain(), 16, 1), "");
  const gmm::Heightfield& hf = e.heightfield();
  gmm::View v;
  v.eye = { hf.worldX(0) - 200, hf.worldY(0) - 200, 1800.0 };
  v.forward = { 1, 1, -0.6 };
  v.fovYDegrees = 30;
  v.farDistance = 4000;
  const gmm::FrameStats& st = e.update(v, 1.0);
  EXPECT_GT(st.culledBlocks, 0);
  EXPECT_GT(st.visibleBlocks, 0);
  EXPECT_EQ(st.visibleBlocks + st.culledBlocks, e.quadtree().blockCount());
  // conservative: every block with a sample inside the frustum (our own test) is drawn
  const MyCamera cam = makeCamera(v);
  const gmm::Quadtree& qt = e.quadtree();
  int mustBeVisible = 0;
  for (int r = 0; r < qt.blockRows; ++r)
    for (int c = 0; c < qt.blockCols; ++c)
    {
      bool inside = false;
      for (int j = qt.rowStart[r]; j <= qt.rowStart[r + 1] && !inside; ++j)
        for (int i = qt.colStart[c]; i <= qt.colStart[c + 1] && !inside; ++i)
          inside = insideFrustum(cam, hf.worldX(i), hf.worldY(j), hf.height(i, j));
      if (inside)
      {
        ++mustBeVisible;
        EXPECT_GE(e.levels()[qt.blockIndex(c, r)], 0) << "block " << c << "," << r << " has a sample in view but is culled";
      }
    }
  EXPECT_GT(mustBeVisible, 0);
  EXPECT_LE(mustBeVisible, st.visibleBlocks);
}
