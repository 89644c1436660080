// Geomorphing's path through a block's levels: a continuous level that moves at a bounded
// rate as the camera moves, so that the morph from one level to the next is spread over a
// range of distances instead of squeezed into the sliver where two levels' errors are close.
//
// Why: the largest morph factor that keeps the certificate (Morph.h) is t = (x - E_m) /
// (E_m' - E_m) for a block at level m with error budget x = tau / f. It moves by
// x / (E_m' - E_m) per unit of ln f, so where the next level's error E_m' is close to E_m
// the whole morph happens within a step of the camera and the surface still pops; a
// block that must refine at that point jumps from its coarse surface to a fine one.
//
// The path: with the block's levels as a chain v_0 = 0 < v_1 < ... (each the next valid
// level, Morph.h's target), lambda_max(x) = k + (x - E_k) / (E_k+1 - E_k) on the segment
// E_k <= x < E_k+1 is the furthest the certificate lets the block go. The drawn path is the
// largest function below it whose slope in ln x is at most s = 1 / ln(range):
//
//   lambda(x) = min over y <= x of  lambda_max(y) + s ln(x / y)
//
// which moves by at most s per unit of ln x in either direction (a smaller budget only
// removes candidates y; a larger one adds s ln(x'/x)) and needs no history: the levels,
// hence the triangles, are a function of the camera (only the rise limit below remembers
// the last frame's morph factors). The block is
// drawn at v_floor(lambda), morphing toward the next level by frac(lambda). lambda <=
// lambda_max, so the level is never coarser than the coarsest within tau: the path only
// costs triangles (blocks one level finer than needed where levels' errors are close).
#pragma once

#include "ErrorTable.h"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace gmm
{

// The default range: a level's morph spans at least this ratio of distances. With levels
// that nest inside blocks, 2 draws 1.05 - 1.3x the triangles of no geomorphing on real DEMs
// and wide views (1.1 - 1.4x with merges on the path, the mapper's default), against
// 1.3 - 2.6x at 3, with no larger worst pop (decision record 002).
constexpr double kDefaultMorphRange = 2.0;

// The path's slope: levels per unit of ln(distance), 1 / ln(range).
double rampSlope(double range);

// The rate limit on a drawn block's morph (Morph.h, computeMorph): from one frame to the
// next its continuous level (chain index + factor) rises by at most rampSlope(range) per unit
// of |ln f| change of its projection factor, plus this much per frame so that a still camera
// still settles. A factor is otherwise free to jump up where a neighbour's level change lifts
// a strip's cap on it; lowering a factor always keeps the certificate.
constexpr double kMorphSettlePerFrame = 0.02;

// The rate limit in pixels: beyond what its path rose since the last frame (or, for an
// edge, what the block setting it rose), a block's or an edge's factor rises by at most as
// much as moves its vertices this far on screen in a frame. A factor held down by a
// constraint that a neighbour's switch releases (a strip's fit, an edge's setter) would
// otherwise jump to the path's value in one frame.
constexpr double kMorphRisePixels = 0.1;

// While merges wait for the path (MorphRamp::mergeOnPath), a quadtree node whose fan is not
// its blocks' surface (over more than 2 x 2 blocks: mergeNestsInBlocks, Tessellate.h) merges
// only where what the merge changes projects within this many pixels: the residual left
// after its corners glided onto the fan (FanMorph.h), or for the nodes that do not glide
// (bounds only, nodata below them), their error. A merge straight from the blocks changes
// the drawn surface by up to the fan's error and its children's: at tau's edge it popped
// (1.8 px on measure_pop_causes' flight over N48W125 at tau 2). The bound on a
// frame's pop (decision records 002, 006).
constexpr double kMergePopPixels = 0.3;

// The last part of a neighbour's path (its factor toward its next level below this) over
// which its strip at its next finer level is phased into a block's beside path
// (rampBesideFinerNeighbours, SelectLevels.h), so that the neighbour's refinement does not
// lower the block at once. Over the whole path (1) it added twice the LOD instructions for
// the same pops; over a quarter, a fast flight's worst pop rose (decision record 002).
constexpr double kBesidePhaseIn = 0.5;

// A quadtree node whose children glide onto its fan in a frame (FanMorph.h): its factor t
// in (0, 1], its projection factor (pixels per unit of stored height) and its table's
// errors of the children at their coarsest and of those children moved onto the fan.
struct FanPremerge
{
  int node;
  double t;
  double factor;
  float childrenError, movedError;
};

// The path's outcome for the blocks a frame selected, per block (stale for the others).
struct MorphRamp
{
  double range = 0.0;          // input: finite and > 1 follows the path, else plain
                               // coarsest-within-tau (NaN, +inf and <= 1 alike)
  bool mergeOnPath = false;    // input: merged nodes only where rampNodeTopBudget allows
                               // (SelectNodes.h), while the path is followed
  std::vector<int8_t> level;   // the path's level (the selection may refine it further)
  std::vector<float> factor;   // the path's morph factor toward the next level, in [0, 1]
  std::vector<double> lambda;  // the path's continuous level (index into the block's chain)
  // The nodes whose children glide onto their fans (hierarchical selections merging on the
  // path, SelectNodes.h; empty after any other), which computeMorph moves.
  std::vector<FanPremerge> premerging;
  // Per quadtree node, memo of rampNodeTopBudget (NaN: not computed yet) for the range
  // `nodeTopRange`; the engine clears it when its terrain changes.
  std::vector<double> nodeTop;
  double nodeTopRange = std::numeric_limits<double>::quiet_NaN();
  // Per block, memo of its own path's segment constants (rampPathConstants, ErrorTable::levels
  // a block: ownPath[b * levels + k]; NaN first: not computed yet) for the errors at
  // `ownPathErrors` and the slope `ownPathSlope`: the path's logarithms of a block's own
  // errors are the same every frame.
  std::vector<double> ownPath;
  const float* ownPathErrors = nullptr;
  double ownPathSlope = std::numeric_limits<double>::quiet_NaN();
  // Per quadtree node, memos of fanReadyBudget and fanMergeBudget (FanMorph.h; NaN: not
  // computed yet) for the range `fanMergeRange` and pixel error `fanMergeTau` (the residual's
  // gate is in pixels).
  std::vector<double> fanReady, fanMerge;
  double fanMergeRange = std::numeric_limits<double>::quiet_NaN();
  double fanMergeTau = std::numeric_limits<double>::quiet_NaN();
  // Drops the memos (a new terrain: they are of the old one's blocks).
  void forgetTerrain()
  {
    nodeTop.clear();
    fanReady.clear();
    fanMerge.clear();
    ownPath.clear();
    ownPathErrors = nullptr;
  }
  bool active() const { return range > 1.0 && range <= std::numeric_limits<double>::max(); }
  // rampSlope(range), remembered: a frame asks it for every block and neighbour.
  double slope() const
  {
    if (!(slopeOf_ == range))
    {
      slopeOf_ = range;
      slope_ = rampSlope(range);
    }
    return slope_;
  }

private:
  mutable double slopeOf_ = std::numeric_limits<double>::quiet_NaN();
  mutable double slope_ = 0.0;
};

// The levels block b morphs through, finest first: 0, then each next valid level
// (Morph.h's targets). Returns how many.
using MorphChain = std::array<int8_t, 32>;
int morphChain(const Quadtree& qt, int b, MorphChain& chain);

// lambda(budget) for the errors of a chain's levels (error[0..count), non-decreasing and
// finite: a chain ends at its first level that is not allowed), in [0, count - 1].
double rampPath(const double* error, int count, double budget, double range);
// The same with the slope s = rampSlope(range) given; with a `ceiling`, min(ceiling, the
// path): the same double, found sooner where the ceiling rules candidates out (a path's
// candidates on link k are at least k, so links at or above the ceiling are not looked at).
double rampPathWithSlope(const double* error, int count, double budget, double s,
  double ceiling = std::numeric_limits<double>::infinity());

// The path in closed form, for a slope s > 0: on a rising segment k (E_k < E_k+1) whose
// candidate's best y (s dE clamped to the segment) lies within the budget x, the candidate
// is k + (y - E_k) / dE + s ln x - s ln y = C_k + s ln x, and C_k does not depend on x. So
// lambda(x) = min(lambda_max(x), s ln x + the least C_k of those segments): one logarithm
// for a budget instead of one for each segment it could not rule out.
// rampPathConstants writes C_k for k in [0, max(count - 1, 1)) into `constant` (+inf for a
// segment that does not rise, and in constant[0] for a chain of fewer than two links).
void rampPathConstants(const double* error, int count, double s, double* constant);
// rampPathWithSlope(error, count, budget, s) from those constants: equal up to rounding
// (ln x - ln y against ln(x / y); about 1e-16 of s |ln y|), and never above lambda_max(x),
// which it computes as rampPathWithSlope does.
double rampPathFromConstants(const double* error, const double* constant, int count, double budget, double s);

// A floor under rampPathWithSlope for errors that are 0 below index j (>= 1) and errorJ
// (finite, > 0) at j, whatever the errors above: j - 1 + min(1, s, budget / errorJ). No
// logarithm: it lets a caller skip a path that cannot come below a level it already has.
double rampPathFloor(int j, double errorJ, double budget, double s);

// The smallest budget at which rampPathWithSlope(error, count, budget, s) reaches the end of
// the chain, count - 1: the largest of error[count - 1] and, over each rising segment k,
// the budget x whose candidate k + (y - E_k) / dE + s ln(x / y) reaches count - 1 at the
// segment's worst y (s dE, clamped to the segment), since the path is the least of those
// candidates and non-decreasing in the budget.
double rampTopBudget(const double* error, int count, double s);

// Merging on the path (SelectNodes.h): the smallest error budget at which every block below
// quadtree node `node` is at its top level on its own path (rampedLambda), +inf when one of
// them never is (nodata). A node's projection factor is at least each of its blocks' (its
// box holds theirs; up to rounding), so a node whose budget is at least this has all its
// blocks at their top level: merging it then replaces one-quad blocks, which a 2 x 2 node
// draws exactly (Tessellate.h), instead of blocks several levels finer, which popped.
// Memoised in `ramp` (for its range) and computed only for the nodes asked about.
double rampNodeTopBudget(const Quadtree& qt, const ErrorTable& t, MorphRamp& ramp, int node);

// The first link of a chain (from morphChain, `links` of them) whose level is above `level`
// (>= 0); `links` when none is. Every link but the last is its own index (0, 1, 2, ...), so
// this is one comparison instead of a walk along the chain.
inline int firstLinkAbove(const MorphChain& chain, int links, int level)
{
  const int j = level + 1 < links - 1 ? level + 1 : links - 1;
  return chain[j] > level ? j : j + 1;
}

// Position of valid level `level` on the block's chain (the computeMorph rise limit's
// continuous level is this plus the factor).
int chainIndex(const Quadtree& qt, int block, int level);

// lambda of block b (its chain from morphChain) on the path of its own errors for error
// budget `budget` (stored-height units), on ramp's path (ramp.active()): from the block's
// constants (rampPathFromConstants), memoised in `ramp` the first time the block is asked.
double rampedLambda(const ErrorTable& t, int b, const MorphChain& chain, int links, double budget,
  MorphRamp& ramp);

// lambda of block b (its chain) on the path that keeps the strip of a finer neighbour `nb` (level
// `nbLevel`, its side `nbSide` facing b) within that neighbour's budget as b coarsens: the
// edge is sampled at b's level once that is coarser, so the neighbour's strip error is a
// function of b's level (0 while b's level is at most nbLevel). A coarse neighbour that the strip does not fit
// is refined by fixStrips (SelectLevels.h) at once, which pops; this path gets there
// smoothly instead. With a `ceiling`, min(ceiling, that lambda) (rampPathWithSlope).
double rampedLambdaBeside(const ErrorTable& t, const MorphChain& chain, int links, int nb,
  int nbSide, int nbLevel, double nbBudget, double slope,
  double ceiling = std::numeric_limits<double>::infinity());

// The level and factor of continuous level `lambda` on `chain` (count levels).
int levelOnChain(const MorphChain& chain, int count, double lambda, float& factor);

} // namespace gmm
