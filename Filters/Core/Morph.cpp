#include "Morph.h"

#include "Levels.h"
#include "SelectLevels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// Band index of sample s in band starts `start` (size bands + 1): the band whose first
// sample is the largest start <= s (the last band for the very last sample).
int bandOf(const std::vector<int>& start, int s)
{
  const int bands = static_cast<int>(start.size()) - 1;
  const int k = static_cast<int>(std::upper_bound(start.begin(), start.end(), s) - start.begin()) - 1;
  return std::min(std::max(k, 0), bands - 1);
}

// Height of the polyline through the samples of [first, last] at `level` (edgeSamples), at
// sample s on that line; `at(k)` gives the height of sample k along the line.
template <typename At>
double polylineAt(int first, int last, int level, int s, At at)
{
  const long long step = 1LL << level;
  const long long lo = first + (s - first) / step * step;
  if (lo == s)
  {
    return at(s);
  }
  const long long hi = std::min<long long>(lo + step, last);
  const double w = static_cast<double>(s - lo) / static_cast<double>(hi - lo);
  const double a = at(static_cast<int>(lo)), b = at(static_cast<int>(hi));
  return a + w * (b - a);
}

// Height of block rectangle [i0, i1] x [j0, j1] drawn at `level` with its own edges, at
// the interior sample (i, j): the cell of the grid edgeSamples(level) x edgeSamples(level)
// that holds it, split as Tessellate splits it (see Morph.h).
double blockSurfaceAt(const Heightfield& hf, int i0, int i1, int j0, int j1, int level, int i, int j)
{
  const long long step = 1LL << level;
  const long long u = (i - i0) / step, v = (j - j0) / step;
  const long long ia = i0 + u * step, ja = j0 + v * step;
  const long long ib = std::min<long long>(ia + step, i1), jb = std::min<long long>(ja + step, j1);
  const long long k = (i1 - i0 + step - 1) / step, L = (j1 - j0 + step - 1) / step; // cells per side
  const bool ring = blockShape(i1 - i0, j1 - j0, level) == BlockShape::Ring;
  const bool anti = ring && ((u == k - 1 && v == 0) || (u == 0 && v == L - 1));
  const double fx = static_cast<double>(i - ia) / static_cast<double>(ib - ia);
  const double fy = static_cast<double>(j - ja) / static_cast<double>(jb - ja);
  const double h00 = hf.height(int(ia), int(ja)), h10 = hf.height(int(ib), int(ja));
  const double h01 = hf.height(int(ia), int(jb)), h11 = hf.height(int(ib), int(jb));
  if (!anti)
  {
    // diagonal (ia, ja)-(ib, jb)
    return fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);
  }
  // diagonal (ib, ja)-(ia, jb)
  return fx + fy <= 1.0 ? h00 + fx * (h10 - h00) + fy * (h01 - h00)
                        : h11 + (1.0 - fx) * (h01 - h11) + (1.0 - fy) * (h10 - h11);
}

// Largest |polyline at target - height| over the samples of an edge at `level` that the
// target level drops; +inf when nodata is involved (such an edge never morphs).
template <typename At>
double edgeDisplacement(int first, int last, int level, int target, At at)
{
  double worst = 0.0;
  const long long step = 1LL << level;
  for (long long s = first + step; s < last; s += step)
  {
    const double h = at(static_cast<int>(s));
    const double c = polylineAt(first, last, target, static_cast<int>(s), at);
    const double d = std::fabs(c - h);
    if (!std::isfinite(d))
    {
      return kInf;
    }
    worst = std::max(worst, d);
  }
  return worst;
}

double clamp01(double t)
{
  return t > 0.0 ? (t < 1.0 ? t : 1.0) : 0.0; // NaN -> 0
}

// Factors are stored as float (what the shader reads): rounded down, never above the
// factor the certificate allows.
float factorDown(double t)
{
  float f = static_cast<float>(clamp01(t));
  if (static_cast<double>(f) > t)
  {
    f = std::nextafter(f, 0.0f);
  }
  return f;
}

// Factor an edge whose vertices move by at most d may take in a block with slack s
// (tau / f - E, < 0 when the block must not morph).
double allowance(double slack, double d)
{
  if (slack < 0.0)
  {
    return 0.0;
  }
  return d > 0.0 ? clamp01(slack / d) : 1.0;
}
} // namespace

int nextValidLevel(int widthQuads, int heightQuads, int m)
{
  const int top = topLevel(widthQuads, heightQuads);
  for (int n = m + 1; n <= top; ++n)
  {
    if (blockShape(widthQuads, heightQuads, n) != BlockShape::Invalid)
    {
      return n;
    }
  }
  return -1;
}

void clearMorph(const Quadtree& qt, MorphFrame& out)
{
  out.blockT.assign(qt.blockCount(), 0.0f);
  out.blockTarget.assign(qt.blockCount(), -1);
  out.vEdges.assign(static_cast<std::size_t>(qt.blockCols + 1) * qt.blockRows, MorphEdge());
  out.hEdges.assign(static_cast<std::size_t>(qt.blockCols) * (qt.blockRows + 1), MorphEdge());
  out.maxBoundPixels = 0.0;
}

void computeMorph(const Heightfield& hf, const Quadtree& qt, const ErrorTable& table,
  const std::vector<int8_t>& levels, const std::vector<double>& factor, double tau,
  MorphFrame& out)
{
  clearMorph(qt, out);
  const int blocks = qt.blockCount();
  // Per drawn block: its certified error E, slack tau / f - E (-1: no morph) and the
  // largest displacement of any of its vertices (for the reported bound).
  std::vector<double> certified(blocks, 0.0), slack(blocks, -1.0), moved(blocks, 0.0);
  for (int b = 0; b < blocks; ++b)
  {
    const int m = levels[b];
    if (m < 0)
    {
      continue;
    }
    certified[b] = blockCertifiedError(qt, table, levels, b);
    const double f = b < static_cast<int>(factor.size()) ? factor[b] : 0.0;
    if (std::isfinite(f) && f > 0.0)
    {
      slack[b] = std::max(0.0, tau / f - certified[b]);
    }
    const int target = nextValidLevel(qt.blockWidth(b), qt.blockHeight(b), m);
    out.blockTarget[b] = static_cast<int8_t>(target);
    if (target < 0)
    {
      continue;
    }
    // Every interior vertex moves to the level-`target` surface at a sample, whose distance
    // to the sample is at most that level's exact error.
    const double dInt = table.ownExact(b, target);
    out.blockT[b] = factorDown(allowance(slack[b], dInt));
    moved[b] = out.blockT[b] > 0.0f ? out.blockT[b] * dInt : 0.0;
  }

  // One shared edge between blocks a and b (either -1 when absent), along [first, last].
  auto edge = [&](int a, int b, int first, int last, auto at) {
    MorphEdge e;
    const int la = a >= 0 ? levels[a] : -1, lb = b >= 0 ? levels[b] : -1;
    const int n = std::max(la, lb);
    if (n < 0)
    {
      return e;
    }
    e.level = static_cast<int8_t>(n);
    int target = -1;
    double tOwner = 1.0;
    for (int k : { a, b })
    {
      if (k >= 0 && levels[k] == n && out.blockTarget[k] >= 0)
      {
        target = target < 0 ? out.blockTarget[k] : std::min<int>(target, out.blockTarget[k]);
        tOwner = std::min(tOwner, static_cast<double>(out.blockT[k]));
      }
    }
    if (target < 0)
    {
      return e;
    }
    e.target = static_cast<int8_t>(target);
    const double d = edgeDisplacement(first, last, n, target, at);
    double t = tOwner;
    for (int k : { a, b })
    {
      if (k >= 0 && levels[k] >= 0)
      {
        t = std::min(t, allowance(slack[k], d));
      }
    }
    e.t = factorDown(t);
    if (e.t > 0.0f)
    {
      for (int k : { a, b })
      {
        if (k >= 0 && levels[k] >= 0)
        {
          moved[k] = std::max(moved[k], e.t * d);
        }
      }
    }
    return e;
  };

  const int bc = qt.blockCols, br = qt.blockRows;
  for (int r = 0; r < br; ++r)
  {
    for (int line = 0; line <= bc; ++line)
    {
      const int west = line > 0 ? qt.blockIndex(line - 1, r) : -1;
      const int east = line < bc ? qt.blockIndex(line, r) : -1;
      const int i = qt.colStart[line];
      out.vEdges[static_cast<std::size_t>(r) * (bc + 1) + line] = edge(west, east, qt.rowStart[r],
        qt.rowStart[r + 1], [&hf, i](int j) { return static_cast<double>(hf.height(i, j)); });
    }
  }
  for (int line = 0; line <= br; ++line)
  {
    for (int c = 0; c < bc; ++c)
    {
      const int south = line > 0 ? qt.blockIndex(c, line - 1) : -1;
      const int north = line < br ? qt.blockIndex(c, line) : -1;
      const int j = qt.rowStart[line];
      out.hEdges[static_cast<std::size_t>(line) * bc + c] = edge(south, north, qt.colStart[c],
        qt.colStart[c + 1], [&hf, j](int i) { return static_cast<double>(hf.height(i, j)); });
    }
  }
  for (int b = 0; b < blocks; ++b)
  {
    const double f = b < static_cast<int>(factor.size()) ? factor[b] : 0.0;
    if (levels[b] >= 0 && std::isfinite(f) && f > 0.0)
    {
      out.maxBoundPixels = std::max(out.maxBoundPixels, (certified[b] + moved[b]) * f);
    }
  }
}

double morphTarget(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j, double* factorOut)
{
  const double h = hf.height(i, j);
  *factorOut = 0.0;
  const int c = bandOf(qt.colStart, i), r = bandOf(qt.rowStart, j);
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const bool onV = i == i0 || i == i1, onH = j == j0 || j == j1;
  if (onV && onH)
  {
    return h; // block corner: on every level
  }
  if (onV)
  {
    const int line = i == i0 ? c : c + 1;
    const MorphEdge& e = frame.vEdges[static_cast<std::size_t>(r) * (qt.blockCols + 1) + line];
    if (e.target < 0)
    {
      return h;
    }
    *factorOut = e.t;
    return polylineAt(j0, j1, e.target, j, [&hf, i](int s) { return double(hf.height(i, s)); });
  }
  if (onH)
  {
    const int line = j == j0 ? r : r + 1;
    const MorphEdge& e = frame.hEdges[static_cast<std::size_t>(line) * qt.blockCols + c];
    if (e.target < 0)
    {
      return h;
    }
    *factorOut = e.t;
    return polylineAt(i0, i1, e.target, i, [&hf, j](int s) { return double(hf.height(s, j)); });
  }
  const int b = qt.blockIndex(c, r);
  const int target = frame.blockTarget[b];
  if (levels[b] < 0 || target < 0)
  {
    return h;
  }
  *factorOut = frame.blockT[b];
  return blockSurfaceAt(hf, i0, i1, j0, j1, target, i, j);
}

double morphedHeight(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j)
{
  double t = 0.0;
  const double c = morphTarget(hf, qt, levels, frame, i, j, &t);
  const double h = hf.height(i, j);
  // t == 0 must give h exactly, even where the target is nodata (NaN).
  return t > 0.0 && std::isfinite(c) ? h + t * (c - h) : h;
}

} // namespace gmm
