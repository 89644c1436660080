#include "MorphBounds.h"

#include "EdgeHeights.h"
#include "Morph.h"
#include "RasterError.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gmm
{

namespace
{
// floor(a / b) and ceil(a / b), for b > 0.
long long floorDiv(long long a, long long b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

long long ceilDiv(long long a, long long b)
{
  return a >= 0 ? (a + b - 1) / b : -(-a / b);
}

// Twice the signed area of t (the sign gives its orientation).
long long doubledArea(const GridTriangle& t)
{
  const long long I[3] = { t.v[0].i, t.v[1].i, t.v[2].i }, J[3] = { t.v[0].j, t.v[1].j, t.v[2].j };
  return (I[1] - I[0]) * (J[2] - J[0]) - (I[2] - I[0]) * (J[1] - J[0]);
}

// Calls visit(i, j, w, vertexRow) for every sample of t (integer barycentric test, edges
// included), with w its three edge functions (orientation-signed as the triangle's doubled
// `area`) and vertexRow whether row j holds one of t's vertices; stops at, and returns, the
// first false. The edge functions are stepped in integers from
// the bounding box's corner, so every sample's weights are exact whatever the path to it.
// A wide triangle's rows visit only the span inside it (solved in integers: a test of every
// sample of the bounding box spent half its work outside); a narrow one tests its bounding
// box, which costs less than solving.
template <class Visit>
bool scanTriangle(const GridTriangle& t, long long area, Visit&& visit)
{
  const long long I[3] = { t.v[0].i, t.v[1].i, t.v[2].i }, J[3] = { t.v[0].j, t.v[1].j, t.v[2].j };
  const long long orient = area < 0 ? -1 : 1;
  const long long i0 = std::min({ I[0], I[1], I[2] }), i1 = std::max({ I[0], I[1], I[2] });
  const long long j0 = std::min({ J[0], J[1], J[2] }), j1 = std::max({ J[0], J[1], J[2] });
  // Edge function k (opposite vertex k, from vertex `from` to `to`):
  //   w_k(i, j) = (I[to] - I[from]) (j - J[from]) - (J[to] - J[from]) (i - I[from]);
  // the sample is inside when orient * w_k >= 0 for all three.
  static const int from[3] = { 1, 2, 0 }, to[3] = { 2, 0, 1 };
  long long stepI[3], stepJ[3], rowStart[3]; // w_k's steps along i and j, its value at (i0, j)
  for (int k = 0; k < 3; ++k)
  {
    const long long di = I[to[k]] - I[from[k]], dj = J[to[k]] - J[from[k]];
    stepI[k] = -dj;
    stepJ[k] = di;
    rowStart[k] = di * (j0 - J[from[k]]) - dj * (i0 - I[from[k]]);
  }
  constexpr long long kNarrow = 2; // bounding boxes up to this many quads wide are scanned
  for (long long j = j0; j <= j1; ++j)
  {
    long long w[3] = { rowStart[0], rowStart[1], rowStart[2] };
    for (int k = 0; k < 3; ++k)
    {
      rowStart[k] += stepJ[k];
    }
    const bool vertexRow = j == J[0] || j == J[1] || j == J[2];
    if (i1 - i0 <= kNarrow)
    {
      for (long long i = i0; i <= i1; ++i, w[0] += stepI[0], w[1] += stepI[1], w[2] += stepI[2])
      {
        if (orient * w[0] >= 0 && orient * w[1] >= 0 && orient * w[2] >= 0 && !visit(i, j, w, vertexRow))
        {
          return false;
        }
      }
      continue;
    }
    long long lo = i0, hi = i1;
    for (int k = 0; k < 3; ++k)
    {
      // orient * w_k(i) = B + A (i - i0), which must be >= 0:
      const long long A = orient * stepI[k], B = orient * w[k];
      if (A > 0)
      {
        lo = std::max(lo, i0 + ceilDiv(-B, A));
      }
      else if (A < 0)
      {
        hi = std::min(hi, i0 + floorDiv(B, -A));
      }
      else if (B < 0)
      {
        hi = lo - 1; // the row is outside this edge
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      w[k] += stepI[k] * (lo - i0);
    }
    for (long long i = lo; i <= hi; ++i, w[0] += stepI[0], w[1] += stepI[1], w[2] += stepI[2])
    {
      if (!visit(i, j, w, vertexRow))
      {
        return false;
      }
    }
  }
  return true;
}

// The largest |x + sum of a subset of a[k]| over the subsets of the sides other than
// `own` (-1: all four): the worst of the other edges' factors at 0 or 1 (MorphBounds.h).
inline double worstOverEdges(double x, const double a[4], int own)
{
  double up = 0.0, down = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    if (k != own)
    {
      (a[k] > 0.0 ? up : down) += a[k];
    }
  }
  return std::max(std::fabs(x + up), std::fabs(x + down));
}

// The inner grid's errors at each corner of the edges' factors (PartErrors::innerAt), as
// measured: the largest |x| over samples whose target moves with no edge, and per mask the
// largest |x + the sum of a[k] over its sides| over the others.
struct InnerCorners
{
  double still = 0.0;
  double at[16] = {};
  void add(double x, const double* a)
  {
    if (!a)
    {
      still = std::max(still, std::fabs(x));
      return;
    }
    double sum[16];
    sum[0] = x;
    at[0] = std::max(at[0], std::fabs(x));
    for (int mask = 1; mask < 16; ++mask)
    {
      const int low = mask & -mask;
      sum[mask] = sum[mask ^ low] + a[low == 1 ? 0 : low == 2 ? 1 : low == 4 ? 2 : 3];
      at[mask] = std::max(at[mask], std::fabs(sum[mask]));
    }
  }
  // PartErrors::innerAt: every corner with the still samples, rounded up to float, and made
  // non-decreasing in the mask (each the largest over its sub-masks).
  void finish(float out[16]) const
  {
    for (int mask = 0; mask < 16; ++mask)
    {
      out[mask] = roundUpToFloat(std::max(still, at[mask]));
    }
    for (int side = 0; side < 4; ++side)
    {
      for (int mask = 0; mask < 16; ++mask)
      {
        if (mask & (1 << side))
        {
          out[mask] = std::max(out[mask], out[mask ^ (1 << side)]);
        }
      }
    }
  }
};

// One triangle's contribution to a part's four corner errors: at every sample it covers,
// its drawn height S, the interpolated displacements of its edge (dE) and ring (dR)
// vertices, and of its ring vertices' targets with each side's edge (dR_k, from `c`: 4 per
// vertex, null when all 0), against the sample's height (MorphBounds.h). `own`: the strip's
// side (-1 for the inner grid). `area`: doubledArea(t). Returns false when nodata is
// involved. `verticesDone`: the triangle's own vertices are skipped (the caller has added
// them, addVertexContribution). `finiteSamples`: every height the triangle covers is known
// to be finite (a block without nodata), so no sample is tested.
bool rasterise(const Heightfield& hf, const GridTriangle& t, long long area, const double h[3],
  const double d[3], const double* const c[3], const bool onEdge[3], int own, bool verticesDone, bool finiteSamples,
  double err[4], InnerCorners* corners)
{
  if (area == 0)
  {
    return true;
  }
  // sign * w / |area| as w * (sign / |area|): the same double (sign is +-1).
  const double signedInv = (area < 0 ? -1.0 : 1.0) / static_cast<double>(area < 0 ? -area : area);
  const double dh1 = h[1] - h[0], dh2 = h[2] - h[0]; // relative to vertex 0: a large datum costs no precision
  const bool coupled = c[0] || c[1] || c[2];
  // A vertex has two edge functions at 0; only rows through a vertex are tested.
  auto isVertex = [&](const long long w[3], bool vertexRow) {
    if (!vertexRow || !verticesDone)
    {
      return false;
    }
    return (w[0] == 0) + (w[1] == 0) + (w[2] == 0) >= 2;
  };
  // The sample's weights l and the unmorphed surface's distance above it, S - H.
  auto gap = [&](long long i, long long j, const long long w[3], double l[3]) {
    l[0] = static_cast<double>(w[0]) * signedInv;
    l[1] = static_cast<double>(w[1]) * signedInv;
    l[2] = static_cast<double>(w[2]) * signedInv;
    const double H = hf.height(static_cast<int>(i), static_cast<int>(j));
    return (l[1] * dh1 + l[2] * dh2) - (H - h[0]);
  };
  // The ring vertices' target moves with each side's edge, interpolated at the sample.
  auto couplingAt = [&](const double l[3], double a[4]) {
    a[0] = a[1] = a[2] = a[3] = 0.0;
    for (int v = 0; v < 3; ++v)
    {
      if (c[v])
      {
        for (int k = 0; k < 4; ++k)
          a[k] += l[v] * c[v][k];
      }
    }
  };
  if (!onEdge[0] && !onEdge[1] && !onEdge[2] && finiteSamples)
  {
    double e0 = 0.0, e1 = 0.0; // max |S| and |S + dR| (every edge at its worst) over the triangle
    scanTriangle(t, area, [&](long long i, long long j, const long long w[3], bool vertexRow) {
      if (isVertex(w, vertexRow))
      {
        return true;
      }
      double l[3];
      const double s = gap(i, j, w, l);
      double dR = 0.0;
      dR += l[0] * d[0];
      dR += l[1] * d[1];
      dR += l[2] * d[2];
      e0 = std::max(e0, std::fabs(s));
      if (coupled)
      {
        double a[4];
        couplingAt(l, a);
        e1 = std::max(e1, worstOverEdges(s + dR, a, own));
        if (corners)
        {
          corners->add(s + dR, a);
        }
      }
      else
      {
        e1 = std::max(e1, std::fabs(s + dR));
        if (corners)
        {
          corners->add(s + dR, nullptr);
        }
      }
      return true;
    });
    err[0] = std::max(err[0], e0);
    err[1] = std::max(err[1], e1);
    err[2] = std::max(err[2], e0); // s + dE with dE = 0
    err[3] = std::max(err[3], e1);
    return true;
  }
  return scanTriangle(t, area, [&](long long i, long long j, const long long w[3], bool vertexRow) {
    if (isVertex(w, vertexRow))
    {
      return true;
    }
    double l[3];
    const double s = gap(i, j, w, l);
    double dE = 0.0, dR = 0.0;
    (onEdge[0] ? dE : dR) += l[0] * d[0];
    (onEdge[1] ? dE : dR) += l[1] * d[1];
    (onEdge[2] ? dE : dR) += l[2] * d[2];
    if (!finiteSamples && (!std::isfinite(s) || !std::isfinite(dE) || !std::isfinite(dR)))
    {
      return false;
    }
    err[0] = std::max(err[0], std::fabs(s));
    err[2] = std::max(err[2], std::fabs(s + dE));
    if (coupled)
    {
      double a[4];
      couplingAt(l, a);
      const double withOwn = own >= 0 ? a[own] : 0.0;
      err[1] = std::max(err[1], worstOverEdges(s + dR, a, own));
      err[3] = std::max(err[3], worstOverEdges(s + dE + dR + withOwn, a, own));
      if (corners)
      {
        corners->add(s + dR, a);
      }
    }
    else
    {
      err[1] = std::max(err[1], std::fabs(s + dR));
      err[3] = std::max(err[3], std::fabs(s + dE + dR));
      if (corners)
      {
        corners->add(s + dR, nullptr);
      }
    }
    return true;
  });
}

// What a vertex sample adds to the four corner errors where its weights are exactly 1 and
// 0 (rasterise at that sample): the drawn surface is the vertex's base height, s above the
// sample (0 but on a glided edge, EdgeHeights.h), moved by its own displacement d with the
// edge factor on the border, with the ring factor inside (its target moving with the
// edges by c, 4 per side, null when all 0).
void addVertexContribution(double s, double d, const double* c, bool onEdge, int own, double err[4],
  InnerCorners* corners)
{
  err[0] = std::max(err[0], std::fabs(s));
  if (corners && !onEdge)
  {
    corners->add(s + d, c);
  }
  if (onEdge)
  {
    err[1] = std::max(err[1], std::fabs(s));
    err[2] = std::max(err[2], std::fabs(s + d));
    err[3] = std::max(err[3], std::fabs(s + d));
    return;
  }
  err[2] = std::max(err[2], std::fabs(s));
  if (!c)
  {
    err[1] = std::max(err[1], std::fabs(s + d));
    err[3] = std::max(err[3], std::fabs(s + d));
    return;
  }
  err[1] = std::max(err[1], worstOverEdges(s + d, c, own));
  err[3] = std::max(err[3], worstOverEdges(s + d + (own >= 0 ? c[own] : 0.0), c, own));
}
} // namespace

namespace
{
// The multilinear interpolation of errors.innerAt at the edges' factors te: one side at a
// time (bit s of a mask is side s), halving the corners each time.
double innerAtEdges(const PartErrors& errors, const std::array<double, 4>& te)
{
  if (te[0] == 0.0 && te[1] == 0.0 && te[2] == 0.0 && te[3] == 0.0)
  {
    return errors.innerAt[0]; // the edges held
  }
  if (errors.innerAt[0] == errors.innerAt[15])
  {
    return errors.innerAt[0]; // no edge moves the inner grid's targets (monotone corners)
  }
  double v[8];
  for (int m = 0; m < 8; ++m)
  {
    v[m] = (1.0 - te[0]) * errors.innerAt[2 * m] + te[0] * errors.innerAt[2 * m + 1];
  }
  for (int side = 1, count = 4; side < 4; ++side, count /= 2)
  {
    for (int m = 0; m < count; ++m)
    {
      v[m] = (1.0 - te[side]) * v[2 * m] + te[side] * v[2 * m + 1];
    }
  }
  return v[0];
}
} // namespace

double innerBound(const PartErrors& errors, const std::array<double, 4>& te, double tb)
{
  return (1.0 - tb) * errors.inner[0] + tb * innerAtEdges(errors, te);
}

double innerReach(const PartErrors& errors, const std::array<double, 4>& te, double limit)
{
  const double a = errors.inner[0];
  return a <= limit ? linearReach(a, innerAtEdges(errors, te), limit) : 0.0;
}

double clamp01(double t)
{
  return t > 0.0 ? (t < 1.0 ? t : 1.0) : 0.0; // NaN -> 0
}

double linearReach(double a, double b, double limit)
{
  if (b <= limit)
  {
    return 1.0;
  }
  return b > a ? clamp01((limit - a) / (b - a)) : 0.0;
}

PartErrors morphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, MorphPartScratch& scratch)
{
  PartErrors out;
  updateMorphPartErrors(hf, qt, block, config, target, edgeTarget, kAllMorphParts, out, scratch);
  return out;
}

void updateMorphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts,
  PartErrors& out, MorphPartScratch& scratch)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const std::size_t rowLength = static_cast<std::size_t>(i1 - i0) + 1;
  const std::size_t vertices = rowLength * (static_cast<std::size_t>(j1 - j0) + 1);
  if (scratch.displacement.size() < vertices)
  {
    scratch.displacement.resize(vertices);
    scratch.coupling.resize(4 * vertices);
  }
  scratch.displaced.begin(vertices);
  // Where an interior vertex's target cell reaches the border: sides whose samples it
  // interpolates (the target's first or last cells across).
  const long long targetStep = target >= 0 ? 1LL << target : 0;
  const long long lastU = target >= 0 ? i0 + ((i1 - i0 - 1) / targetStep) * targetStep : 0;
  const long long lastV = target >= 0 ? j0 + ((j1 - j0 - 1) / targetStep) * targetStep : 0;
  auto reaches = [&](int side, int i, int j) {
    switch (side)
    {
      case South:
        return j - j0 < targetStep;
      case North:
        return j >= lastV;
      case West:
        return i - i0 < targetStep;
      default:
        return i >= lastU;
    }
  };
  // Block vertex v = (i, j)'s displacement at its target with the edges at their base
  // heights, and (interior vertices) how far that target moves with each moving edge (null
  // when with none), found once per call.
  auto displacement = [&](std::size_t v, int i, int j, double h, const double** coupling) {
    double* c = &scratch.coupling[4 * v];
    if (scratch.displaced.mark(v))
    {
      const double t0 = blockVertexTarget(hf, qt, block, target, edgeTarget, config.edgeLevel, i, j);
      scratch.displacement[v] = t0 - h;
      c[0] = c[1] = c[2] = c[3] = 0.0;
      const bool interior = !(i == i0 || i == i1 || j == j0 || j == j1);
      for (int side = 0; interior && target >= 0 && side < 4; ++side)
      {
        if (edgeTarget[side] >= 0 && reaches(side, i, j))
        {
          std::array<double, 4> unit{ 0.0, 0.0, 0.0, 0.0 };
          unit[side] = 1.0;
          c[side] = blockVertexTarget(hf, qt, block, target, edgeTarget, config.edgeLevel, i, j, unit) - t0;
        }
      }
    }
    *coupling = (c[0] != 0.0 || c[1] != 0.0 || c[2] != 0.0 || c[3] != 0.0) ? c : nullptr;
    return scratch.displacement[v];
  };
  // Block vertex (i, j)'s index: a block's triangles have their vertices in it.
  auto vertexIndex = [&](GridPoint p) {
    return static_cast<std::size_t>(p.i - i0) + static_cast<std::size_t>(p.j - j0) * rowLength;
  };
  // Vertices on the border are drawn at their base heights (on a glided edge, its polyline).
  auto onEdgeLine = [&](int i, int j) { return i == i0 || i == i1 || j == j0 || j == j1; };
  // A block without nodata has finite heights only (the heightfield turns infinities into
  // nodata), and it holds every sample its triangles cover.
  const bool finiteSamples = !qt.blockHasNodata[block];
  // A coarser block's triangles cut at a glided edge's samples have the same surface:
  // measured uncut.
  BlockConfig uncut = config;
  for (int side = 0; side < 4; ++side)
  {
    uncut.sampleLevel[side] = config.cutsSide(side) ? -1 : config.sampleLevel[side];
  }
  std::vector<GridTriangle>& tris = scratch.triangles;
  for (int p = 0; p < 5; ++p)
  {
    if (!(parts & (1u << p)))
    {
      continue;
    }
    const BlockPart part = p == 0 ? BlockPart::Inner : static_cast<BlockPart>(static_cast<int>(BlockPart::StripSouth) + p - 1);
    tris.clear();
    emitBlockGrid(qt, block, uncut, part, tris, scratch.emit);
    double err[4] = { 0.0, 0.0, 0.0, 0.0 };
    bool finite = true;
    const int own = p - 1; // the strip's side, -1 for the inner grid
    InnerCorners innerCorners;
    InnerCorners* corners = p == 0 ? &innerCorners : nullptr;
    scratch.measured.begin(vertices);
    for (const GridTriangle& t : tris)
    {
      // A half quad whose vertices an earlier triangle measured adds nothing: they were
      // measured only where finite (exactAtVertices), and it covers no other sample. At the
      // finest levels nearly every triangle is one, and each vertex is shared by about six.
      const long long signedArea = doubledArea(t);
      if ((signedArea == 1 || signedArea == -1) && scratch.measured.marked(vertexIndex(t.v[0])) &&
        scratch.measured.marked(vertexIndex(t.v[1])) && scratch.measured.marked(vertexIndex(t.v[2])))
      {
        continue;
      }
      double h[3], d[3];
      const double* coupling[3];
      bool onEdge[3];
      std::size_t v[3];
      bool finiteVertices = true;
      for (int k = 0; k < 3; ++k)
      {
        const int i = t.v[k].i, j = t.v[k].j;
        v[k] = vertexIndex(t.v[k]);
        h[k] = onEdgeLine(i, j) ? sideBaseHeight(hf, i0, i1, j0, j1, config.edgeLevel, i, j) : hf.height(i, j);
        d[k] = displacement(v[k], i, j, h[k], &coupling[k]);
        onEdge[k] = i == i0 || i == i1 || j == j0 || j == j1;
        finiteVertices = finiteVertices && std::isfinite(h[k]) && std::isfinite(d[k]);
        for (int side = 0; coupling[k] && side < 4; ++side)
        {
          finiteVertices = finiteVertices && std::isfinite(coupling[k][side]);
        }
      }
      // A vertex shared by about six triangles is measured once: in a triangle whose
      // doubled area is a power of two (most of them: a block's cells and fans span powers
      // of two unless a side of the block is not one) its weights are exactly 1 and 0 there,
      // so each such triangle would add the same values. Where the area is not, 1 / area
      // rounds, and the triangle measures its vertices itself.
      const long long area = std::llabs(signedArea);
      const bool exactAtVertices = area > 0 && (area & (area - 1)) == 0 && finiteVertices;
      if (exactAtVertices)
      {
        for (int k = 0; k < 3; ++k)
        {
          if (scratch.measured.mark(v[k]))
          {
            addVertexContribution(
              h[k] - hf.height(t.v[k].i, t.v[k].j), d[k], coupling[k], onEdge[k], own, err, corners);
          }
        }
        if (area == 1)
        {
          continue; // a half quad covers its three vertices only (Pick's theorem)
        }
      }
      if (!rasterise(hf, t, signedArea, h, d, coupling, onEdge, own, exactAtVertices, finiteSamples && finiteVertices,
            err, corners))
      {
        finite = false;
        break;
      }
    }
    if (p == 0)
    {
      out.inner[0] = err[0];
      out.inner[1] = err[1];
      innerCorners.finish(out.innerAt);
      out.innerFrozen = !finite;
    }
    else
    {
      std::copy(err, err + 4, out.side[p - 1]);
      out.sideFrozen[p - 1] = !finite;
    }
  }
}

} // namespace gmm
