// Poyart's ownership (Tessellate.h): each drawn block or merged node draws its area and its
// east and south connects. Checked against the per-block triangles that the error table
// certifies (emitBlock with every part, emitMergedNode's fan): after any engine frame the
// slots hold each of those triangles exactly once, a slot reaches no further than its
// owner and the blocks east and south of it, and the strips on a block's west and north
// sides are in the slot of what lies there whenever something is drawn there.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>

using namespace gmmtest;

namespace
{
using Tri = std::array<uint32_t, 3>;

// A triangle with its smallest index first (the winding kept).
Tri canonical(const uint32_t* t)
{
  Tri a{ t[0], t[1], t[2] };
  std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
  return a;
}

std::vector<Tri> trianglesOf(const std::vector<uint32_t>& idx)
{
  std::vector<Tri> t;
  for (std::size_t k = 0; k + 2 < idx.size(); k += 3)
    t.push_back(canonical(&idx[k]));
  std::sort(t.begin(), t.end());
  return t;
}

struct Rect
{
  int i0, i1, j0, j1;
  bool holds(int i, int j) const { return i >= i0 && i <= i1 && j >= j0 && j <= j1; }
};

Rect blockRect(const gmm::Quadtree& qt, int b)
{
  const int c = b % qt.blockCols, r = b / qt.blockCols;
  return { qt.colStart[c], qt.colStart[c + 1], qt.rowStart[r], qt.rowStart[r + 1] };
}

Rect nodeRect(const gmm::Quadtree& qt, int n)
{
  const gmm::QuadtreeNode& node = qt.nodes[n];
  return { qt.colStart[node.colBegin], qt.colStart[node.colEnd], qt.rowStart[node.rowBegin],
    qt.rowStart[node.rowEnd] };
}

// The slot that holds what is drawn over block b: b's own, or its merged node's; -1 when
// nothing is drawn there.
int ownerSlot(const gmm::Engine& e, int b)
{
  const gmm::Quadtree& qt = e.quadtree();
  if (e.levels()[b] >= 0)
    return b;
  const int c = b % qt.blockCols, r = b / qt.blockCols;
  for (int n : e.mergedNodeList())
  {
    const gmm::QuadtreeNode& node = qt.nodes[n];
    if (c >= node.colBegin && c < node.colEnd && r >= node.rowBegin && r < node.rowEnd)
      return qt.blockCount() + n;
  }
  return -1;
}

struct Found
{
  int byBlock = 0, byNode = 0; // west / north strip triangles in a neighbour block's / node's slot
};

// Checks one frame and counts what it found in `found`.
void checkFrame(const gmm::Engine& e, const std::string& what, Found& found)
{
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  const std::vector<int8_t>& levels = e.levels();
  // 1. Every block's and node's own triangles, exactly once.
  std::vector<uint32_t> own;
  gmm::EmitScratch scratch;
  for (int b = 0; b < qt.blockCount(); ++b)
    if (levels[b] >= 0)
      gmm::emitBlock(hf, qt, b, gmm::blockConfigOf(qt, levels, b), gmm::BlockPart::Whole, own, scratch);
  const std::vector<int8_t> depth = drawnNodeDepths(e);
  const gmm::PerimeterContext across{ levels, depth };
  for (int n : e.mergedNodeList())
    gmm::emitMergedNode(hf, qt, n, own, scratch, &across);
  EXPECT_TRUE(trianglesOf(e.indices()) == trianglesOf(own))
    << what << ": the slots do not hold every block's triangles exactly once";

  // 2. Each slot within its owner and the blocks east and south of it.
  const gmm::IndexArena& arena = e.indexArena();
  std::map<Tri, int> slotOf;
  auto slotRects = [&](int slot) {
    std::vector<Rect> rects;
    std::vector<int> east, south;
    if (slot < qt.blockCount())
    {
      rects.push_back(blockRect(qt, slot));
      const std::array<int, 4> nb = qt.blockNeighbours(slot);
      for (int s : { gmm::East, gmm::South })
        if (nb[s] >= 0)
          rects.push_back(blockRect(qt, nb[s]));
    }
    else
    {
      const int n = slot - qt.blockCount();
      const gmm::QuadtreeNode& node = qt.nodes[n];
      rects.push_back(nodeRect(qt, n));
      for (int r = node.rowBegin; node.colEnd < qt.blockCols && r < node.rowEnd; ++r)
        rects.push_back(blockRect(qt, qt.blockIndex(node.colEnd, r)));
      for (int c = node.colBegin; node.rowBegin > 0 && c < node.colEnd; ++c)
        rects.push_back(blockRect(qt, qt.blockIndex(c, node.rowBegin - 1)));
    }
    return rects;
  };
  std::vector<int> slots;
  for (int b = 0; b < qt.blockCount(); ++b)
    if (levels[b] >= 0)
      slots.push_back(b);
  for (int n : e.mergedNodeList())
    slots.push_back(qt.blockCount() + n);
  for (int slot : slots)
  {
    const std::vector<Rect> rects = slotRects(slot);
    const gmm::IndexArena::Range r = arena.slot(slot);
    for (std::size_t k = r.begin; k + 2 < r.end; k += 3)
    {
      const Tri t = canonical(&arena.indices()[k]);
      slotOf[t] = slot;
      for (uint32_t v : t)
      {
        const int i = static_cast<int>(v % static_cast<uint32_t>(hf.nx));
        const int j = static_cast<int>(v / static_cast<uint32_t>(hf.nx));
        const bool inside = std::any_of(rects.begin(), rects.end(), [&](const Rect& q) { return q.holds(i, j); });
        EXPECT_TRUE(inside) << what << ": slot " << slot << " draws sample (" << i << ", " << j
                            << "), beyond its owner and the blocks east and south of it";
        if (!inside)
          return;
      }
    }
  }

  // 3. A block's west / north strip is in the slot of what lies there, when drawn.
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    if (levels[b] < 0)
      continue;
    const gmm::BlockConfig cfg = gmm::blockConfigOf(qt, levels, b);
    const std::array<int, 4> nb = qt.blockNeighbours(b);
    for (int side : { gmm::West, gmm::North })
    {
      const int owner = nb[side] >= 0 ? ownerSlot(e, nb[side]) : -1;
      std::vector<uint32_t> strip;
      gmm::emitBlock(hf, qt, b, cfg, side == gmm::West ? gmm::BlockPart::StripWest : gmm::BlockPart::StripNorth, strip);
      for (std::size_t k = 0; k + 2 < strip.size(); k += 3)
      {
        const auto it = slotOf.find(canonical(&strip[k]));
        if (it == slotOf.end())
          continue; // reported by 1.
        const int expected = owner >= 0 ? owner : b;
        EXPECT_EQ(it->second, expected) << what << ": block " << b << "'s "
                                        << (side == gmm::West ? "west" : "north") << " strip";
        if (it->second != expected)
          return;
        if (owner >= qt.blockCount())
          ++found.byNode;
        else if (owner >= 0)
          ++found.byBlock;
      }
    }
  }
}

} // namespace

TEST(Connects, EachSlotIsItsAreaAndEastSouthConnects)
{
  Rng rng(2811);
  Found found;
  int mergedFrames = 0, frames = 0;
  for (int dem = 0; dem < 8; ++dem)
  {
    gmm::Engine e;
    gmm::Heightfield hf = roughTerrain(randInt(rng, 40, 220), randInt(rng, 40, 220), rng);
    if (dem % 3 == 1)
      hf.z[hf.index(hf.nx / 2, hf.ny / 3)] = std::numeric_limits<float>::quiet_NaN();
    ASSERT_EQ(e.setHeightfield(hf, 4 << randInt(rng, 0, 3)), "");
    for (int frame = 0; frame < 25; ++frame)
    {
      randomEngineFrame(e, rng);
      ASSERT_EQ(e.lastError(), "");
      const std::string what = "dem " + std::to_string(dem) + " frame " + std::to_string(frame);
      checkFrame(e, what, found);
      if (::testing::Test::HasFailure())
        return;
      mergedFrames += !e.mergedNodeList().empty();
      ++frames;
    }
  }
  std::printf("[ connects ] %d frames, %d with merged nodes; strip triangles drawn by the block / "
              "merged node west or north of theirs: %d / %d\n", frames, mergedFrames, found.byBlock,
    found.byNode);
  EXPECT_GT(found.byBlock, 0);
  EXPECT_GT(found.byNode, 0);
}
