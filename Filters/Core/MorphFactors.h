// The rules that turn a frame's part errors into its morph factors, as computeMorph
// (Morph.h) applies them once each drawn block has its factor: the edges fitted to their
// blocks' factors and strips, blocks that yield to a coarser neighbour's edge, inner grids
// fitted to their edges' factors, and the pixel rise limit on edges. Each reads the drawn
// blocks (MorphFrame::blocks) and their state in `cache` as computeMorph fills it (edges,
// budgets, part errors, history), and lowers or refits factors in `out`; none raises a
// factor above what the parts' bounds allow at the factors it leaves.
#pragma once

#include "Morph.h"

#include <array>
#include <cstdint>
#include <vector>

namespace gmm
{

// Factors are stored as float (what the shader reads): rounded down, never above the
// factor the certificate allows.
float factorDown(double t);

// The factors of a block's four edges (0 where an edge does not move).
std::array<double, 4> edgeFactors(const std::array<MorphEdge*, 4>& edges);

// kMorphRisePixels as a factor for block part errors `pe` seen at `factor` pixels per unit
// of height: a vertex moves by at most its target's error plus its drawn error (the
// triangle inequality through the sample), so a factor step of r moves it at most
// r (E_target + E_drawn) f on screen. side -1: the block's interior vertices (ring vertices
// at their targets with any edges); else that side's edge vertices.
double risePixels(const PartErrors& pe, int side, double factor);

// Edge factors: the largest factor of the blocks setting the edge (those at its level),
// lowered until both sides' strips fit their budgets with their blocks' factors. The edges
// start from 0 (resetMorph, or a refit).
void fitEdgeFactors(const std::vector<int8_t>& levels, MorphCache& cache, MorphFrame& out);

// A block whose strip holds a coarser neighbour's edge more than kMorphRisePixels below
// what it drew last frame (typically: the block set that edge before it refined) gives up
// some of its own factor instead, where that moves its vertices less on screen than the
// edge's drop would: the edge's vertices otherwise jump at the block's switch although the
// block's own morph is continuous across it (levels nest). The edge may still drop
// kMorphRisePixels a frame, so that a still camera settles where it would without this.
// Refits the edges when a block yielded. Needs the path's history (MorphBlockState).
void yieldToCoarserEdges(const Quadtree& qt, const std::vector<int8_t>& levels, const std::vector<double>& factor,
  MorphCache& cache, MorphFrame& out);

// The inner grids at their edges' factors (innerBound, MorphBounds.h): a block whose factor,
// chosen with its edges held, does not fit with them as fitted is lowered until it does;
// then the edges are fitted again to the lowered factors, never above what they were, so
// that every inner grid's bound (non-decreasing in the edges' factors) still holds.
void fitInnerGridsToEdges(const std::vector<int8_t>& levels, MorphCache& cache, MorphFrame& out);

// The pixel rise limit on edges (kMorphRisePixels): an edge drawn with the same level and
// target as in the last frame rises by at most what its fastest setter rose plus the
// pixel allowance of the more sensitive of its two blocks. Lowering an edge keeps both
// strips certified (its factor's bound is linear between held and as fitted).
void limitEdgeRises(const std::vector<int8_t>& levels, const std::vector<double>& factor, MorphCache& cache,
  MorphFrame& out);

} // namespace gmm
