#include "RasterError.h"

#include "EdgeHeights.h"
#include "Levels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{
constexpr float kInf = std::numeric_limits<float>::infinity();
} // namespace

float roundUpToFloat(double e)
{
  if (!(e <= std::numeric_limits<float>::max()))
  {
    return kInf; // only for heights validateHeightfield would refuse; avoids an undefined cast
  }
  const float f = static_cast<float>(e);
  return static_cast<double>(f) < e ? std::nextafter(f, kInf) : f;
}

namespace
{
constexpr double kInfD = std::numeric_limits<double>::infinity();

// Floor and ceiling of a / b for b > 0, any sign of a.
int64_t floorDiv(int64_t a, int64_t b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

int64_t ceilDiv(int64_t a, int64_t b)
{
  return -floorDiv(-a, b);
}

int64_t edgeFn(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py)
{
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Two lines (rows or columns) whose samples triangleError leaves out: a side strip's lines,
// measured by polylineError. Leaving out fewer samples than asked (where a triangle is not
// walked along the lines' direction) only measures some twice.
struct SkipLines
{
  bool rows; // rows j = a and j = b; else columns i = a and i = b
  int64_t a, b;
};

// The height a vertex is drawn at: on a glided line, its polyline's (EdgeHeights.h).
double glidedHeight(const Heightfield& hf, const GlidedLine& g, GridPoint v, double own)
{
  if (g.rows ? v.j != g.line : v.i != g.line)
  {
    return own;
  }
  return linePolylineAt(hf, g.rows, g.line, g.first, g.last, g.level, g.rows ? v.i : v.j);
}

// Error of one triangle over the samples it covers (edges included), in grid space.
// strict: a nodata vertex or covered nodata sample is an infinite error (the triangle would
// draw over a hole); otherwise a nodata-touching triangle is an accepted full-res hole.
//
// Samples are walked line by line with the barycentric weights updated by additions. The
// fans and cells Tessellate emits are walked span by span (see below); any other triangle
// by scanning its bounding box with an inside test, which is cheaper than solving each
// row's span with integer divisions (measured: 4097^2, one thread, 1.20 s against 1.32 s).
// skip, when given, names lines whose samples are left out (SkipLines); glide, a line whose
// vertices are drawn on a coarser polyline (GlidedLine).
//
// Returns the error as a double (+inf for nodata when strict); maxTriangleError rounds the
// maximum over a list up to float once, which is the maximum of the rounded errors
// (rounding up is monotone) without a nextafter per triangle.
double triangleError(const Heightfield& hf, const GridTriangle& t, bool strict, const SkipLines* skip,
  const GlidedLine* glide = nullptr)
{
  const int64_t nx = hf.nx;
  const int64_t ax = t.v[0].i, ay = t.v[0].j, bx = t.v[1].i, by = t.v[1].j, cx = t.v[2].i, cy = t.v[2].j;
  const float* z = hf.heights();
  double za = z[ay * nx + ax], zb = z[by * nx + bx], zc = z[cy * nx + cx];
  if (std::isnan(za) || std::isnan(zb) || std::isnan(zc))
  {
    return strict ? kInfD : 0.0;
  }
  if (glide)
  {
    za = glidedHeight(hf, *glide, t.v[0], za);
    zb = glidedHeight(hf, *glide, t.v[1], zb);
    zc = glidedHeight(hf, *glide, t.v[2], zc);
  }
  // Heights relative to vertex a: the difference of two floats of similar magnitude is
  // exact in double, so the error does not depend on a constant height offset (an ECEF-like
  // 6.4e6 m gives the same table as 0 m) and is exactly 0 on a plane, where the absolute
  // barycentric sum w0*za + w1*zb + w2*zc left residues of ~1e-9 m that grew with the offset.
  const double dzb = zb - za, dzc = zc - za;
  const int64_t area = edgeFn(ax, ay, bx, by, cx, cy);
  if (area == 0)
  {
    return 0.0; // no sample strictly covered; cannot happen for emitted triangles
  }
  // Barycentric weights times the area, w1 (of b) = edgeFn(c, a, p) and w2 (of c) =
  // edgeFn(a, b, p), at the box's first sample, and their steps per column and per row;
  // all multiplied by the sign of the area, so that a sample is covered when w0 = area -
  // w1 - w2, w1 and w2 are all >= 0. The error expression only changes sign with them.
  const int64_t sign = area < 0 ? -1 : 1;
  const int64_t i0 = std::min({ ax, bx, cx }), i1 = std::max({ ax, bx, cx });
  const int64_t j0 = std::min({ ay, by, cy }), j1 = std::max({ ay, by, cy });
  const int64_t twiceArea = sign * area;
  const int64_t w1Start = sign * edgeFn(cx, cy, ax, ay, i0, j0);
  const int64_t w2Start = sign * edgeFn(ax, ay, bx, by, i0, j0);
  const int64_t w1di = sign * (cy - ay), w1dj = sign * (ax - cx);
  const int64_t w2di = sign * (ay - by), w2dj = sign * (bx - ax);
  const double fullArea = static_cast<double>(twiceArea);
  double worst = 0.0; // largest |(h - surface) * area|
  // Samples first .. first + (count - 1) * stride along one line, weights w1, w2 at the
  // first and their steps along the line. Returns false on nodata when strict.
  auto line = [&](const float* first, int64_t stride, int64_t count, int64_t w1, int64_t w2,
                int64_t w1Step, int64_t w2Step, bool test) {
    for (int64_t k = 0; k < count; ++k, w1 += w1Step, w2 += w2Step)
    {
      if (test && (w1 < 0 || w2 < 0 || w1 + w2 > twiceArea))
      {
        continue; // outside
      }
      const float h = first[k * stride];
      if (std::isnan(h))
      {
        if (strict)
        {
          return false;
        }
        continue;
      }
      // (h - surface) * area: products of small integers and exact height differences,
      // so exactly 0 on a plane. The one rounding, by the division, comes after the max:
      // division by a positive constant is monotone, so it gives the max of the quotients.
      worst = std::max(worst,
        std::abs((h - za) * fullArea - (static_cast<double>(w1) * dzb + static_cast<double>(w2) * dzc)));
    }
    return true;
  };
  auto weightsAt = [&](int64_t i, int64_t j, int64_t& w1, int64_t& w2) {
    w1 = w1Start + (i - i0) * w1di + (j - j0) * w1dj;
    w2 = w2Start + (i - i0) * w2di + (j - j0) * w2dj;
  };
  // Fans and grid cells have an edge along a row or a column (the base) and the third
  // vertex (the apex) at a distance D from it, a power of two for all but the last strip
  // of a block whose side the step does not divide. Then every line parallel to the base
  // meets the triangle in one span whose ends are apex + (base end - apex) * t / D, t the
  // line's distance to the apex: a multiplication and a shift, exact. Walking those spans
  // tests no sample outside, where the box of a long thin fan holds several per covered one.
  // With lines to skip, a walk along their direction is preferred (first pass): a corner
  // triangle of a strip has both a row and a column base.
  const GridPoint v[3] = { t.v[0], t.v[1], t.v[2] };
  for (int k = skip ? 0 : 3; k < 6; ++k)
  {
    const int apex = k % 3;
    const bool firstPass = k < 3;
    const GridPoint p = v[(apex + 1) % 3], q = v[(apex + 2) % 3], o = v[apex];
    const bool rows = p.j == q.j && o.j != p.j, cols = p.i == q.i && o.i != p.i;
    const int64_t D = rows ? std::abs(static_cast<int64_t>(o.j) - p.j) : std::abs(static_cast<int64_t>(o.i) - p.i);
    if (!(rows || cols) || (D & (D - 1)) != 0 || (firstPass && rows != skip->rows))
    {
      continue;
    }
    const bool skipping = skip && rows == skip->rows;
    const int shift = __builtin_ctzll(static_cast<unsigned long long>(D)); // D is a power of two
    // Along the base: position a (i for rows, j for columns); across: position b.
    const int64_t oa = rows ? o.i : o.j, ob = rows ? o.j : o.i, baseB = rows ? p.j : p.i;
    const int64_t lowA = std::min(rows ? p.i : p.j, rows ? q.i : q.j) - oa;
    const int64_t highA = std::max(rows ? p.i : p.j, rows ? q.i : q.j) - oa;
    const int64_t dir = baseB > ob ? 1 : -1;
    for (int64_t tt = 0; tt <= D; ++tt)
    {
      const int64_t b = ob + dir * tt;
      if (skipping && (b == skip->a || b == skip->b))
      {
        continue;
      }
      const int64_t lo = oa - ((-lowA * tt) >> shift); // ceil(oa + lowA * tt / D)
      const int64_t hi = oa + ((highA * tt) >> shift);  // floor(oa + highA * tt / D)
      if (lo > hi)
      {
        continue;
      }
      int64_t w1, w2;
      if (rows)
      {
        weightsAt(lo, b, w1, w2);
        if (!line(z + b * nx + lo, 1, hi - lo + 1, w1, w2, w1di, w2di, false))
        {
          return kInfD;
        }
      }
      else
      {
        weightsAt(b, lo, w1, w2);
        if (!line(z + lo * nx + b, nx, hi - lo + 1, w1, w2, w1dj, w2dj, false))
        {
          return kInfD;
        }
      }
    }
    return worst / fullArea;
  }
  // The box walks below go row by row: they skip rows only.
  auto skipRow = [skip](int64_t j) { return skip && skip->rows && (j == skip->a || j == skip->b); };
  // A long sliver (a merged node's fan) covers a small part of its box: solve each row's
  // span exactly instead (three integer divisions a row). Small triangles scan the box.
  const int64_t boxSamples = (i1 - i0 + 1) * (j1 - j0 + 1);
  if (boxSamples > 4 * (twiceArea + (j1 - j0 + 1)))
  {
    const int64_t w0di = -(w1di + w2di);
    for (int64_t j = j0; j <= j1; ++j)
    {
      if (skipRow(j))
      {
        continue;
      }
      int64_t w1, w2;
      weightsAt(i0, j, w1, w2);
      // Columns i0 + d, d in [lo, hi], where every weight w + d * step is >= 0.
      int64_t lo = 0, hi = i1 - i0;
      const int64_t w[3] = { twiceArea - w1 - w2, w1, w2 }, step[3] = { w0di, w1di, w2di };
      for (int e = 0; e < 3; ++e)
      {
        if (step[e] > 0)
          lo = std::max(lo, ceilDiv(-w[e], step[e]));
        else if (step[e] < 0)
          hi = std::min(hi, floorDiv(w[e], -step[e]));
        else if (w[e] < 0)
          hi = -1;
      }
      if (lo > hi)
      {
        continue;
      }
      if (!line(z + j * nx + i0 + lo, 1, hi - lo + 1, w1 + lo * w1di, w2 + lo * w2di, w1di, w2di,
            false))
      {
        return kInfD;
      }
    }
    return worst / fullArea;
  }
  for (int64_t j = j0; j <= j1; ++j)
  {
    if (skipRow(j))
    {
      continue;
    }
    int64_t w1, w2;
    weightsAt(i0, j, w1, w2);
    if (!line(z + j * nx + i0, 1, i1 - i0 + 1, w1, w2, w1di, w2di, true))
    {
      return kInfD;
    }
  }
  return worst / fullArea;
}

// Residual (h - surface) * s^2 of sample (I0 + u, J0 + v) in the cell of side s whose
// corner heights relative to z00 are d10 = z(s, 0) - z00, d11, d01. The cell is split
// along its (0, 0)-(s, s) diagonal, or with `anti` its (s, 0)-(0, s) one, as
// TriangleSink::quad does; the weights are the very integers triangleError derives for
// those triangles, so the arithmetic is the same.
inline double cellResidual(double h, double z00, double area, int64_t s, int64_t u, int64_t v,
  double d10, double d11, double d01, bool anti)
{
  if (anti)
  {
    return u + v <= s
      ? (h - z00) * area - (static_cast<double>(s * u) * d10 + static_cast<double>(s * v) * d01)
      : (h - z00) * area -
        (static_cast<double>(s * (s - v)) * d10 + static_cast<double>(s * (u + v - s)) * d11 +
          static_cast<double>(s * (s - u)) * d01);
  }
  return u >= v
    ? (h - z00) * area - (static_cast<double>(s * (u - v)) * d10 + static_cast<double>(s * v) * d11)
    : (h - z00) * area - (static_cast<double>(s * u) * d11 + static_cast<double>(s * (v - u)) * d01);
}

} // namespace

float innerAreaError(const Heightfield& hf, const std::vector<int>& C, const std::vector<int>& R)
{
  // drawInnerGrid's cells: columns C[1..k-1] and rows R[1..L-1], all one step apart.
  if (C.size() < 4 || R.size() < 4)
  {
    return 0.0f; // fewer than two inner columns or rows: no cell
  }
  const int64_t s = C[2] - C[1];
  const int64_t cellsX = static_cast<int64_t>(C.size()) - 3, cellsY = static_cast<int64_t>(R.size()) - 3;
  const int64_t iFirst = C[1], jFirst = R[1];
  const int64_t jLast = jFirst + cellsY * s;
  const int64_t nx = hf.nx;
  const float* z = hf.heights();
  const double area = static_cast<double>(s * s);
  double worst = 0.0;
  bool nodata = false;
  // Every sample of the inner rectangle once: cell (cu, cv) takes its half-open square, the
  // last column and row of cells also their far side. A sample on a cell border lies on an
  // edge of both cells' triangles, where they interpolate the same two corners.
  for (int64_t j = jFirst; j <= jLast; ++j)
  {
    const int64_t cv = std::min((j - jFirst) / s, cellsY - 1);
    const int64_t J0 = jFirst + cv * s, v = j - J0;
    const float* row0 = z + J0 * nx;
    const float* row1 = z + (J0 + s) * nx;
    const float* row = z + j * nx;
    for (int64_t cu = 0; cu < cellsX; ++cu)
    {
      const int64_t I0 = iFirst + cu * s;
      const double z00 = row0[I0];
      const double d10 = row0[I0 + s] - z00, d11 = row1[I0 + s] - z00, d01 = row1[I0] - z00;
      const int64_t uEnd = cu + 1 < cellsX ? s - 1 : s;
      // Cell (cu + 1, cv + 1) of the block's level grid (the inner grid starts one cell in).
      const bool anti = cellAntiDiagonal(static_cast<int>(cu + 1), static_cast<int>(cv + 1));
      for (int64_t u = 0; u <= uEnd; ++u)
      {
        const float h = row[I0 + u];
        nodata |= std::isnan(h);
        worst = std::max(worst, std::abs(cellResidual(h, z00, area, s, u, v, d10, d11, d01, anti)));
      }
    }
  }
  // A nodata corner or sample: the cells would draw over a hole (all inner levels > 0 are
  // strict). NaN residuals do not enter std::max(worst, NaN), hence the separate flag.
  return nodata ? kInf : roundUpToFloat(worst / area);
}

namespace
{
// The largest triangleError over a list, rounded up to float once; stops at +inf.
float maxTriangleError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool strict,
  const SkipLines* skip, const GlidedLine* glide = nullptr)
{
  double worst = 0.0;
  for (const GridTriangle& t : tris)
  {
    worst = std::max(worst, triangleError(hf, t, strict, skip, glide));
    if (worst == kInfD)
    {
      break;
    }
  }
  return roundUpToFloat(worst);
}
} // namespace

float trianglesError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool strictNodata)
{
  return maxTriangleError(hf, tris, strictNodata, nullptr);
}

float polylineError(const Heightfield& hf, const std::vector<GridPoint>& points)
{
  const int64_t nx = hf.nx;
  const float* z = hf.heights();
  if (points.size() == 1 && std::isnan(z[static_cast<int64_t>(points[0].j) * nx + points[0].i]))
  {
    return kInf; // a one-point polyline (a strip's inner ring of one sample) is a vertex
  }
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
  {
    const GridPoint p = points[k], q = points[k + 1];
    // Samples p + d * (step), d = 0 .. length, along the segment's row or column.
    const bool alongRow = p.j == q.j;
    const int64_t length = alongRow ? std::abs(q.i - p.i) : std::abs(q.j - p.j);
    const int64_t step = (alongRow ? 1 : nx) * ((alongRow ? q.i - p.i : q.j - p.j) < 0 ? -1 : 1);
    const float* first = z + static_cast<int64_t>(p.j) * nx + p.i;
    const double zp = first[0], dz = static_cast<double>(first[length * step]) - zp;
    if (std::isnan(zp) || std::isnan(dz))
    {
      return kInf;
    }
    // (h - surface) * length, as triangleError forms (h - surface) * area: exact height
    // differences times small integers, so exactly 0 on a line; one division per segment.
    const double len = static_cast<double>(length);
    double segmentWorst = 0.0;
    for (int64_t d = 1; d < length; ++d)
    {
      const float h = first[d * step];
      if (std::isnan(h))
      {
        return kInf;
      }
      segmentWorst = std::max(segmentWorst, std::abs((h - zp) * len - static_cast<double>(d) * dz));
    }
    worst = std::max(worst, segmentWorst / len);
  }
  return roundUpToFloat(worst);
}

float sidePolylineError(const Heightfield& hf, const Quadtree& qt, int block, int side, int level,
  EmitScratch& scratch)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const bool rows = side == South || side == North;
  const int line = side == South ? j0 : side == North ? j1 : side == West ? i0 : i1;
  std::vector<int>& along = scratch.edge;
  std::vector<GridPoint>& points = scratch.outer;
  if (rows)
  {
    edgeSamples(i0, i1, level, along);
  }
  else
  {
    edgeSamples(j0, j1, level, along);
  }
  points.clear();
  for (int x : along)
  {
    points.push_back(rows ? GridPoint{ x, line } : GridPoint{ line, x });
  }
  return polylineError(hf, points);
}

float stripInteriorError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool rows,
  int lineA, int lineB, const GlidedLine* glide)
{
  const SkipLines skip{ rows, lineA, lineB };
  return maxTriangleError(hf, tris, true, &skip, glide);
}

} // namespace gmm
