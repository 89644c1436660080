#include "ErrorProjection.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gmm
{

namespace
{

// selectLevels reads a zero factor as "culled", so a visible block keeps a positive one
// even when the exact value underflows.
double visibleFactor(double f)
{
  return std::max(f, std::numeric_limits<double>::min());
}

// The tight factor's ratio is usable when no corner's across-the-vertical square
// overflowed or underflowed (a zero one may be an underflow: a corner exactly on the
// eye's vertical takes the loose bound instead) and the ratio is finite.
bool tightRatioUsable(const double* across, int corners, double ratio)
{
  for (int k = 0; k < corners; ++k)
  {
    if (!(across[k] >= std::numeric_limits<double>::min() && across[k] <= std::numeric_limits<double>::max()))
    {
      return false;
    }
  }
  return ratio <= std::numeric_limits<double>::max();
}

} // namespace

BoxProjector::BoxProjector(const View& view, const glm::dmat4& toWorld, ErrorMetric metric)
  : view_(view)
  , toWorld_(toWorld)
  , metric_(metric)
  , cam_(cameraFrameOf(view))
{
  // World length of a unit stored-height error: height scale times the actor's z column.
  const double vertical = robustLength(glm::dvec3(toWorld[2]));
  ppu_ = pixelsPerUnit(view) * vertical;
  for (int a = 0; a < 3; ++a)
  {
    for (int c = 0; c < 4; ++c)
    {
      column_[c][a] = toWorld[c][a];
    }
    eye_[a] = view.eye[a];
    forward_[a] = cam_.forward[a];
  }
  diagonal_ = true;
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a)
      diagonal_ = diagonal_ && (a == c || column_[c][a] == 0.0);
  // The unit direction of a stored-height error in the world. Exactly (0, 0, +-1) in a
  // diagonal frame, so that the corner loop's cross products there are the plain
  // horizontal terms diagonalFactor takes.
  for (int a = 0; a < 3; ++a)
  {
    up_[a] = diagonal_ ? (a == 2 ? (column_[2][2] < 0.0 ? -1.0 : 1.0) : 0.0) : column_[2][a] / vertical;
  }
  for (int a = 0; a < 3; ++a)
  {
    for (int lane = 0; lane < 2; ++lane)
    {
      lanes_.scale[a][lane] = column_[a][a];
      lanes_.offset[a][lane] = column_[3][a];
      lanes_.eye[a][lane] = eye_[a];
      lanes_.forward[a][lane] = forward_[a];
    }
  }
}

double BoxProjector::factor(const Box& box) const
{
  if (view_.parallel)
  {
    return visibleFactor(ppu_); // orthographic: same scale at every depth
  }
  if (metric_ == ErrorMetric::CenterDistance)
  {
    const glm::dvec3 centre(toWorld_ * glm::dvec4(0.5 * (box.lo + box.hi), 1.0));
    const double d = robustLength(centre - view_.eye);
    return visibleFactor(ppu_ / std::max(d, view_.nearDistance));
  }
  double f = 0.0;
  return diagonal_ && diagonalFactor(box, f) ? f : cornerFactor(box);
}

// The world image of the box is the parallelepiped spanned by its transformed corners;
// depth is linear, distance convex and |v x p| / Z quasi-convex (design.md, "Projecting the
// error"), so every extreme is at a corner. Each corner is toWorld * (x, y, z, 1) summed in
// glm's order, (c0 x + c1 y) + (c2 z + c3), from per-axis terms: the very same doubles with
// 6 products instead of 8 matrix-vector products.
//
// With a diagonal toWorld, the corner term of axis a is (column_[a][a] * (lo or hi) +
// column_[3][a]) - eye_[a], the same doubles as cornerFactor's (the other columns add exact
// zeros), and up_ is (0, 0, +-1), so a corner's across-the-vertical square is q1^2 + q0^2
// exactly. Rounded addition is monotone in each operand, so the smallest depth is the sum
// of each axis's smallest term, each (x, y) column's smallest depth is at the height axis's
// smallest term (where its ratio is largest), and the loose bound's largest
// (q0^2 + q1^2) + q2^2 is the sum of each axis's largest square: the same values as the
// corner loop. False when a square overflowed or underflowed: cornerFactor then takes each
// length robustly. (An axis's lo and hi terms are computed side by side where SSE2 is.)
bool BoxProjector::diagonalFactor(const Box& box, double& factor) const
{
  const double lo[3] = { box.lo.x, box.lo.y, box.lo.z }, hi[3] = { box.hi.x, box.hi.y, box.hi.z };
  // Per axis, the lo and hi corner terms' squares and depth terms ([axis][lo, hi]).
  double square[3][2], depthTerm[3][2];
#if defined(__SSE2__)
  // The lo and hi terms of an axis side by side in the two lanes of a register: the same
  // IEEE operations on the same operands, so the same doubles.
  for (int a = 0; a < 3; ++a)
  {
    const __m128d q = _mm_sub_pd(
      _mm_add_pd(_mm_mul_pd(_mm_load_pd(lanes_.scale[a]), _mm_set_pd(hi[a], lo[a])), _mm_load_pd(lanes_.offset[a])),
      _mm_load_pd(lanes_.eye[a]));
    _mm_storeu_pd(square[a], _mm_mul_pd(q, q));
    _mm_storeu_pd(depthTerm[a], _mm_mul_pd(q, _mm_load_pd(lanes_.forward[a])));
  }
#else
  for (int a = 0; a < 3; ++a)
  {
    const double qLo = (column_[a][a] * lo[a] + column_[3][a]) - eye_[a];
    const double qHi = (column_[a][a] * hi[a] + column_[3][a]) - eye_[a];
    square[a][0] = qLo * qLo;
    square[a][1] = qHi * qHi;
    depthTerm[a][0] = qLo * forward_[a];
    depthTerm[a][1] = qHi * forward_[a];
  }
#endif
  // std::min / std::max as the corner loop takes them (lo first).
  const double nearestZ = std::min(depthTerm[2][0], depthTerm[2][1]);
  const double minDepth =
    (std::min(depthTerm[0][0], depthTerm[0][1]) + std::min(depthTerm[1][0], depthTerm[1][1])) + nearestZ;
  if (minDepth >= view_.nearDistance && minDepth > 0.0)
  {
    // The box beyond the near plane (the tight bound): the horizontal term of corner (i, j) is
    // q1^2 + q0^2 at every height, and its depth is least at the lower depth term of the
    // height axis (rounded addition is monotone), where its ratio is largest.
    double ratio = 0.0;
    bool usable = true;
#if defined(__SSE2__)
    // Both x columns (lanes) of one y row at a time: the scalar loop's operations, lane by
    // lane (SQRTPD and DIVPD round as SQRTSD and DIVSD do). A NaN ratio takes the loose
    // bound below either way (its across square is out of range).
    const __m128d squareX = _mm_loadu_pd(square[0]), depthX = _mm_loadu_pd(depthTerm[0]);
    const __m128d least = _mm_set1_pd(std::numeric_limits<double>::min());
    const __m128d most = _mm_set1_pd(std::numeric_limits<double>::max());
    __m128d largest = _mm_setzero_pd(), inRange = _mm_cmpeq_pd(largest, largest);
    for (int j = 0; j < 2; ++j)
    {
      const __m128d across = _mm_add_pd(_mm_set1_pd(square[1][j]), squareX);
      const __m128d depth = _mm_add_pd(_mm_add_pd(depthX, _mm_set1_pd(depthTerm[1][j])), _mm_set1_pd(nearestZ));
      largest = _mm_max_pd(largest, _mm_div_pd(_mm_sqrt_pd(across), depth));
      inRange = _mm_and_pd(inRange, _mm_and_pd(_mm_cmpge_pd(across, least), _mm_cmple_pd(across, most)));
    }
    ratio = std::max(_mm_cvtsd_f64(largest), _mm_cvtsd_f64(_mm_unpackhi_pd(largest, largest)));
    usable = _mm_movemask_pd(inRange) == 3 && ratio <= std::numeric_limits<double>::max();
#else
    double across[2][2];
    for (int i = 0; i < 2; ++i)
    {
      for (int j = 0; j < 2; ++j)
      {
        across[i][j] = square[1][j] + square[0][i];
        ratio = std::max(ratio, std::sqrt(across[i][j]) / ((depthTerm[0][i] + depthTerm[1][j]) + nearestZ));
      }
    }
    usable = tightRatioUsable(&across[0][0], 4, ratio);
#endif
    if (usable)
    {
      factor = visibleFactor(ppu_ * ratio / minDepth);
      return true;
    }
  }
  // Loose: each axis's largest square and smallest depth term.
  const double maxSquare = (std::max(square[0][0], square[0][1]) + std::max(square[1][0], square[1][1])) +
    std::max(square[2][0], square[2][1]);
  if (!(std::isfinite(maxSquare) && maxSquare >= std::numeric_limits<double>::min()))
  {
    return false;
  }
  const double depth = std::max(minDepth, view_.nearDistance);
  factor = visibleFactor(ppu_ * (std::sqrt(maxSquare) / depth) / depth);
  return true;
}

double BoxProjector::cornerFactor(const Box& box) const
{
  // The corners computed side by side, axis by axis (q[axis][corner]: 2.7x faster than a
  // loop of vectors, the same values); the largest distance is the root of the largest
  // square (sqrt is monotone and correctly rounded: the same value).
  const double lo[3] = { box.lo.x, box.lo.y, box.lo.z }, hi[3] = { box.hi.x, box.hi.y, box.hi.z };
  double q[3][8];
  for (int a = 0; a < 3; ++a)
  {
    const double x0 = column_[0][a] * lo[0], x1 = column_[0][a] * hi[0];
    const double y0 = column_[1][a] * lo[1], y1 = column_[1][a] * hi[1];
    const double z0 = column_[2][a] * lo[2] + column_[3][a], z1 = column_[2][a] * hi[2] + column_[3][a];
    const double xy[4] = { x0 + y0, x1 + y0, x0 + y1, x1 + y1 };
    for (int k = 0; k < 4; ++k)
    {
      q[a][k] = (xy[k] + z0) - eye_[a];
      q[a][k + 4] = (xy[k] + z1) - eye_[a];
    }
  }
  double maxSquare = 0.0, minDepth = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k)
  {
    const double square = (q[0][k] * q[0][k] + q[1][k] * q[1][k]) + q[2][k] * q[2][k];
    const double depth = (q[0][k] * forward_[0] + q[1][k] * forward_[1]) + q[2][k] * forward_[2];
    maxSquare = std::max(maxSquare, square);
    minDepth = std::min(minDepth, depth);
  }
  if (minDepth >= view_.nearDistance && minDepth > 0.0)
  {
    // Tight: the box beyond the near plane. up_ x q is the part of a corner's offset across
    // the vertical; its length over the corner's depth is largest at a corner.
    double across[8], ratio = 0.0;
    for (int k = 0; k < 8; ++k)
    {
      const double c0 = up_[1] * q[2][k] - up_[2] * q[1][k];
      const double c1 = up_[2] * q[0][k] - up_[0] * q[2][k];
      const double c2 = up_[0] * q[1][k] - up_[1] * q[0][k];
      across[k] = (c0 * c0 + c1 * c1) + c2 * c2;
      const double depth = (q[0][k] * forward_[0] + q[1][k] * forward_[1]) + q[2][k] * forward_[2];
      ratio = std::max(ratio, std::sqrt(across[k]) / depth);
    }
    if (tightRatioUsable(across, 8, ratio))
    {
      return visibleFactor(ppu_ * ratio / minDepth);
    }
  }
  double maxDist = std::sqrt(maxSquare);
  if (!(std::isfinite(maxSquare) && maxSquare >= std::numeric_limits<double>::min()))
  {
    maxDist = 0.0; // a square overflowed or underflowed: take each length robustly
    for (int k = 0; k < 8; ++k)
    {
      maxDist = std::max(maxDist, robustLength(glm::dvec3(q[0][k], q[1][k], q[2][k])));
    }
  }
  const double depth = std::max(minDepth, view_.nearDistance);
  // Divide twice rather than by depth^2, which overflows first. +inf (a near plane of
  // 1e-300) is allowed: selectLevels then gives the block a zero error budget.
  return visibleFactor(ppu_ * (maxDist / depth) / depth);
}

void projectionFactors(const Quadtree& qt, const View& view, const glm::dmat4& toWorld,
  const std::vector<int>& visible, ErrorMetric metric, std::vector<double>& factor)
{
  factor.assign(qt.blockCount(), 0.0);
  const BoxProjector projector(view, toWorld, metric);
  for (int b : visible)
  {
    factor[b] = projector.factor(qt.blockBox[b]);
  }
}

} // namespace gmm
