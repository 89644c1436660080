// The projection of a stored-height error to pixels over a box, a bound (design.md,
// "Projecting the error"), and the error budget it gives a block or a node.
#pragma once

#include "Quadtree.h"
#include "View.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gmm
{

enum class ErrorMetric
{
  // Certified: a vertical displacement of length delta at p (relative to the eye, depth Z)
  // projects to at most f * delta * |v x p| / Z^2 pixels (f = pixels per unit at depth 1,
  // v the unit vertical). Over a box beyond the near plane that is at most
  // f * delta * maxAcross / minDepth, maxAcross the largest |v x p| / Z over the box (at a
  // corner: its level sets are convex cones) and minDepth its smallest depth ("tight");
  // over a box that reaches the near plane, f * delta * maxDist / max(minDepth, near)^2 with
  // maxDist the largest eye distance ("loose", never below the tight one). This also
  // covers the off-axis magnification that delta * f / distance misses.
  Certified,
  // de Boer's approximation: f * delta / (distance from eye to box centre). Cheaper and not
  // a bound; offered for comparison.
  CenterDistance
};

// Pixels per unit of stored-height error for each listed (visible) block; 0 for the others.
// `toWorld` maps the quadtree's frame to the view's world (heightfieldToWorld): each box's
// corners are taken to world coordinates, where the bound is evaluated, and a vertical
// error of 1 becomes a world displacement of |toWorld * (0, 0, 1, 0)|. Exact for any
// affine toWorld: a non-uniform scale or shear moves both.
void projectionFactors(const Quadtree& qt, const View& view, const glm::dmat4& toWorld,
  const std::vector<int>& visible, ErrorMetric metric, std::vector<double>& factor);

// The factor of projectionFactors for any box of the quadtree's frame (a block's, a
// node's): pixels per unit of stored-height error anywhere inside it, always > 0.
class BoxProjector
{
public:
  BoxProjector(const View& view, const glm::dmat4& toWorld, ErrorMetric metric);
  double factor(const Box& box) const;
  // The certified factor from the box's 8 corners, for any affine toWorld: factor's own
  // path for a toWorld that is not diagonal. For a diagonal one, factor takes the extremes
  // axis by axis instead, which gives the very same double (tests compare the two).
  double cornerFactor(const Box& box) const;

private:
  // The certified factor for a diagonal toWorld, axis by axis; false when it cannot tell
  // (a square out of range). Tight: 4 corner columns (x, y) at the box's lower depth term.
  bool diagonalFactor(const Box& box, double& factor) const;
  View view_;
  glm::dmat4 toWorld_;
  ErrorMetric metric_;
  CameraFrame cam_;
  double ppu_ = 0.0;
  // toWorld's first four columns' x, y, z, the eye and the view direction, as plain
  // doubles for factor's corner loops.
  double column_[4][3] = {};
  double eye_[3] = {};
  double forward_[3] = {};
  double up_[3] = {}; // the unit world direction of a stored-height error
  // toWorld's linear part is diagonal (a DEM's usual frame: spacing, height scale and an
  // offset): each corner term then depends on one box coordinate, and factor takes the
  // extremes axis by axis.
  bool diagonal_ = false;
  // diagonalFactor's per-axis operands, each twice (a lane for the box's lo, one for its
  // hi), aligned for SSE2 loads.
  struct alignas(16) DiagonalLanes
  {
    double scale[3][2], offset[3][2], eye[3][2], forward[3][2];
  } lanes_ = {};
};

// The largest stored-height error that projects within tau pixels at `factor`: tau /
// factor, clamped to a finite value (an infinite budget would accept the +inf of levels
// that are not allowed), 0 for an infinite factor.
// Inline: the quadtree walk asks it for every node it considers drawing whole.
inline double errorBudget(double tau, double factor)
{
  // tau / factor overflows for a huge tau or a tiny factor (a far camera); +inf would let
  // "error <= budget" accept the +inf of levels not allowed (over nodata).
  const double most = std::numeric_limits<double>::max();
  return std::isfinite(factor) ? std::min(tau / factor, most) : 0.0;
}

} // namespace gmm
