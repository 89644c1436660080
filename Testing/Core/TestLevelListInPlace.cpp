// The engine keeps its level list from frame to frame: a hierarchical selection rewrites
// only the blocks and nodes the last selection drew and those it draws now (SelectNodes.h,
// `lastBlocks`), not every block of the DEM. After any sequence of calls the list must be
// the one a selection written whole gives. Checked after every call of random sequences
// (views that move a little or jump, tau from fine to coarse, geomorphing's path on and
// off, budgeted frames, view-independent frames, explicit levels, merged nodes off and on):
//  - against a fresh engine on the same terrain making the same call (a list written whole);
//  - from first principles against what the frame reports: a level >= 0 exactly at the
//    drawn blocks, kCoveredLevel exactly at the blocks inside the merged nodes' rectangles,
//    -1 everywhere else.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{

// Higher eyes and views up to the horizon and beyond: more nodes drawn whole.
const ViewRanges kRanges{ 0.3, 20.0, 6000.0, -1.5, 0.2, 300.0 };

// The view moved a step: forward or back, and turned a little, so that merged nodes split,
// join and leave the view gradually.
gmm::View stepOf(const gmm::View& v, Rng& rng, double step)
{
  gmm::View s = v;
  const double t = randReal(rng, -1.0, 1.0) * step;
  for (int a = 0; a < 3; ++a)
    s.eye[a] += t * v.forward[a];
  s.eye[2] = std::max(s.eye[2] + randReal(rng, -0.1, 0.1) * step, 5.0);
  const double turn = randReal(rng, -0.08, 0.08);
  const double x = v.forward[0], y = v.forward[1];
  s.forward[0] = std::cos(turn) * x - std::sin(turn) * y;
  s.forward[1] = std::sin(turn) * x + std::cos(turn) * y;
  return s;
}

// The level list a frame reports, checked from its drawn blocks and merged nodes alone.
void expectListOfFrame(const gmm::Engine& e, const std::string& what)
{
  const gmm::Quadtree& qt = e.quadtree();
  std::vector<int8_t> expect(qt.blockCount(), -1);
  for (int n : e.mergedNodeList())
  {
    const gmm::QuadtreeNode& node = qt.nodes[n];
    for (int r = node.rowBegin; r < node.rowEnd; ++r)
      for (int c = node.colBegin; c < node.colEnd; ++c)
        expect[r * qt.blockCols + c] = gmm::kCoveredLevel;
  }
  const std::vector<int8_t>& levels = e.levels();
  ASSERT_EQ(levels.size(), expect.size()) << what;
  for (int b : e.drawnBlocks())
  {
    ASSERT_GE(levels[b], 0) << what << ": drawn block " << b;
    ASSERT_EQ(expect[b], -1) << what << ": block " << b << " drawn and inside a merged node";
    expect[b] = levels[b];
  }
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    ASSERT_EQ(static_cast<int>(levels[b]), static_cast<int>(expect[b]))
      << what << ": block " << b << " (" << (expect[b] >= 0 ? "drawn" : expect[b] == -1 ? "not drawn" : "covered")
      << ")";
  }
}

} // namespace

TEST(LevelListInPlace, EqualsAListWrittenWholeAfterAnySequence)
{
  Rng rng(2026);
  int merges = 0, uncovered = 0, frames = 0;
  for (int dem = 0; dem < 8; ++dem)
  {
    gmm::Heightfield hf = roughTerrain(randInt(rng, 80, 330), randInt(rng, 80, 330), rng);
    if (dem % 3 == 1)
      hf.z[hf.index(hf.nx / 3, hf.ny / 2)] = std::numeric_limits<float>::quiet_NaN();
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 4 << randInt(rng, 0, 3)), "");
    gmm::View view = randomViewOver(e.heightfield(), rng, kRanges);
    const double extent = (hf.nx - 1) * hf.dx;
    std::vector<int> lastMerged;
    for (int call = 0; call < 120; ++call)
    {
      const std::string what = "dem " + std::to_string(dem) + " call " + std::to_string(call);
      const int kind = randInt(rng, 0, 19);
      view = kind < 3 ? randomViewOver(e.heightfield(), rng, kRanges) : stepOf(view, rng, 0.02 * extent);
      const double tau = std::exp(randReal(rng, std::log(0.3), std::log(40.0)));
      if (kind == 19)
      {
        const bool on = !e.mergedNodes();
        e.setMergedNodes(on);
      }
      if (kind == 18)
      {
        e.setMorphRange(e.morphRange() > 1.0 ? 0.0 : gmm::kDefaultMorphRange);
        e.setMergeOnPath(randInt(rng, 0, 1) == 1);
      }
      // The same call on a fresh engine, whose list is written whole.
      gmm::Engine fresh;
      fresh.setTerrain(e.terrain());
      fresh.setMergedNodes(e.mergedNodes());
      fresh.setMorphRange(e.morphRange());
      fresh.setMergeOnPath(e.mergeOnPath());
      if (kind < 12 || kind >= 18)
      {
        e.update(view, tau);
        fresh.update(view, tau);
      }
      else if (kind < 15)
      {
        const std::size_t budget = static_cast<std::size_t>(randInt(rng, 50, 20000));
        const double start = randInt(rng, 0, 1) ? tau * randReal(rng, 0.5, 2.0) : 0.0;
        e.update(view, 0.0, budget, start);
        fresh.update(view, 0.0, budget, start);
      }
      else if (kind < 17)
      {
        const double maxError = randReal(rng, 0.0, 80.0);
        e.updateForError(maxError);
        fresh.updateForError(maxError);
      }
      else
      {
        const std::vector<int8_t> levels = randomValidLevels(e.quadtree(), rng);
        e.updateWithLevels(levels);
        fresh.updateWithLevels(levels);
      }
      ASSERT_EQ(e.lastError(), "") << what;
      ASSERT_TRUE(e.levels() == fresh.levels()) << what << ": the list kept from frame to frame differs";
      expectListOfFrame(e, what);
      ++frames;
      // What the sequence went through: nodes drawn whole that the last frame did not draw,
      // and nodes drawn whole before and not now (whose blocks had to be uncovered).
      const std::vector<int>& now = e.mergedNodeList();
      for (int n : now)
        merges += std::find(lastMerged.begin(), lastMerged.end(), n) == lastMerged.end();
      for (int n : lastMerged)
        uncovered += std::find(now.begin(), now.end(), n) == now.end();
      lastMerged = now;
    }
  }
  // The sequences must have exercised what the in-place update does differently.
  EXPECT_GT(merges, 500);
  EXPECT_GT(uncovered, 500);
  std::printf("[ info ] %d calls: %d nodes newly drawn whole, %d no longer\n", frames, merges, uncovered);
}
