// Budgeted selection (Engine::update with a triangle budget), checked from outside:
//  - the drawn triangles never exceed the budget along flights (unless even the coarsest
//    selection does, which the statistics must then say);
//  - the drawn surface, measured with the independent screen-error measure
//    (CoreTestUtil.h), stays within the error the frame reports;
//  - at the triangle count of a tau-driven frame, the budgeted error is no larger than the
//    tau-driven one (the budget is that frame's count, so the budgeted frame draws at most
//    as many triangles: a fair comparison);
//  - no budget is exactly update(view, tau).
#include "CoreTestUtil.h"
#include "Engine.h"
#include "SyntheticTerrain.h"
#include "TriangleCount.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace gmmtest;

namespace
{
// A low flight across the DEM, heading turning, looking ahead and down; the last views
// are a high oblique and an orthographic one.
std::vector<gmm::View> flight(const gmm::Heightfield& hf, int frames)
{
  std::vector<gmm::View> views;
  const double w = hf.dx * (hf.nx - 1), h = hf.dy * (hf.ny - 1);
  for (int k = 0; k < frames; ++k)
  {
    const double s = k / double(frames - 1);
    gmm::View v;
    v.eye = { hf.x0 + w * (0.1 + 0.8 * s), hf.y0 + h * (0.2 + 0.3 * std::sin(3.0 * s)), 1700.0 + 400.0 * s };
    const double heading = 0.4 + 2.5 * s;
    v.forward = { std::cos(heading), std::sin(heading), -0.35 };
    v.fovYDegrees = 60.0;
    v.nearDistance = 1.0;
    v.farDistance = 1e6;
    v.viewportWidth = 640;
    v.viewportHeight = 480;
    views.push_back(v);
  }
  gmm::View high = views.front();
  high.eye = { hf.x0 - 0.2 * w, hf.y0 - 0.2 * h, 6000.0 };
  high.forward = { 1.0, 1.0, -0.8 };
  views.push_back(high);
  gmm::View ortho = high;
  ortho.parallel = true;
  ortho.parallelScale = 0.4 * h;
  views.push_back(ortho);
  return views;
}

struct Case
{
  const char* name;
  gmm::Heightfield hf;
  int blockQuads;
};

std::vector<Case> cases()
{
  Rng rng(1414);
  std::vector<Case> c;
  c.push_back({ "synthetic 257^2", gmm::makeSyntheticTerrain(257, 257, 30.0, 7, 1500.0, 1), 32 });
  c.push_back({ "rough 200x150", roughTerrain(200, 150, rng, 30.0, 30.0, 800.0, 0.05), 16 });
  c.push_back({ "noisy 130x120", roughTerrain(130, 120, rng, 20.0, 25.0, 300.0, 0.3), 8 });
  return c;
}
} // namespace

TEST(BudgetSelection, TrianglesWithinBudgetOnEveryFrame)
{
  int merged = 0;
  for (const Case& c : cases())
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(c.hf, c.blockQuads, 1), "");
    int frames = 0, limited = 0;
    for (const gmm::View& v : flight(c.hf, 24))
    {
      for (std::size_t budget : { 64u, 600u, 3000u, 12000u, 50000u })
      {
        const gmm::FrameStats s = e.update(v, 0.0, budget);
        ASSERT_EQ(e.lastError(), "");
        ASSERT_EQ(s.triangles * 3, e.indices().size());
        ++frames;
        limited += s.budgetReached;
        if (s.overBudget)
        {
          // Only when the coarsest selection (every visible block one quad) is over budget.
          EXPECT_GT(2 * static_cast<std::size_t>(s.visibleBlocks), budget) << c.name;
          continue;
        }
        EXPECT_LE(s.triangles, budget) << c.name << " frame " << frames;
        // Crack-free and hole-free whatever the budget (neighbours at any levels).
        std::vector<bool> drawn(e.levels().size());
        for (std::size_t b = 0; b < drawn.size(); ++b)
          drawn[b] = gmm::drawnLevel(e.levels()[b]);
        merged += s.mergedNodes > 0;
        MeshCheckOptions opt;
        opt.drawn = drawn;
        const MeshCheckResult mc = checkMesh(e.heightfield(), e.quadtree().colStart,
          e.quadtree().rowStart, e.indices(), opt);
        ASSERT_EQ(mc.error, "") << c.name << " budget " << budget;
      }
    }
    EXPECT_GT(limited, frames / 2) << c.name << ": the budgets should bind in most frames";
  }
  std::printf("[ budget ] %d budgeted frames drew merged nodes\n", merged);
  EXPECT_GT(merged, 20); // the hierarchical selection was really part of it
}

TEST(BudgetSelection, DrawnSurfaceWithinReportedError)
{
  int measured = 0;
  double worstRatio = 0.0;
  for (const Case& c : cases())
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(c.hf, c.blockQuads, 1), "");
    for (const gmm::View& v : flight(c.hf, 8))
    {
      for (std::size_t budget : { 600u, 5000u, 40000u })
      {
        const gmm::FrameStats s = e.update(v, 0.0, budget);
        ASSERT_EQ(e.lastError(), "");
        const double bound = s.maxScreenError;
        const ScreenMeasure m =
          measureScreenError(e.heightfield(), e.indices(), &v, bound, MeasureTransform(), drawnHeights(e).data());
        EXPECT_EQ(m.uncovered, 0u) << c.name << " " << m.first;
        EXPECT_EQ(m.violations, 0u) << c.name << " budget " << budget << ": measured " << m.maxDist
                                    << " px > reported " << bound << " px; " << m.first;
        EXPECT_LE(m.maxVertical, s.maxGeometricError * (1 + 1e-6) + 1e-5) << c.name;
        if (bound > 0)
          worstRatio = std::max(worstRatio, m.maxDist / bound);
        ++measured;
      }
    }
  }
  std::printf("[ budget ] %d frames measured; worst measured / reported = %.3f\n", measured, worstRatio);
}

// Budgeted frames against the tau-driven frame at its triangle count.
//  - Block by block (merged nodes off in both): phase 1 bisects a family of selections
//    whose count falls as tau grows, to within kBudgetTauPrecision (1 %), so its selection's
//    error is at most tau (1 + 1 %), and phase 2 only lowers it; no worse on average beyond
//    that precision's hundredth (one frame in 371 is 0.4 % worse, within the precision).
//  - With merged nodes (the default, in both): a node drawn whole can cost more triangles
//    than its blocks or reach outside the view, so the count is not monotone in tau; a cold
//    search walks down through the bumps below its bracket (kWalkSteps), and on these
//    frames all but 2 of 315 are within the same 1 % of the tau-driven frame's error, those
//    up to 1.24x worse (up to 2.37x worse on 4 frames without the walk). Measured, not
//    guaranteed: with other terrain seeds 3 of 521 frames were up to 1.19x worse
//    (BudgetSelection.h). Also against what budgeted frames did before they used merged
//    nodes (block by block, against the same default tau-driven frames): worse no more
//    often; and better than the tau-driven frames on average.
TEST(BudgetSelection, NeverWorseThanTauAtTheSameTriangleCount)
{
  struct Tally
  {
    int compared = 0, positive = 0, worse = 0, worseBeyondPrecision = 0;
    double sumRatio = 0.0, worstRatio = 0.0;
    void add(double budgeted, double tauDriven)
    {
      ++compared;
      if (tauDriven > 0)
      {
        ++positive;
        sumRatio += budgeted / tauDriven;
        worstRatio = std::max(worstRatio, budgeted / tauDriven);
      }
      worse += budgeted > tauDriven * (1 + 1e-9);
      worseBeyondPrecision += budgeted > tauDriven * (1 + gmm::kBudgetTauPrecision) * (1 + 1e-9);
    }
    double mean() const { return sumRatio / std::max(positive, 1); }
  };
  Tally blockwise, merged, mergedBefore;
  int measured = 0;
  for (const Case& c : cases())
  {
    gmm::Engine tauBlocks, tauMerged, budgetBlocks, budgetMerged;
    ASSERT_EQ(tauBlocks.setHeightfield(c.hf, c.blockQuads, 1), "");
    for (gmm::Engine* e : { &tauMerged, &budgetBlocks, &budgetMerged })
      e->setTerrain(tauBlocks.terrain());
    tauBlocks.setMergedNodes(false);
    budgetBlocks.setMergedNodes(false);
    for (const gmm::View& v : flight(c.hf, 16))
    {
      for (double tau : { 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 64.0 })
      {
        const gmm::FrameStats t = tauBlocks.update(v, tau);
        if (t.triangles > 0)
        {
          // No nodata here, so the drawn count is blockTriangleCount's count.
          const gmm::FrameStats b = budgetBlocks.update(v, 0.0, t.triangles);
          ASSERT_FALSE(b.overBudget);
          EXPECT_LE(b.triangles, t.triangles);
          EXPECT_LE(b.maxScreenError, tau * (1 + gmm::kBudgetTauPrecision) * (1 + 1e-9))
            << c.name << " block by block, tau " << tau << " at " << t.triangles << " triangles";
          blockwise.add(b.maxScreenError, t.maxScreenError);
        }
        const gmm::FrameStats tm = tauMerged.update(v, tau);
        if (tm.triangles > 0)
        {
          const gmm::FrameStats bm = budgetMerged.update(v, 0.0, tm.triangles);
          EXPECT_LE(bm.triangles, tm.triangles);
          if (bm.maxScreenError > tm.maxScreenError * (1 + gmm::kBudgetTauPrecision) * (1 + 1e-9))
            std::printf("[ budget vs tau ] %s merged nodes, tau %g at %zu triangles: %.4f px against %.4f\n",
              c.name, tau, static_cast<std::size_t>(tm.triangles), bm.maxScreenError, tm.maxScreenError);
          // The errors compared are bounds of the drawn surfaces: the independent measure
          // stays within each (so a lower reported error is a lower true bound).
          for (const gmm::Engine* e : { &tauMerged, &budgetMerged })
          {
            const double bound = e->stats().maxScreenError;
            const ScreenMeasure m = measureScreenError(
              e->heightfield(), e->indices(), &v, bound, MeasureTransform(), drawnHeights(*e).data());
            EXPECT_EQ(m.violations, 0u) << c.name << " tau " << tau << ": " << m.first;
            ++measured;
          }
          merged.add(bm.maxScreenError, tm.maxScreenError);
          const gmm::FrameStats bb = budgetBlocks.update(v, 0.0, tm.triangles);
          mergedBefore.add(bb.maxScreenError, tm.maxScreenError);
        }
      }
    }
  }
  auto print = [](const char* what, const Tally& t) {
    std::printf("[ budget vs tau ] %s: %d frames, %d with an error; budgeted / tau-driven error: "
                "mean %.4f, worst %.4f, worse in %d\n",
      what, t.compared, t.positive, t.mean(), t.worstRatio, t.worse);
  };
  print("block by block", blockwise);
  print("merged nodes", merged);
  print("block-by-block budget vs merged tau", mergedBefore);
  std::printf("[ budget vs tau ] %d merged-node frames measured within their reported bounds\n", measured);
  EXPECT_GT(blockwise.compared, 100);
  EXPECT_GT(merged.compared, 100);
  EXPECT_LE(blockwise.mean(), 1.0 + 1e-2 * gmm::kBudgetTauPrecision);
  EXPECT_LE(merged.worse, mergedBefore.worse);
  EXPECT_LT(merged.mean(), 1.0);
  // Merged nodes: measured, not guaranteed (above): worse than the precision on at most 1 %
  // of the frames, by at most 1.25x (2 frames, 1.24x, since blocks are power-of-two bands).
  EXPECT_LE(merged.worseBeyondPrecision * 100, merged.positive);
  EXPECT_LE(merged.worstRatio, 1.25);
}

// A warm start (update's startTau: the previous frame's budgetTau) along a smooth flight,
// against cold starts of the same frames:
//  - within the budget, and the drawn surface within the reported error (independent
//    measure, every fourth frame);
//  - a function of its arguments: a fresh engine given the same start draws the same
//    triangles (what lets vtkGeoMipMapFilter reproduce a frame the mapper drew);
//  - no worse in kind: the search finds the boundary nearest its start, which is the cold
//    search's where the count is monotone in tau; over the flight the errors agree on
//    average within 1 %, and no frame is more than 10 % worse;
//  - shorter: fewer whole selections than the cold searches (the point of it).
TEST(BudgetSelection, WarmStartAlongAFlight)
{
  int warmTrials = 0, coldTrials = 0, frames = 0, worse = 0, measured = 0;
  double sumRatio = 0.0, worstRatio = 0.0;
  for (const Case& c : cases())
  {
    gmm::Engine warm, cold;
    ASSERT_EQ(warm.setHeightfield(c.hf, c.blockQuads, 1), "");
    cold.setTerrain(warm.terrain());
    for (std::size_t budget : { 3000u, 12000u })
    {
      double start = 0.0;
      const std::vector<gmm::View> views = flight(c.hf, 40);
      for (std::size_t k = 0; k + 2 < views.size(); ++k) // the flight, not its last two views
      {
        const gmm::View& v = views[k];
        const gmm::FrameStats w = warm.update(v, 0.0, budget, start);
        ASSERT_EQ(warm.lastError(), "");
        EXPECT_EQ(w.budgetStartTau, start);
        start = w.budgetTau;
        const gmm::FrameStats col = cold.update(v, 0.0, budget);
        if (w.overBudget || col.overBudget || !col.budgetReached)
        {
          continue;
        }
        ++frames;
        EXPECT_LE(w.triangles, budget) << c.name;
        gmm::Engine replay;
        replay.setTerrain(warm.terrain());
        replay.update(v, 0.0, budget, w.budgetStartTau);
        EXPECT_EQ(replay.indices(), warm.indices()) << c.name << " frame " << k << ": not reproduced";
        if (k % 4 == 0)
        {
          const ScreenMeasure m = measureScreenError(
            warm.heightfield(), warm.indices(), &v, w.maxScreenError, MeasureTransform(), drawnHeights(warm).data());
          EXPECT_EQ(m.violations, 0u) << c.name << " frame " << k << ": " << m.first;
          ++measured;
        }
        if (k > 0) // the first frame has no start: it is the cold search
        {
          warmTrials += w.budgetTrials;
          coldTrials += col.budgetTrials;
        }
        const double ratio = col.maxScreenError > 0 ? w.maxScreenError / col.maxScreenError : 1.0;
        sumRatio += ratio;
        worstRatio = std::max(worstRatio, ratio);
        worse += ratio > 1 + 1e-9;
      }
    }
  }
  std::printf("[ warm start ] %d frames (%d measured): selections %d warm against %d cold; warm / cold "
              "error mean %.4f, worst %.4f, worse in %d\n",
    frames, measured, warmTrials, coldTrials, sumRatio / std::max(frames, 1), worstRatio, worse);
  EXPECT_GT(frames, 100);
  EXPECT_LT(warmTrials, 0.7 * coldTrials);
  EXPECT_LE(sumRatio / std::max(frames, 1), 1.01);
  EXPECT_LE(worstRatio, 1.1);
}

TEST(BudgetSelection, TauStopsWhenItComesFirst)
{
  const Case c = cases().front();
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(c.hf, c.blockQuads, 1), "");
  for (const gmm::View& v : flight(c.hf, 6))
  {
    const gmm::FrameStats full = e.update(v, 0.0, std::size_t(1) << 40);
    EXPECT_FALSE(full.budgetReached);
    EXPECT_EQ(full.maxScreenError, 0.0); // tau 0, unlimited: refined to exactness
    const gmm::FrameStats s = e.update(v, 2.0, std::size_t(1) << 40);
    EXPECT_FALSE(s.budgetReached);
    EXPECT_LE(s.maxScreenError, 2.0);
    const ScreenMeasure m =
      measureScreenError(e.heightfield(), e.indices(), &v, 2.0, MeasureTransform(), drawnHeights(e).data());
    EXPECT_EQ(m.violations, 0u) << m.first;
  }
}

// A view whose blocks all fit the budget at full resolution: the frame is the full-resolution
// frame (every block in view at level 0, error 0), found without sweeping tau down to
// kLowestBudgetTau (about 25 selections before; over Puget Sound 37 ms of a 100 ms frame).
// fullResolutionTrianglesInView is checked against the block-by-block tau 0 frame's drawn
// triangles (no nodata here): every block in view at level 0, two triangles a quad.
TEST(BudgetSelection, FullResolutionWithinBudgetIsFoundAtOnce)
{
  int frames = 0;
  for (const Case& c : cases())
  {
    gmm::Engine full, budgeted;
    ASSERT_EQ(full.setHeightfield(c.hf, c.blockQuads, 1), "");
    budgeted.setTerrain(full.terrain());
    full.setMergedNodes(false);
    for (const gmm::View& v : flight(c.hf, 8))
    {
      const gmm::FrameStats f = full.update(v, 0.0);
      if (f.triangles == 0)
      {
        continue;
      }
      const gmm::Frustum frustum =
        gmm::transformPlanes(gmm::frustumOf(v), gmm::heightfieldToWorld(v, c.hf.z0, 1.0));
      EXPECT_EQ(gmm::fullResolutionTrianglesInView(full.quadtree(), frustum), f.triangles) << c.name;
      for (std::size_t slack : { std::size_t(0), f.triangles / 2 })
      {
        const gmm::FrameStats b = budgeted.update(v, 0.0, f.triangles + slack);
        EXPECT_EQ(b.maxScreenError, 0.0) << c.name;
        EXPECT_LE(b.triangles, f.triangles) << c.name;
        EXPECT_LE(b.budgetTrials, 1) << c.name << ": " << b.budgetTrials << " selections";
        const ScreenMeasure m = measureScreenError(
          budgeted.heightfield(), budgeted.indices(), &v, 1e-9, MeasureTransform(), drawnHeights(budgeted).data());
        EXPECT_EQ(m.violations, 0u) << c.name << ": " << m.first;
        ++frames;
      }
    }
  }
  EXPECT_GT(frames, 20);
}

TEST(BudgetSelection, CoarsestOverBudgetIsDrawnAndReported)
{
  const Case c = cases().front();
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(c.hf, c.blockQuads, 1), "");
  const gmm::View v = flight(c.hf, 4)[4]; // the high oblique: every block in view
  const gmm::FrameStats s = e.update(v, 1.0, 1);
  EXPECT_TRUE(s.overBudget);
  EXPECT_TRUE(s.budgetReached);
  EXPECT_EQ(s.triangleBudget, 1u);
  EXPECT_EQ(s.mergedNodes, 0); // over budget: block by block, whatever the merged-node setting
  EXPECT_EQ(s.triangles, 2u * s.visibleBlocks); // each visible block one quad
  for (int b = 0; b < e.quadtree().blockCount(); ++b)
    if (e.levels()[b] >= 0)
      EXPECT_EQ(e.levels()[b], refTopLevel(e.quadtree().blockWidth(b), e.quadtree().blockHeight(b)));
}

TEST(BudgetSelection, NoBudgetIsTheTauFrame)
{
  const Case c = cases().back();
  gmm::Engine a, b;
  ASSERT_EQ(a.setHeightfield(c.hf, c.blockQuads, 1), "");
  b.setTerrain(a.terrain());
  for (const gmm::View& v : flight(c.hf, 5))
  {
    const gmm::FrameStats sa = a.update(v, 1.5);
    const gmm::FrameStats sb = b.update(v, 1.5, 0);
    EXPECT_EQ(a.levels(), b.levels());
    EXPECT_EQ(a.indices(), b.indices());
    EXPECT_EQ(sa.maxScreenError, sb.maxScreenError);
    EXPECT_EQ(sb.triangleBudget, 0u);
    EXPECT_FALSE(sb.budgetReached);
  }
}

TEST(BudgetSelection, BadInputIsRefused)
{
  const Case c = cases().back();
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(c.hf, c.blockQuads, 1), "");
  const gmm::View v = flight(c.hf, 2)[0];
  EXPECT_EQ(e.update(v, std::nan(""), 1000).triangles, 0u);
  EXPECT_NE(e.lastError(), "");
  EXPECT_EQ(e.update(v, -1.0, 1000).triangles, 0u);
  EXPECT_NE(e.lastError(), "");
  gmm::View bad = v;
  bad.forward = { 0, 0, 0 };
  EXPECT_EQ(e.update(bad, 1.0, 1000).triangles, 0u);
  EXPECT_NE(e.lastError(), "");
  gmm::Engine empty;
  EXPECT_EQ(empty.update(v, 1.0, 1000).triangles, 0u);
  EXPECT_NE(empty.lastError(), "");
}
