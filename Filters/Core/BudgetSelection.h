// Budgeted level selection: the smallest certified error a triangle budget allows.
//
// NDL's sorted heightfield renderer fixes a frame's work and spends it by importance. Here
// in two phases:
//  1. the finest tau-driven selection (selectLevels) that fits the budget, found by
//     bisecting tau: every block's own error and strips within one tau, as cheaply as the
//     tau-driven mode would draw them, so the result is never worse than a tau-driven frame
//     that fits (up to the search's 1 % in tau, which phase 2 makes up for: see below);
//  2. then, with what is left of the budget, the drawn node whose projected certified
//     error is largest is refined, one level at a time, until the next refinement would
//     exceed the budget or the largest error is within tau. A refinement can raise the
//     largest error (a finer block meets a coarser neighbour across a strip), so the best
//     state seen is the one kept.
// The frame's certified error is the largest remaining projected error.
//
// Why two phases: a greedy loop alone, started from the coarsest levels, lost to the
// tau-driven selection at equal triangle counts on 20 % of the frames of the engine tests
// (by up to 45 %), because strip errors are not monotone in a block's own level and a
// local choice cannot see that; phase 1 gives the greedy a start that is already as good.
//
// Phase 2 refines the quadtree's leaf blocks (each a level plus four side strips stitched
// to its neighbours' edge levels). A node's certified error is blockCertifiedError
// times its projection factor: its own error at its level and the error of every strip
// joined to a coarser neighbour. Refining a node whose error is its own lowers its level;
// refining one whose error is a strip lowers the level of the neighbour across that strip
// (the only way to shrink a strip, as fixStrips does for tau). With merged nodes
// (SelectNodes.h; the engine's default), phase 1 searches the hierarchical selection
// instead (Engine::update) and phase 2 refines its blocks, leaving the merged nodes as
// they are: it stops when the largest error is a node's or a strip beside one (Merged).
#pragma once

#include "ErrorTable.h"
#include "Quadtree.h"
#include "SelectLevels.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gmm
{

// Phase 1 bisects tau in log space from max(tau, kLowestBudgetTau) up, until the bounds are
// within kBudgetTauPrecision, in at most kBudgetBisections steps (24 halve a ratio of 1e20
// to within 3e-6 in log: 0.0003 %). With merged nodes a warm start or a sweep comes first,
// and the steps interpolate (Engine::update).
// The precision, 1 %: phase 2 spends what a coarser phase-1 selection leaves of the budget,
// so the search's last steps bought almost nothing. Measured against 0.01 % (session 15):
// bench_core's BM_BudgetFlight (4097², 100 000 triangles, 400 frames) 7.7 -> 3.5 selections
// a frame, mean certified error +0.13 %; TestBudgetSelection's merged-node frames worse
// than the tau-driven ones at the same count in 5 of 280 instead of 4, mean ratio 0.9916
// against 0.9915.
constexpr double kLowestBudgetTau = 1e-6; // pixels: below it, a selection is exact in practice
constexpr double kBudgetTauPrecision = 1e-2;
constexpr int kBudgetBisections = 40;
// With merged nodes, a frame starts from the previous budgeted frame's tau (Engine::update):
// kWarmSteps steps away from it, the k-th by a factor kWarmStep^(2^k) (1.01 ... 1.38, 1.87 in
// all), before the cold start; and the search interpolates the crossing in log-log, each
// trial at least kInterpolationMargin of the bracket (in log tau) inside it.
// The first step is the precision: a crossing within it of the start closes the search in
// two selections. Against a first step of 1.02 (five steps): BM_BudgetFlight/4097 3.47 ->
// 2.14 selections a frame (held budget), 3.99 -> 2.97 (moving); TestBudgetSelection's
// flight, whose views jump further, 1 543 -> 1 627 selections in all.
constexpr double kWarmStep = 1.0 + kBudgetTauPrecision;
constexpr int kWarmSteps = 6;
constexpr double kInterpolationMargin = 0.02;
// A cold search then walks down through the selections below its bracket's failure, one at
// a time, at most kWalkSteps, until kWalkPatience in a row bring no new low of the count (a
// dip below the budget can lie beyond a bump). Measured (session 24) on
// TestBudgetSelection's merged-node frames, and on the same test with three other terrain
// seeds and 23 frames: frames worse than the tau-driven one at its count 4 / 9 / 9 / 14
// without the walk (up to 13.1x before session 24, 2.57x with its sweep), 0 / 0 / 2 / 3
// with it (the 2 within the 1 % precision, the 3 up to 1.19x). Patience 1: 0 / 3 / 4 / 9;
// 2: 0 / 0 / 3 / 5; 4: 0 / 0 / 2 / 2. Walking on while counts stay within 2 % of the least
// instead: 0 / 0 / 2 / 0, but at 100 000 triangles, where a step adds a few dozen, it always
// took all 16 steps (cold frames of BM_BudgetFlight/4097: 29.1 -> 45.0 selections; with
// patience 3, 32.1).
constexpr int kWalkSteps = 16;
constexpr int kWalkPatience = 3;

// Why refinement stopped.
enum class BudgetStop
{
  Tau,       // the largest projected error is within tau (or 0): the budget was not binding
  Budget,    // the next refinement would exceed the triangle budget
  OverBudget, // the coarsest selection alone exceeds the budget; it is drawn nonetheless
  Merged     // the largest error is a merged node's, or a strip beside one: only splitting
             // the node would lower it, which refinement does not do
};

struct BudgetOutcome
{
  // Triangles of the selection as counted by blockTriangleCount: what is drawn, or more
  // (a DEM one quad wide counts its nodata's triangles), so the drawn count is <= the budget
  // unless OverBudget.
  std::size_t triangles = 0;
  int refinements = 0; // levels lowered by one step
  double tau = 0.0; // with merged nodes (Engine::update), the tau whose selection phase 1 kept
  int trials = 0;   // whole selections phase 1 ran (its cost)
  BudgetStop stop = BudgetStop::Tau;
};

// Buffers reused from frame to frame (one per engine): nothing DEM-sized is cleared.
struct BudgetScratch
{
  struct Entry
  {
    double error;
    int block;
    uint32_t stamp;
  };
  std::vector<Entry> heap;       // lazy max-heap: entries with a stale stamp are skipped
  std::vector<uint32_t> stamp;   // per block, bumped whenever its error may have changed
  std::vector<std::size_t> count; // per drawn block, its triangles at its configuration
  struct Step
  {
    int block;
    int8_t level; // its level before the step
  };
  std::vector<Step> log;          // phase 2's refinements, to undo those after the best state
  std::vector<int8_t> trial;      // phase 1's candidate selection
  SelectionScratch select;
};

// Selects levels for the visible blocks (factor > 0; others get -1) within
// `triangleBudget` triangles (> 0) and tau pixels (finite, >= 0), as described above.
// `factor` comes from projectionFactors.
void selectLevelsWithinBudget(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& visible, const std::vector<double>& factor, double tau,
  std::size_t triangleBudget, std::vector<int8_t>& levels, BudgetScratch& scratch,
  BudgetOutcome& outcome);

// Triangles of the listed blocks that have a level (blockTriangleCount), each also written
// to perBlock[b] when given.
std::size_t selectionTriangles(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& drawn, const std::vector<int8_t>& levels,
  std::vector<std::size_t>* perBlock = nullptr);

// The largest projected certified error (pixels) of the listed blocks that have a level.
double selectionScreenError(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& drawn, const std::vector<int8_t>& levels, const std::vector<double>& factor);

// Phase 2 alone, on a selection made elsewhere: `drawn` lists the blocks that may have a
// level >= 0 (kCoveredLevel blocks belong to merged nodes, which stay); `fixedTriangles`
// and `fixedError` (pixels) are the merged nodes' triangles and largest projected error.
// outcome.triangles includes fixedTriangles.
void refineWithinBudget(const Quadtree& qt, const ErrorTable& table, const std::vector<int>& drawn,
  const std::vector<double>& factor, double tau, std::size_t triangleBudget,
  std::size_t fixedTriangles, double fixedError, std::vector<int8_t>& levels,
  BudgetScratch& scratch, BudgetOutcome& outcome);

} // namespace gmm
