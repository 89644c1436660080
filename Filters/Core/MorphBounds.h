// Exact errors of a block's parts with their vertices as drawn or at their morph targets:
// what the geomorph factors are chosen from (Morph.h).
//
// A part is the inner grid or one side strip (Tessellate's BlockPart). In a strip, the
// edge vertices (on the block's border, from their base heights: EdgeHeights.h) move with
// the edge's factor t_e and the inner-ring vertices with the block's factor t_b toward
// targets that follow the edges' factors (Morph.h, blockVertexTarget). On every triangle
// the drawn height is
//     S + t_e dE + t_b (dR + t_e dR_e + sum over the other sides k of t_k dR_k)
// (S the unmorphed triangle, dE and dR the interpolated displacements of its edge and ring
// vertices at factor 1 with the edges at their base heights, dR_e and dR_k how far the ring
// vertices' targets move with side e's and side k's edge): multilinear in the factors, so
// its distance to a sample is at most the multilinear interpolation of its distances at
// the factors' corners, and for any t_k in [0, 1] at most the largest over those. The
// corner errors E_er (e, r in {0, 1}) are the maxima over the part's samples of
// |S + e dE + r (dR + e dR_e + sum t_k dR_k) - h| with each t_k at its worst (0 or 1), and
// the strip's bound at (t_e, t_b) their bilinear interpolation. The inner grid has no edge
// vertex: its bound is (1 - t_b) E_0 + t_b E_1, every side's t_k at its worst, or with
// E_1 interpolated at the edges' factors from its errors at every corner of them
// (PartErrors::innerAt). These are exact maxima over samples, not estimates.
#pragma once

#include "ErrorTable.h"
#include "Heightfield.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace gmm
{

struct PartErrors
{
  double inner[2] = { 0.0, 0.0 }; // ring vertices as drawn / at their targets
  // innerAt[mask]: the inner grid with its ring vertices at their targets and side s's edge
  // at its target where bit s of `mask` is set, at its base heights elsewhere (so
  // innerAt[0] has every edge held and innerAt[15] is inner[1]), rounded up to float and
  // made non-decreasing in the mask (each the largest over its sub-masks): innerBound then
  // never grows when an edge's factor is lowered.
  float innerAt[16] = {};
  // side[s][e * 2 + r]: strip s with edge vertices (e) and ring vertices (r) as drawn (0)
  // or at their targets (1).
  double side[4][4] = {};
  bool innerFrozen = false;     // nodata involved: the part must not morph
  std::array<bool, 4> sideFrozen{ false, false, false, false };
  // The parts (masks below) whose corners are upper bounds taken from the error table
  // (tablePartBounds), not measured: valid while they are within the block's budget.
  unsigned bounded = 0;
};

// Bound of a strip at factors (te, tb): bilinear in the four corner errors. (Inline:
// computeMorph evaluates it about 25 times a drawn block and frame.)
inline double stripBound(const double e[4], double te, double tb)
{
  return (1.0 - te) * ((1.0 - tb) * e[0] + tb * e[1]) + te * ((1.0 - tb) * e[2] + tb * e[3]);
}

// Bound of the inner grid at block factor tb with the edges' factors te (by side): the
// multilinear interpolation of innerAt at te (the drawn height is affine in the edge factors,
// so the error is convex in them and at most that interpolation), then linear in tb from
// inner[0].
double innerBound(const PartErrors& errors, const std::array<double, 4>& te, double tb);
// The largest tb in [0, 1] with innerBound(errors, te, t) <= limit for every t in [0, tb].
double innerReach(const PartErrors& errors, const std::array<double, 4>& te, double limit);

// t in [0, 1] (NaN -> 0).
double clamp01(double t);
// Largest x in [0, 1] with a + x (b - a) <= limit, given a <= limit (the linear bound at 0
// holds): how far a linear bound may be pushed.
double linearReach(double a, double b, double limit);

// Largest t in [0, 1] with stripBound(e, t, t) <= limit on all of [0, t] (0 when it does
// not hold at 0): how far a block and an edge it sets may morph together.
double diagonalReach(const double e[4], double limit);

// Marks on block vertices that are all cleared at once: begin(n) starts a new generation
// over at least n vertices, and mark(v) is true the first time v is marked in it.
struct VertexMarks
{
  std::vector<uint32_t> stamp; // per vertex: the generation that marked it
  uint32_t generation = 0;
  void begin(std::size_t n)
  {
    if (stamp.size() < n)
    {
      stamp.resize(n, 0u);
    }
    if (++generation == 0) // wrapped: no stamp may look current
    {
      std::fill(stamp.begin(), stamp.end(), 0u);
      generation = 1;
    }
  }
  bool mark(std::size_t v)
  {
    const bool first = stamp[v] != generation;
    stamp[v] = generation;
    return first;
  }
  bool marked(std::size_t v) const { return stamp[v] == generation; }
};

// Buffers of morphPartErrors, reused from call to call: the part's triangles and each
// block vertex's displacement, found once per call although about six triangles share it.
struct MorphPartScratch
{
  EmitScratch emit;
  std::vector<GridTriangle> triangles;
  std::vector<double> displacement; // per block vertex: target height - height
  // Per block vertex, 4 per side: how far its target moves when that side's edge goes from
  // its base heights to its target (an interior vertex whose target cell reaches the side).
  std::vector<double> coupling;
  VertexMarks displaced;            // per call: the vertices whose displacement is set
  VertexMarks measured;             // per part: the vertices measured once (exact weights)
};

// Errors of every part of `block` drawn with `config`, its interior moving toward level
// `target` (-1: not moving) and side s's edge toward `edgeTarget[s]` (-1: not moving).
PartErrors morphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, MorphPartScratch& scratch);

// Parts as bits of a mask: bit 0 the inner grid, bit 1 + s side strip s.
constexpr unsigned kAllMorphParts = 0x1f;

// The parts of `errors` whose bits are set in `parts`, recomputed as morphPartErrors does;
// the others are left as they are. The inner grid depends on config.level and `target`
// alone, and side strip s on those and on config.edgeLevel[s] and edgeTarget[s] (block
// corners never move), so a neighbour's change of level or target costs one strip.
void updateMorphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts,
  PartErrors& errors, MorphPartScratch& scratch);

// Upper bounds of the corner errors of `block`'s parts from its error table, where they
// prove the part within `budget` at every factor, so that it need not be measured
// (computeMorph with a table: the largest certified factors are then the same, 1 capped by
// the path and the rise limit, as with the measured errors; only the bound reported for the
// frame is looser). A part's drawn surface moved by factors t moves by at most
// t_ring D_ring + t_edge D_edge at any sample (a sample's displacement interpolates its
// triangle's vertices'), so its corners are at most E + D: E its error as drawn (the
// block's own error at its level with its own edges, or the strip table's for a coarser
// edge), D_ring the block's exact error at its target level with the same edges (its own
// error there, and the strip table's toward edges coarser than the target: a ring vertex
// goes to that surface, blockVertexTarget), D_edge the strip table's error of the side at
// the edge's target level (which covers that polyline's samples) plus, on a glided edge,
// the side's polyline distance at its level (where its vertices start). Where level m
// nests in the target (a power-of-two block going one level up, Levels.h), a part with
// every vertex at its target is the target's surface: the inner grid's second corner is
// D_ring itself, and so is the last corner of a strip of the block's own cells (edge level
// m) whose edge moves to the same target; such a strip with only its ring vertices moved
// is that surface less the edge vertices' moves, within D_ring + p (p the side's samples'
// largest distance from its polyline at the target, measured along the side: one line of
// samples, not the strip's area). Blocks with a side that may be drawn at full resolution
// are left out (their targets do not follow that side). Writes the bounds of every part of
// `parts` it bounds into `errors`, with their bits set in errors.bounded (the other parts
// are left as they are), and returns those whose bounds are all <= budget.
// `polylines`, when given, keeps each side's polyline distance p from call to call.
class SidePolylineMemo;
unsigned tablePartBounds(const Heightfield& hf, const ErrorTable& table, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts, double budget,
  PartErrors& errors, MorphPartScratch& scratch, SidePolylineMemo* polylines = nullptr);

// The parts in errors.bounded whose largest corner exceeds `budget`: bounds that no longer
// prove their part within a smaller budget, so it must be measured.
unsigned boundedPartsOver(const PartErrors& errors, double budget);

} // namespace gmm
