// The index arena behind incremental index uploads: a renderer that mirrors it by copying
// only the reported ranges (or everything on a rewrite) always holds exactly the list, and
// the triangles in it are, after any sequence of frames, those of a from-scratch
// tessellation; a frame that changes a few blocks reports only their slots.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{
using Tri = std::array<uint32_t, 3>;

// What a GPU index buffer updated the way the mapper does holds.
struct Mirror
{
  std::vector<uint32_t> buffer;
  std::size_t uploaded = 0; // indices copied by the last apply
  void apply(const gmm::IndexArena& a)
  {
    if (a.rewritten())
    {
      buffer = a.indices();
      uploaded = buffer.size();
      return;
    }
    ASSERT_EQ(buffer.size(), a.indices().size()) << "size changed without a rewrite";
    uploaded = 0;
    std::size_t previousEnd = 0;
    for (const gmm::IndexArena::Range& r : a.dirtyRanges())
    {
      ASSERT_LT(r.begin, r.end);
      ASSERT_GE(r.begin, previousEnd) << "ranges overlap or are unsorted";
      ASSERT_LE(r.end, buffer.size());
      std::copy(a.indices().begin() + r.begin, a.indices().begin() + r.end, buffer.begin() + r.begin);
      uploaded += r.end - r.begin;
      previousEnd = r.end;
    }
  }
};

std::vector<Tri> sortedTriangles(const std::vector<uint32_t>& idx, bool skipRestart)
{
  std::vector<Tri> t;
  for (std::size_t k = 0; k + 2 < idx.size(); k += 3)
  {
    if (skipRestart && idx[k] == gmm::kRestartIndex)
    {
      EXPECT_TRUE(idx[k + 1] == gmm::kRestartIndex && idx[k + 2] == gmm::kRestartIndex)
        << "a restart index inside a triangle at " << k;
      continue;
    }
    t.push_back(Tri{ idx[k], idx[k + 1], idx[k + 2] });
  }
  std::sort(t.begin(), t.end());
  return t;
}

// After a frame: the mirror equals the arena, its triangles equal a fresh tessellation of
// the engine's levels, and indices() is that tessellation in block order.
void expectFrameConsistent(const gmm::Engine& e, Mirror& m, const std::string& what)
{
  m.apply(e.indexArena());
  ASSERT_TRUE(m.buffer == e.indexArena().indices()) << what << ": mirror differs";
  ASSERT_EQ(m.buffer.size() % 3, 0u);
  std::vector<uint32_t> fresh;
  gmm::tessellate(e.heightfield(), e.quadtree(), e.levels(), fresh, e.mergedNodeList(), &e.mergedNodeDepths());
  ASSERT_TRUE(e.indices() == fresh) << what << ": indices() is not a fresh tessellation";
  ASSERT_TRUE(sortedTriangles(m.buffer, true) == sortedTriangles(fresh, false))
    << what << ": drawn triangles differ from a fresh tessellation";
  ASSERT_EQ(e.stats().triangles * 3, fresh.size()) << what;
}

} // namespace

TEST(IndexArena, MirrorAndTrianglesAfterRandomFrames)
{
  Rng rng(31);
  for (int dem = 0; dem < 6; ++dem)
  {
    gmm::Engine e;
    gmm::Heightfield hf = roughTerrain(randInt(rng, 60, 260), randInt(rng, 60, 260), rng);
    if (dem % 2)
      hf.z[hf.index(hf.nx / 2, hf.ny / 3)] = std::numeric_limits<float>::quiet_NaN();
    ASSERT_EQ(e.setHeightfield(hf, 8 << randInt(rng, 0, 3)), "");
    Mirror m;
    for (int frame = 0; frame < 60; ++frame)
    {
      randomEngineFrame(e, rng);
      ASSERT_EQ(e.lastError(), "");
      expectFrameConsistent(e, m, "dem " + std::to_string(dem) + " frame " + std::to_string(frame));
    }
  }
}

TEST(IndexArena, SmallChangeUploadsSmallRanges)
{
  Rng rng(5);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(roughTerrain(257, 257, rng), 16), "");
  const gmm::Quadtree& qt = e.quadtree();
  std::vector<int8_t> levels(qt.blockCount(), 1);
  Mirror m;
  e.updateWithLevels(levels);
  expectFrameConsistent(e, m, "all at level 1");
  EXPECT_TRUE(e.indexArena().rewritten()); // the first frame
  // One block in the middle goes to level 0. Its neighbours keep their edges (the coarser
  // side sets an edge, and they are the coarser), but its west and north strips, whose inner
  // ring moved, are drawn by the east and south connects of its west and north neighbours
  // (Tessellate.h): three slots.
  const int b = qt.blockIndex(qt.blockCols / 2, qt.blockRows / 2);
  levels[b] = 0;
  e.updateWithLevels(levels);
  expectFrameConsistent(e, m, "one block refined");
  EXPECT_FALSE(e.indexArena().rewritten());
  EXPECT_EQ(e.stats().blocksRetessellated, 3);
  // Uploaded: those slots, new and released.
  const std::size_t full = e.indexArena().indices().size();
  EXPECT_GT(m.uploaded, 0u);
  EXPECT_LT(m.uploaded * 10, full) << m.uploaded << " of " << full << " indices uploaded";
  // And back to level 1: the east and south neighbours' slots are untouched again.
  levels[b] = 1;
  e.updateWithLevels(levels);
  expectFrameConsistent(e, m, "back to level 1");
  EXPECT_FALSE(e.indexArena().rewritten());
  EXPECT_LT(m.uploaded * 10, full);
  // Nothing changes: nothing uploaded.
  e.updateWithLevels(levels);
  m.apply(e.indexArena());
  EXPECT_EQ(m.uploaded, 0u);
}

TEST(IndexArena, SparseListIsCompacted)
{
  Rng rng(8);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(roughTerrain(513, 513, rng), 32), "");
  const gmm::Quadtree& qt = e.quadtree();
  Mirror m;
  e.updateWithLevels(std::vector<int8_t>(qt.blockCount(), 0)); // full resolution
  expectFrameConsistent(e, m, "level 0");
  const std::size_t big = e.indexArena().indices().size();
  std::vector<int8_t> top(qt.blockCount());
  for (int b = 0; b < qt.blockCount(); ++b)
    top[b] = static_cast<int8_t>(gmm::topLevel(qt.blockWidth(b), qt.blockHeight(b)));
  e.updateWithLevels(top); // two triangles a block: the slots are nearly all unused
  expectFrameConsistent(e, m, "top levels");
  EXPECT_TRUE(e.indexArena().rewritten());
  EXPECT_LT(e.indexArena().indices().size() * 20, big);
  // The full-resolution list is not kept as the next compaction's spare.
  EXPECT_LT(e.indexArena().heldIndices() * 5, big);
}
