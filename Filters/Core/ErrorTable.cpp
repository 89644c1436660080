#include "ErrorTable.h"

#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <atomic>
#include <chrono>
#include <thread>

namespace gmm
{

namespace
{
constexpr float kInf = std::numeric_limits<float>::infinity();

// The table stores floats; rounding a double error to nearest could make the certified
// bound a hair smaller than the measured error, so round up instead. Heights are limited to
// +-kMaxHeight (Heightfield.h), so an error never overflows to the +inf that marks a level
// as not allowed.
float roundUpToFloat(double e)
{
  if (!(e <= std::numeric_limits<float>::max()))
  {
    return kInf; // only for heights validateHeightfield would refuse; avoids an undefined cast
  }
  const float f = static_cast<float>(e);
  return static_cast<double>(f) < e ? std::nextafter(f, kInf) : f;
}

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

// Error of one triangle over the samples it covers (edges included), in grid space.
// strict: a nodata vertex or covered nodata sample is an infinite error (the triangle would
// draw over a hole); otherwise a nodata-touching triangle is an accepted full-res hole.
//
// Samples are walked line by line with the barycentric weights updated by additions. The
// fans and cells Tessellate emits are walked span by span (see below); any other triangle
// by scanning its bounding box with an inside test, which is cheaper than solving each
// row's span with integer divisions (measured: 4097^2, one thread, 1.20 s against 1.32 s).
float triangleError(const Heightfield& hf, const GridTriangle& t, bool strict)
{
  const int64_t nx = hf.nx;
  const int64_t ax = t.v[0].i, ay = t.v[0].j, bx = t.v[1].i, by = t.v[1].j, cx = t.v[2].i, cy = t.v[2].j;
  const float* z = hf.heights();
  const double za = z[ay * nx + ax], zb = z[by * nx + bx], zc = z[cy * nx + cx];
  if (std::isnan(za) || std::isnan(zb) || std::isnan(zc))
  {
    return strict ? kInf : 0.0f;
  }
  // Heights relative to vertex a: the difference of two floats of similar magnitude is
  // exact in double, so the error does not depend on a constant height offset (an ECEF-like
  // 6.4e6 m gives the same table as 0 m) and is exactly 0 on a plane, where the absolute
  // barycentric sum w0*za + w1*zb + w2*zc left residues of ~1e-9 m that grew with the offset.
  const double dzb = zb - za, dzc = zc - za;
  const int64_t area = edgeFn(ax, ay, bx, by, cx, cy);
  if (area == 0)
  {
    return 0.0f; // no sample strictly covered; cannot happen for emitted triangles
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
  const GridPoint v[3] = { t.v[0], t.v[1], t.v[2] };
  for (int apex = 0; apex < 3; ++apex)
  {
    const GridPoint p = v[(apex + 1) % 3], q = v[(apex + 2) % 3], o = v[apex];
    const bool rows = p.j == q.j && o.j != p.j, cols = p.i == q.i && o.i != p.i;
    const int64_t D = rows ? std::abs(static_cast<int64_t>(o.j) - p.j) : std::abs(static_cast<int64_t>(o.i) - p.i);
    if (!(rows || cols) || (D & (D - 1)) != 0)
    {
      continue;
    }
    int shift = 0;
    while ((int64_t(1) << shift) < D)
    {
      ++shift;
    }
    // Along the base: position a (i for rows, j for columns); across: position b.
    const int64_t oa = rows ? o.i : o.j, ob = rows ? o.j : o.i, baseB = rows ? p.j : p.i;
    const int64_t lowA = std::min(rows ? p.i : p.j, rows ? q.i : q.j) - oa;
    const int64_t highA = std::max(rows ? p.i : p.j, rows ? q.i : q.j) - oa;
    const int64_t dir = baseB > ob ? 1 : -1;
    for (int64_t tt = 0; tt <= D; ++tt)
    {
      const int64_t b = ob + dir * tt;
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
          return kInf;
        }
      }
      else
      {
        weightsAt(b, lo, w1, w2);
        if (!line(z + lo * nx + b, nx, hi - lo + 1, w1, w2, w1dj, w2dj, false))
        {
          return kInf;
        }
      }
    }
    return roundUpToFloat(worst / fullArea);
  }
  // A long sliver (a merged node's fan) covers a small part of its box: solve each row's
  // span exactly instead (three integer divisions a row). Small triangles scan the box.
  const int64_t boxSamples = (i1 - i0 + 1) * (j1 - j0 + 1);
  if (boxSamples > 4 * (twiceArea + (j1 - j0 + 1)))
  {
    const int64_t w0di = -(w1di + w2di);
    for (int64_t j = j0; j <= j1; ++j)
    {
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
        return kInf;
      }
    }
    return roundUpToFloat(worst / fullArea);
  }
  for (int64_t j = j0; j <= j1; ++j)
  {
    int64_t w1, w2;
    weightsAt(i0, j, w1, w2);
    if (!line(z + j * nx + i0, 1, i1 - i0 + 1, w1, w2, w1di, w2di, true))
    {
      return kInf;
    }
  }
  return roundUpToFloat(worst / fullArea);
}

// Residual (h - surface) * s^2 of sample (I0 + u, J0 + v) in the cell of side s whose
// corner heights relative to z00 are d10 = z(s, 0) - z00, d11, d01. The cell is split
// along its (0, 0)-(s, s) diagonal as TriangleSink::quad does; the weights are the very
// integers triangleError derives for those two triangles, so the arithmetic is the same.
inline double cellResidual(double h, double z00, double area, int64_t s, int64_t u, int64_t v,
  double d10, double d11, double d01)
{
  return u >= v
    ? (h - z00) * area - (static_cast<double>(s * (u - v)) * d10 + static_cast<double>(s * v) * d11)
    : (h - z00) * area - (static_cast<double>(s * u) * d11 + static_cast<double>(s * (v - u)) * d01);
}

} // namespace

float innerAreaError(const Heightfield& hf, const std::vector<int>& C, const std::vector<int>& R)
{
  // drawArea's cells: columns C[1..k-1] and rows R[1..L-1], all one step apart.
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
      for (int64_t u = 0; u <= uEnd; ++u)
      {
        const float h = row[I0 + u];
        nodata |= std::isnan(h);
        worst = std::max(worst, std::abs(cellResidual(h, z00, area, s, u, v, d10, d11, d01)));
      }
    }
  }
  // A nodata corner or sample: the cells would draw over a hole (all inner levels > 0 are
  // strict). NaN residuals do not enter std::max(worst, NaN), hence the separate flag.
  return nodata ? kInf : roundUpToFloat(worst / area);
}

namespace
{

// Buffers one worker reuses for every part it rasterises.
struct Scratch
{
  std::vector<GridTriangle> triangles;
  EmitScratch emit;
};

float partError(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& cfg,
  BlockPart part, bool strict, Scratch& scratch)
{
  scratch.triangles.clear();
  emitBlockGrid(qt, block, cfg, part, scratch.triangles, scratch.emit);
  return trianglesError(hf, scratch.triangles, strict);
}

void fillBlock(const Heightfield& hf, const Quadtree& qt, int block, ErrorTable& t,
  Scratch& scratch)
{
  const int width = qt.blockWidth(block), height = qt.blockHeight(block);
  const int top = topLevel(width, height);
  float* own = &t.ownError[static_cast<std::size_t>(block) * t.levels];
  float* exact = &t.ownErrorExact[static_cast<std::size_t>(block) * t.levels];
  float* strips = &t.stripError[static_cast<std::size_t>(block) * 4 * t.pairs];
  const bool lockFullRes = qt.blockHasNodata[block] != 0;
  float running = 0.0f;
  for (int m = 0; m < t.levels; ++m)
  {
    const BlockShape shape = blockShape(width, height, m);
    own[m] = exact[m] = kInf;
    if (m > top || shape == BlockShape::Invalid || (lockFullRes && m > 0))
    {
      continue; // never selected
    }
    // Full resolution with its own edges draws every sample: holes there are the data's.
    const bool strict = m > 0;
    BlockConfig cfg;
    cfg.level = m;
    cfg.edgeLevel = { m, m, m, m };
    // Level 0 with its own edges has every sample as a vertex: its error is exactly 0
    // (a vertex's residual is (zb - za) * A - A * (zb - za) = 0 in double), so only its
    // strips towards coarser edges are rasterised.
    float e = 0.0f;
    if (shape != BlockShape::Ring)
    {
      e = m == 0 ? 0.0f : partError(hf, qt, block, cfg, BlockPart::Whole, strict, scratch);
    }
    else
    {
      if (m > 0)
      {
        edgeSamples(qt.colStart[block % qt.blockCols], qt.colStart[block % qt.blockCols + 1], m, scratch.emit.cols);
        edgeSamples(qt.rowStart[block / qt.blockCols], qt.rowStart[block / qt.blockCols + 1], m, scratch.emit.rows);
        e = innerAreaError(hf, scratch.emit.cols, scratch.emit.rows);
      }
      for (int side = 0; side < 4; ++side)
      {
        const BlockPart part = static_cast<BlockPart>(static_cast<int>(BlockPart::StripSouth) + side);
        float previous = m == 0 ? 0.0f : partError(hf, qt, block, cfg, part, strict, scratch);
        e = std::max(e, previous);
        // Coarser edges: from the first coarser level until the edge is just its corners;
        // beyond that the strip no longer changes.
        const int edgeLength = (side == South || side == North) ? width : height;
        for (int n = m + 1; n < t.levels; ++n)
        {
          const bool changes = ((1LL << (n - 1)) < edgeLength);
          float s = previous;
          if (changes)
          {
            BlockConfig coarse = cfg;
            coarse.edgeLevel[side] = n;
            s = std::max(previous, partError(hf, qt, block, coarse, part, true, scratch));
          }
          strips[side * t.pairs + ErrorTable::pairIndex(m, n)] = s;
          previous = s;
        }
      }
    }
    exact[m] = e;
    running = std::max(running, e);
    own[m] = running; // monotone over the valid levels
  }
}

// A merged node's fan over every sample of the node; nodata anywhere below it is +inf
// (the fan would draw over the hole). Nodes above kExactMergedHeight get a bound instead:
// every fan vertex is a sample of the node, so the fan lies within the node's height range
// and no sample is further from it than that range. Such nodes are drawn only from far
// away, and computing their fans exactly would cost the table one more pass over every
// sample per level.
float mergedNodeError(const Heightfield& hf, const Quadtree& qt, int node, Scratch& scratch)
{
  if (!mergeableNode(qt, node))
  {
    return kInf;
  }
  const QuadtreeNode& n = qt.nodes[node];
  if (n.height > kExactMergedHeight)
  {
    for (int r = n.rowBegin; r < n.rowEnd; ++r)
      for (int c = n.colBegin; c < n.colEnd; ++c)
        if (qt.blockHasNodata[qt.blockIndex(c, r)])
          return kInf;
    return roundUpToFloat(n.box.hi.z - n.box.lo.z);
  }
  scratch.triangles.clear();
  emitMergedNodeGrid(qt, node, scratch.triangles);
  return trianglesError(hf, scratch.triangles, true);
}

} // namespace

float ErrorTable::strip(int block, int side, int m, int n) const
{
  return stripError[(static_cast<std::size_t>(block) * 4 + side) * pairs + pairIndex(m, n)];
}

float trianglesError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool strictNodata)
{
  float worst = 0.0f;
  for (const GridTriangle& t : tris)
  {
    worst = std::max(worst, triangleError(hf, t, strictNodata));
    if (worst == kInf)
    {
      break;
    }
  }
  return worst;
}

ErrorTable buildErrorTable(const Heightfield& hf, const Quadtree& qt, int threads,
  const std::function<void(double)>& progress)
{
  ErrorTable t;
  int maxTop = 0;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    maxTop = std::max(maxTop, topLevel(qt.blockWidth(b), qt.blockHeight(b)));
  }
  t.levels = maxTop + 1;
  t.pairs = t.levels * (t.levels - 1) / 2;
  const std::size_t blocks = static_cast<std::size_t>(qt.blockCount());
  t.ownError.assign(blocks * t.levels, kInf);
  t.ownErrorExact.assign(blocks * t.levels, kInf);
  t.stripError.assign(blocks * 4 * std::max(1, t.pairs), 0.0f);

  const std::size_t nodes = qt.nodes.size();
  t.mergedError.assign(nodes, kInf);
  // Work items: every block, then every quadtree node (its merged fan).
  const std::size_t items = blocks + nodes;

  unsigned workers = threads > 0 ? static_cast<unsigned>(threads) : std::thread::hardware_concurrency();
  workers = std::max(1u, std::min<unsigned>(workers, static_cast<unsigned>(items)));
  // Items are independent: interleave them over the workers so that expensive regions of
  // the DEM spread evenly.
  std::atomic<std::size_t> done{ 0 };
  auto work = [&](unsigned first) {
    Scratch scratch;
    for (std::size_t k = first; k < items; k += workers)
    {
      if (k < blocks)
        fillBlock(hf, qt, static_cast<int>(k), t, scratch);
      else
        t.mergedError[k - blocks] = mergedNodeError(hf, qt, static_cast<int>(k - blocks), scratch);
      done.fetch_add(1, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < workers; ++w)
  {
    pool.emplace_back(work, w);
  }
  if (progress)
  {
    // The caller's thread reports (VTK progress events must come from it) while it waits.
    // Short waits first, so that a small table is not held up by the polling.
    for (int wait = 1; done.load(std::memory_order_relaxed) < items; wait = std::min(2 * wait, 50))
    {
      progress(static_cast<double>(done.load(std::memory_order_relaxed)) / items);
      std::this_thread::sleep_for(std::chrono::milliseconds(wait));
    }
    progress(1.0);
  }
  for (std::thread& th : pool)
  {
    th.join();
  }
  return t;
}

} // namespace gmm
