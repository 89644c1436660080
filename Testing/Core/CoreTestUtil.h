// Shared helpers for the engine tests. Everything here is written from first principles:
// no helper calls the engine's error, tessellation or projection code, so the tests that
// use them check the engine independently of the code that makes the claims.
#pragma once

#include "CoarsePerimeter.h"
#include "Engine.h"
#include "Heightfield.h"
#include "Morph.h"
#include "Quadtree.h"
#include "View.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace gmmtest
{

using Rng = std::mt19937_64;

inline int randInt(Rng& rng, int lo, int hi) // inclusive
{
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}
inline double randReal(Rng& rng, double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Rough terrain: smooth base + white noise + spikes + steps. Deliberately nasty for LOD.
inline gmm::Heightfield roughTerrain(int nx, int ny, Rng& rng, double spacingX = 10.0,
  double spacingY = 10.0, double amplitude = 300.0, double maxNoise = 0.1)
{
  gmm::Heightfield hf;
  hf.nx = nx;
  hf.ny = ny;
  hf.dx = spacingX;
  hf.dy = spacingY;
  hf.x0 = randReal(rng, -1000.0, 1000.0);
  hf.y0 = randReal(rng, -1000.0, 1000.0);
  hf.z.resize(static_cast<std::size_t>(nx) * ny);
  const double fx = randReal(rng, 0.01, 0.2), fy = randReal(rng, 0.01, 0.2);
  const double noise = amplitude * randReal(rng, 0.0, maxNoise);
  const int stepCol = randInt(rng, 0, nx - 1);
  const double stepH = randReal(rng, -0.5, 0.5) * amplitude;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      double h = amplitude * 0.5 * (std::sin(fx * i) * std::cos(fy * j) + 1.0);
      h += noise * u(rng);
      if (i >= stepCol)
        h += stepH;
      hf.z[hf.index(i, j)] = static_cast<float>(h);
    }
  const int spikes = randInt(rng, 0, 1 + nx * ny / 500);
  for (int s = 0; s < spikes; ++s)
  {
    int i = randInt(rng, 0, nx - 1), j = randInt(rng, 0, ny - 1);
    hf.z[hf.index(i, j)] += static_cast<float>(randReal(rng, -1.0, 1.0) * amplitude);
  }
  return hf;
}

// Ranges of randomViewOver: the eye up to `margin` of the extent outside it, at a height in
// [lowEye, highEye]; the pitch in [lowPitch, highPitch] radians; the far plane in [lowFar, 1e5].
struct ViewRanges
{
  double margin = 0.2, lowEye = 50.0, highEye = 3000.0;
  double lowPitch = -1.4, highPitch = -0.05, lowFar = 500.0;
};

// A perspective view over the heightfield, any heading, fov 20 - 90, 640 x 400, near 1.
inline gmm::View randomViewOver(const gmm::Heightfield& hf, Rng& rng, const ViewRanges& r = ViewRanges())
{
  const double w = (hf.nx - 1) * hf.dx, h = (hf.ny - 1) * hf.dy;
  gmm::View v;
  v.eye = { hf.x0 + randReal(rng, -r.margin, 1.0 + r.margin) * w,
    hf.y0 + randReal(rng, -r.margin, 1.0 + r.margin) * h, randReal(rng, r.lowEye, r.highEye) };
  const double yaw = randReal(rng, 0, 6.283), pitch = randReal(rng, r.lowPitch, r.highPitch);
  v.forward = { std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch) };
  v.up = { 0, 0, 1 };
  v.fovYDegrees = randReal(rng, 20, 90);
  v.viewportWidth = 640;
  v.viewportHeight = 400;
  v.nearDistance = 1.0;
  v.farDistance = randReal(rng, r.lowFar, 1e5);
  return v;
}

// Valid levels of a block, from Levels.h's rules restated here (not the engine's code).
inline bool refLevelValid(int w, int h, int m)
{
  const long long s = 1LL << m;
  if (s < w && s < h)
    return true; // ring
  if (s >= w && s >= h)
    return true; // one quad
  if (m == 0 && (w == 1 || h == 1))
    return true; // thin
  return false;
}
inline int refTopLevel(int w, int h)
{
  int side = std::max(w, h), m = 0;
  while ((1LL << m) < side)
    ++m;
  return m;
}

// Random explicit levels (Engine::updateWithLevels): each block -1 or a level from 0 to its
// top, kept where valid (refLevelValid; 0 only on a block with nodata), else -1.
inline std::vector<int8_t> randomValidLevels(const gmm::Quadtree& qt, Rng& rng)
{
  std::vector<int8_t> levels(qt.blockCount(), -1);
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    const int m = randInt(rng, -1, refTopLevel(w, h));
    if (m >= 0 && refLevelValid(w, h, m) && !(qt.blockHasNodata[b] && m > 0))
      levels[b] = static_cast<int8_t>(m);
  }
  return levels;
}

// One engine frame of a random kind: a random view at tau 0.3 - 8 (6 in 10), a
// view-independent error of 0 - 50 (2 in 10), or random valid levels (2 in 10).
inline void randomEngineFrame(gmm::Engine& e, Rng& rng)
{
  const int kind = randInt(rng, 0, 9);
  if (kind < 6)
    e.update(randomViewOver(e.heightfield(), rng), randReal(rng, 0.3, 8.0));
  else if (kind < 8)
    e.updateForError(randReal(rng, 0.0, 50.0));
  else
    e.updateWithLevels(randomValidLevels(e.quadtree(), rng));
}

// Triangles of the coarsest frame (a huge tolerance, no nodata) below quadtree node
// `node`, from the design rather than the engine: with merged nodes, the highest node on
// each path that spans at least 2 x 2 blocks is drawn whole, a fan with one triangle per
// block side on its border, 2 (cols + rows); a block not below one is a single quad, two
// triangles.
// Calls set(i, j, value) at every grid sample that triangle (a, b, c) covers, edges
// included, with the value interpolated from its vertices' heights: a plain per-sample
// test, independent of the engine's rasterisers.
template <typename Set>
void paintTriangle(int ai, int aj, int bi, int bj, int ci, int cj, double ha, double hb, double hc, Set set)
{
  const double area = double(bi - ai) * (cj - aj) - double(bj - aj) * (ci - ai);
  if (area == 0.0)
    return;
  for (int j = std::min({ aj, bj, cj }); j <= std::max({ aj, bj, cj }); ++j)
    for (int i = std::min({ ai, bi, ci }); i <= std::max({ ai, bi, ci }); ++i)
    {
      const double wa = (double(bi - i) * (cj - j) - double(bj - j) * (ci - i)) / area;
      const double wb = (double(ci - i) * (aj - j) - double(cj - j) * (ai - i)) / area;
      const double wc = 1.0 - wa - wb;
      if (wa >= -1e-12 && wb >= -1e-12 && wc >= -1e-12)
        set(i, j, wa * ha + wb * hb + wc * hc);
    }
}

// Per quadtree node, the perimeter depth of each node the engine drew whole in its last
// frame, -1 for the others (PerimeterContext's depths).
inline std::vector<int8_t> drawnNodeDepths(const gmm::Engine& e)
{
  std::vector<int8_t> depth(e.quadtree().nodes.size(), -1);
  for (std::size_t k = 0; k < e.mergedNodeList().size(); ++k)
    depth[e.mergedNodeList()[k]] = e.mergedNodeDepths()[k];
  return depth;
}

inline std::size_t coarsestTriangles(const gmm::Quadtree& qt, bool mergedNodes = true, int node = 0)
{
  const gmm::QuadtreeNode& n = qt.nodes[node];
  const int cols = n.colEnd - n.colBegin, rows = n.rowEnd - n.rowBegin;
  // A node drawn whole: a fan to its four corners where its perimeter may be coarse
  // (CoarsePerimeter.h), else to every block corner on its border.
  if (mergedNodes && cols >= 2 && rows >= 2)
    return gmm::perimeterCoarsens(qt, node) ? 4u : 2u * static_cast<std::size_t>(cols + rows);
  if (n.childCount == 0)
    return 2u;
  std::size_t sum = 0;
  for (int k = 0; k < n.childCount; ++k)
    sum += coarsestTriangles(qt, mergedNodes, n.firstChild + k);
  return sum;
}

// Reference bands (Quadtree.h, splitBands) over `quads` quads from `start`: as many bands of
// the width w as fit, the remainder after them; a remainder of one quad makes the last full
// band w + 1 quads, split into max(2, (w + 1) / 4 * 2) and the rest when w + 1 > maxQuads.
// w: `quads` when it is at most maxQuads, else the largest power of two p >= 2 with
// p * 2^k <= quads, 2^k the smallest power of two with quads <= maxQuads * 2^k.
inline void refSplit(int start, int quads, int maxQuads, std::vector<int>& starts)
{
  if (maxQuads < 1)
    maxQuads = 1;
  long scale = 1;
  while (static_cast<long>(maxQuads) * scale < quads)
    scale *= 2;
  int w = 2;
  while (static_cast<long>(w) * 2 * scale <= quads)
    w *= 2;
  if (quads <= w || quads <= maxQuads)
  {
    starts.push_back(start);
    return;
  }
  int full = quads / w;
  const int rest = quads % w;
  if (rest == 0 || rest == 1)
    --full; // the last band: w quads, or w + 1 split below
  for (int k = 0; k < full; ++k)
    starts.push_back(start + k * w);
  const int at = start + full * w, left = quads - full * w;
  starts.push_back(at);
  if (rest == 1 && w + 1 > maxQuads)
    starts.push_back(at + std::max(2, left / 4 * 2));
}
// With collars (Quadtree.h, splitBands): a band of each collar at the ends, widened by one
// quad where the band after (before) it would start on an odd sample, the quads between
// split by refSplit; both collars dropped when fewer than 4 quads would be left between.
inline std::vector<int> refSplitBands(int quads, int maxQuads, int lowCollar = 0, int highCollar = 0)
{
  if (lowCollar % 2 == 1)
    ++lowCollar;
  if (highCollar > 0 && (quads - highCollar) % 2 == 1)
    ++highCollar;
  if (quads - lowCollar - highCollar < 4)
    lowCollar = highCollar = 0;
  std::vector<int> s;
  if (lowCollar > 0)
    s.push_back(0);
  refSplit(lowCollar, quads - lowCollar - highCollar, maxQuads, s);
  if (highCollar > 0)
    s.push_back(quads - highCollar);
  s.push_back(quads);
  return s;
}

// ---------------------------------------------------------------------------------------
// Mesh invariants, exact integer arithmetic in grid (i, j) coordinates.
struct MeshCheckOptions
{
  // Per block: drawn or not. Empty = all drawn.
  std::vector<bool> drawn;
  bool allowNodataHoles = false; // boundary edges may also border cells touching NaN
  bool checkArea = true;         // area sum == drawn area (only without NaN)
};

struct MeshCheckResult
{
  std::string error; // empty when all invariants hold
  long long doubledArea = 0;
  std::size_t triangles = 0;
};

inline long long cross2(long long ax, long long ay, long long bx, long long by)
{
  return ax * by - ay * bx;
}

// Checks the triangle list `idx` over the heightfield `hf` split into blocks by `qt` bands.
inline MeshCheckResult checkMesh(const gmm::Heightfield& hf, const std::vector<int>& colStart,
  const std::vector<int>& rowStart, const std::vector<uint32_t>& idx, const MeshCheckOptions& opt)
{
  MeshCheckResult res;
  std::ostringstream err;
  auto fail = [&](const std::string& s) {
    if (res.error.empty())
      res.error = s;
  };
  const int nx = hf.nx, ny = hf.ny;
  const long long nv = static_cast<long long>(nx) * ny;
  if (idx.size() % 3 != 0)
  {
    fail("index count not a multiple of 3");
    return res;
  }
  res.triangles = idx.size() / 3;
  const int blockCols = static_cast<int>(colStart.size()) - 1;
  const int blockRows = static_cast<int>(rowStart.size()) - 1;
  // cell -> band lookups
  std::vector<int> colOfCell(std::max(nx - 1, 0)), rowOfCell(std::max(ny - 1, 0));
  for (int c = 0; c < blockCols; ++c)
    for (int i = colStart[c]; i < colStart[c + 1]; ++i)
      colOfCell[i] = c;
  for (int r = 0; r < blockRows; ++r)
    for (int j = rowStart[r]; j < rowStart[r + 1]; ++j)
      rowOfCell[j] = r;
  auto cellDrawn = [&](int ci, int cj) -> bool {
    if (ci < 0 || cj < 0 || ci >= nx - 1 || cj >= ny - 1)
      return false;
    if (!opt.drawn.empty() && !opt.drawn[rowOfCell[cj] * blockCols + colOfCell[ci]])
      return false;
    if (opt.allowNodataHoles)
    {
      for (int dj = 0; dj <= 1; ++dj)
        for (int di = 0; di <= 1; ++di)
          if (!std::isfinite(hf.height(ci + di, cj + dj)))
            return false;
    }
    return true;
  };

  const bool mirrored = (hf.dx < 0) != (hf.dy < 0);
  std::vector<uint8_t> used(static_cast<std::size_t>(nv), 0);
  std::vector<uint64_t> directed;
  directed.reserve(idx.size());
  std::vector<std::array<uint32_t, 3>> canon;
  canon.reserve(res.triangles);
  for (std::size_t t = 0; t < res.triangles; ++t)
  {
    uint32_t v[3] = { idx[3 * t], idx[3 * t + 1], idx[3 * t + 2] };
    bool inRange = true;
    for (uint32_t x : v)
      if (static_cast<long long>(x) >= nv)
        inRange = false;
    if (!inRange)
    {
      fail("index out of range in triangle " + std::to_string(t));
      return res;
    }
    for (uint32_t x : v)
      used[x] = 1;
    long long i0 = v[0] % nx, j0 = v[0] / nx, i1 = v[1] % nx, j1 = v[1] / nx, i2 = v[2] % nx,
              j2 = v[2] / nx;
    long long a2 = cross2(i1 - i0, j1 - j0, i2 - i0, j2 - j0);
    if (a2 == 0)
    {
      fail("zero-area triangle " + std::to_string(t));
      continue;
    }
    // world orientation: grid area sign times sign(dx*dy)
    const bool ccwWorld = mirrored ? (a2 < 0) : (a2 > 0);
    if (!ccwWorld)
    {
      std::ostringstream s;
      s << "triangle " << t << " (" << i0 << "," << j0 << ")(" << i1 << "," << j1 << ")(" << i2
        << "," << j2 << ") is clockwise seen from +z in world coordinates";
      fail(s.str());
    }
    res.doubledArea += std::llabs(a2);
    for (int e = 0; e < 3; ++e)
      directed.push_back((static_cast<uint64_t>(v[e]) << 32) | v[(e + 1) % 3]);
    std::array<uint32_t, 3> c{ v[0], v[1], v[2] };
    std::sort(c.begin(), c.end());
    canon.push_back(c);
  }
  std::sort(canon.begin(), canon.end());
  if (std::adjacent_find(canon.begin(), canon.end()) != canon.end())
    fail("duplicate triangle");
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end())
    fail("directed edge used twice (overlap or fold)");
  for (uint64_t e : directed)
  {
    uint32_t a = static_cast<uint32_t>(e >> 32), b = static_cast<uint32_t>(e);
    uint64_t rev = (static_cast<uint64_t>(b) << 32) | a;
    long long ia = a % nx, ja = a / nx, ib = b % nx, jb = b / nx;
    // T-junction: no used vertex strictly inside the segment (lattice points only).
    long long di = ib - ia, dj = jb - ja;
    long long g = std::gcd(std::llabs(di), std::llabs(dj));
    for (long long k = 1; k < g; ++k)
    {
      long long pi = ia + k * di / g, pj = ja + k * dj / g;
      if (used[static_cast<std::size_t>(pj * nx + pi)])
      {
        std::ostringstream s;
        s << "T-junction: vertex (" << pi << "," << pj << ") lies inside edge (" << ia << ","
          << ja << ")-(" << ib << "," << jb << ")";
        fail(s.str());
        break;
      }
    }
    if (std::binary_search(directed.begin(), directed.end(), rev))
      continue; // interior edge with opposite orientation
    // boundary edge: must be axis-aligned and every unit piece must separate a drawn cell
    // from an undrawn/outside one.
    bool ok = true;
    if (ia == ib)
    {
      for (long long j = std::min(ja, jb); j < std::max(ja, jb) && ok; ++j)
        if (cellDrawn(static_cast<int>(ia - 1), static_cast<int>(j)) &&
          cellDrawn(static_cast<int>(ia), static_cast<int>(j)))
          ok = false;
    }
    else if (ja == jb)
    {
      for (long long i = std::min(ia, ib); i < std::max(ia, ib) && ok; ++i)
        if (cellDrawn(static_cast<int>(i), static_cast<int>(ja - 1)) &&
          cellDrawn(static_cast<int>(i), static_cast<int>(ja)))
          ok = false;
    }
    else
      ok = false;
    if (!ok && opt.allowNodataHoles)
    {
      // around holes any edge may be a border: accept it when a cell touching its
      // midpoint is not drawn (outside, undrawn block, or touching nodata)
      const double mx = 0.5 * (ia + ib), my = 0.5 * (ja + jb);
      for (int cj = static_cast<int>(std::ceil(my)) - 1; cj <= static_cast<int>(std::floor(my)); ++cj)
        for (int ci = static_cast<int>(std::ceil(mx)) - 1; ci <= static_cast<int>(std::floor(mx)); ++ci)
          if (!cellDrawn(ci, cj))
            ok = true;
    }
    if (!ok)
    {
      std::ostringstream s;
      s << "boundary edge (" << ia << "," << ja << ")-(" << ib << "," << jb
        << ") used once but not on the border of the drawn region";
      fail(s.str());
    }
  }
  if (opt.checkArea)
  {
    long long expected = 0;
    for (int r = 0; r < blockRows; ++r)
      for (int c = 0; c < blockCols; ++c)
        if (opt.drawn.empty() || opt.drawn[r * blockCols + c])
          expected += 2LL * (colStart[c + 1] - colStart[c]) * (rowStart[r + 1] - rowStart[r]);
    if (expected != res.doubledArea)
      fail("doubled area " + std::to_string(res.doubledArea) + " != drawn region's " +
        std::to_string(expected));
  }
  return res;
}

// ---------------------------------------------------------------------------------------
// Area coverage of the unit cells: cell (i, j) is the grid square [i, i+1] x [j, j+1]. Each
// triangle (lattice vertices, grid coordinates) is clipped to every cell of its bounding box
// and the clipped areas are summed per cell, so a cell covered once has area 1 (to double
// rounding, ~1e-12), a missing triangle leaves a deficit and an overlap an excess.
inline std::vector<double> cellCoverage(const gmm::Heightfield& hf, const std::vector<uint32_t>& idx)
{
  const int nx = hf.nx, cw = std::max(hf.nx - 1, 0), ch = std::max(hf.ny - 1, 0);
  std::vector<double> area(static_cast<std::size_t>(cw) * ch, 0.0);
  struct P
  {
    double x, y;
  };
  // keeps the part of poly with sign * (coord - bound) >= 0 (axis 0: x, 1: y)
  auto clip = [](const P* in, int n, P* out, int axis, double bound, double sign) {
    int m = 0;
    for (int k = 0; k < n; ++k)
    {
      const P& a = in[k];
      const P& b = in[(k + 1) % n];
      const double da = sign * ((axis ? a.y : a.x) - bound), db = sign * ((axis ? b.y : b.x) - bound);
      if (da >= 0)
        out[m++] = a;
      if ((da >= 0) != (db >= 0))
      {
        const double t = da / (da - db);
        out[m++] = P{ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) };
      }
    }
    return m;
  };
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
  {
    P tri[3];
    for (int k = 0; k < 3; ++k)
      tri[k] = P{ static_cast<double>(idx[t + k] % nx), static_cast<double>(idx[t + k] / nx) };
    const int i0 = static_cast<int>(std::min({ tri[0].x, tri[1].x, tri[2].x }));
    const int i1 = static_cast<int>(std::max({ tri[0].x, tri[1].x, tri[2].x }));
    const int j0 = static_cast<int>(std::min({ tri[0].y, tri[1].y, tri[2].y }));
    const int j1 = static_cast<int>(std::max({ tri[0].y, tri[1].y, tri[2].y }));
    for (int j = j0; j < j1 && j < ch; ++j)
      for (int i = i0; i < i1 && i < cw; ++i)
      {
        P a[8], b[8];
        int n = clip(tri, 3, a, 0, i, 1.0);
        n = clip(a, n, b, 0, i + 1, -1.0);
        n = clip(b, n, a, 1, j, 1.0);
        n = clip(a, n, b, 1, j + 1, -1.0);
        double twice = 0.0;
        for (int k = 0; k < n; ++k)
          twice += b[k].x * b[(k + 1) % n].y - b[(k + 1) % n].x * b[k].y;
        area[static_cast<std::size_t>(j) * cw + i] += 0.5 * std::fabs(twice);
      }
  }
  return area;
}

// Coverage a frame must have, whatever its levels: every cell of a block with mustCover
// whose four corner samples are finite is covered exactly once; no cell of a block that is
// not drawn is covered; no cell anywhere is covered more than once. Blocks are the bands
// colStart x rowStart (block index row * cols + col). Returns "" or the first violation.
inline std::string checkCoverage(const gmm::Heightfield& hf, const std::vector<int>& colStart,
  const std::vector<int>& rowStart, const std::vector<uint32_t>& idx,
  const std::vector<bool>& drawn, const std::vector<bool>& mustCover)
{
  const std::vector<double> area = cellCoverage(hf, idx);
  const int cw = hf.nx - 1, cols = static_cast<int>(colStart.size()) - 1;
  const double eps = 1e-9;
  for (int r = 0; r + 1 < static_cast<int>(rowStart.size()); ++r)
    for (int c = 0; c < cols; ++c)
    {
      const int b = r * cols + c;
      for (int j = rowStart[r]; j < rowStart[r + 1]; ++j)
        for (int i = colStart[c]; i < colStart[c + 1]; ++i)
        {
          const double a = area[static_cast<std::size_t>(j) * cw + i];
          const bool valid = std::isfinite(hf.height(i, j)) && std::isfinite(hf.height(i + 1, j)) &&
            std::isfinite(hf.height(i, j + 1)) && std::isfinite(hf.height(i + 1, j + 1));
          std::string why;
          if (a > 1.0 + eps)
            why = "covered more than once";
          else if (!drawn[b] && a > eps)
            why = "covered although its block is not drawn";
          else if (drawn[b] && mustCover[b] && valid && std::fabs(a - 1.0) > eps)
            why = "has 4 valid samples but is not covered exactly once";
          if (!why.empty())
          {
            char buf[200];
            std::snprintf(buf, sizeof buf, "cell (%d,%d) of block %d: area %.9f %s", i, j, b, a,
              why.c_str());
            return buf;
          }
        }
    }
  return std::string();
}

// ---------------------------------------------------------------------------------------
// Drawn surface under every sample: rasterise each triangle over lattice points (exact
// integer inside test) and interpolate z barycentrically in double from the float heights.
struct SurfaceSample
{
  std::vector<double> z;        // NaN where no triangle covers the sample
  std::vector<uint8_t> covered; // number of covering triangles (capped at 255)
  double maxDisagreement = 0.0; // between triangles sharing a sample (edges/vertices)
};

// `drawnZ` (one height per sample, optional): the heights the mesh's vertices are drawn
// at when they are not the samples' own (a geomorphed frame).
inline SurfaceSample sampleSurface(const gmm::Heightfield& hf, const std::vector<uint32_t>& idx,
  const double* drawnZ = nullptr)
{
  SurfaceSample s;
  const int nx = hf.nx;
  s.z.assign(hf.z.size(), std::numeric_limits<double>::quiet_NaN());
  s.covered.assign(hf.z.size(), 0);
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
  {
    long long I[3], J[3];
    double Z[3];
    for (int k = 0; k < 3; ++k)
    {
      I[k] = idx[t + k] % nx;
      J[k] = idx[t + k] / nx;
      Z[k] = drawnZ ? drawnZ[idx[t + k]] : static_cast<double>(hf.z[idx[t + k]]);
    }
    long long area = cross2(I[1] - I[0], J[1] - J[0], I[2] - I[0], J[2] - J[0]);
    if (area == 0)
      continue;
    long long imin = std::min({ I[0], I[1], I[2] }), imax = std::max({ I[0], I[1], I[2] });
    long long jmin = std::min({ J[0], J[1], J[2] }), jmax = std::max({ J[0], J[1], J[2] });
    for (long long j = jmin; j <= jmax; ++j)
      for (long long i = imin; i <= imax; ++i)
      {
        long long w0 = cross2(I[2] - I[1], J[2] - J[1], i - I[1], j - J[1]);
        long long w1 = cross2(I[0] - I[2], J[0] - J[2], i - I[2], j - J[2]);
        long long w2 = cross2(I[1] - I[0], J[1] - J[0], i - I[0], j - J[0]);
        if (area < 0)
        {
          w0 = -w0;
          w1 = -w1;
          w2 = -w2;
        }
        if (w0 < 0 || w1 < 0 || w2 < 0)
          continue;
        const double a = static_cast<double>(std::llabs(area));
        const double z = (w0 * Z[0] + w1 * Z[1] + w2 * Z[2]) / a;
        const std::size_t k = static_cast<std::size_t>(j) * nx + i;
        if (s.covered[k] == 0)
          s.z[k] = z;
        else
          s.maxDisagreement = std::max(s.maxDisagreement, std::fabs(s.z[k] - z));
        if (s.covered[k] < 255)
          ++s.covered[k];
      }
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// Projection written from the definition in View.h (not the engine's code).
struct MyCamera
{
  double ex, ey, ez;
  double f[3], r[3], u[3];
  double scale; // pixels per unit at depth 1 (perspective) or everywhere (parallel)
  bool parallel;
  double nearD, farD;
  int W, H;
};

inline MyCamera makeCamera(const gmm::View& v)
{
  MyCamera c{};
  c.ex = v.eye.x;
  c.ey = v.eye.y;
  c.ez = v.eye.z;
  double fl = std::sqrt(v.forward.x * v.forward.x + v.forward.y * v.forward.y +
    v.forward.z * v.forward.z);
  c.f[0] = v.forward.x / fl;
  c.f[1] = v.forward.y / fl;
  c.f[2] = v.forward.z / fl;
  // right = f x up, normalised; true up = right x f
  double rx = c.f[1] * v.up.z - c.f[2] * v.up.y;
  double ry = c.f[2] * v.up.x - c.f[0] * v.up.z;
  double rz = c.f[0] * v.up.y - c.f[1] * v.up.x;
  double rl = std::sqrt(rx * rx + ry * ry + rz * rz);
  c.r[0] = rx / rl;
  c.r[1] = ry / rl;
  c.r[2] = rz / rl;
  c.u[0] = c.r[1] * c.f[2] - c.r[2] * c.f[1];
  c.u[1] = c.r[2] * c.f[0] - c.r[0] * c.f[2];
  c.u[2] = c.r[0] * c.f[1] - c.r[1] * c.f[0];
  c.parallel = v.parallel;
  const double halfH = 0.5 * v.viewportHeight;
  const double pi = 3.14159265358979323846;
  c.scale = v.parallel ? halfH / v.parallelScale : halfH / std::tan(v.fovYDegrees * pi / 360.0);
  c.nearD = v.nearDistance;
  c.farD = v.farDistance;
  c.W = v.viewportWidth;
  c.H = v.viewportHeight;
  return c;
}

// Returns depth along forward; px, py in pixels (origin lower-left, y up).
inline double project(const MyCamera& c, double x, double y, double z, double& px, double& py)
{
  const double p[3] = { x - c.ex, y - c.ey, z - c.ez };
  const double d = p[0] * c.f[0] + p[1] * c.f[1] + p[2] * c.f[2];
  const double a = p[0] * c.r[0] + p[1] * c.r[1] + p[2] * c.r[2];
  const double b = p[0] * c.u[0] + p[1] * c.u[1] + p[2] * c.u[2];
  if (c.parallel)
  {
    px = 0.5 * c.W + c.scale * a;
    py = 0.5 * c.H + c.scale * b;
  }
  else
  {
    px = 0.5 * c.W + c.scale * a / d;
    py = 0.5 * c.H + c.scale * b / d;
  }
  return d;
}

inline bool insideFrustum(const MyCamera& c, double x, double y, double z)
{
  double px, py;
  const double d = project(c, x, y, z, px, py);
  if (!(d >= c.nearD && d <= c.farD))
    return false;
  return px >= 0.0 && px <= c.W && py >= 0.0 && py <= c.H;
}

// Measured error of a drawn mesh, sample by sample (the independent check behind every
// certification test). For each finite sample: the vertical distance to the drawn surface
// (drawn samples only); with a view, for samples inside the frustum, the pixel distance
// between the sample and the surface point above/below it, projected with MyCamera.
struct ScreenMeasure
{
  std::size_t inFrustum = 0, uncovered = 0, skippedNear = 0, violations = 0;
  double maxDist = 0.0;     // pixels
  double maxVertical = 0.0; // metres, over drawn samples
  std::string first;        // the first uncovered sample or violation, in words
};

// True when the sample and its 8 neighbours (inside the grid) are finite: such a sample
// lies in cells whose every triangle is drawable, so it must be covered.
inline bool awayFromNodata(const gmm::Heightfield& hf, int i, int j)
{
  for (int b = std::max(0, j - 1); b <= std::min(hf.ny - 1, j + 1); ++b)
    for (int a = std::max(0, i - 1); a <= std::min(hf.nx - 1, i + 1); ++a)
      if (!std::isfinite(hf.height(a, b)))
        return false;
  return true;
}

// Violations are distances above tau * (1 + 1e-6) + 1e-6 px; uncovered counts in-frustum
// samples away from nodata that no triangle covers.
// Data -> world for the measure, written out by hand (no glm, no engine): the drawn point
// (x, y, z0 + scale * h) goes through a 4x4 affine matrix m (row-major, m[r][c]).
struct MeasureTransform
{
  double m[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
  double z0 = 0.0, heightScale = 1.0;
  void apply(double x, double y, double h, double out[3]) const
  {
    const double z = z0 + heightScale * h;
    for (int r = 0; r < 3; ++r)
      out[r] = m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3];
  }
};

// The heights an Engine's last frame draws its vertices at, unmorphed: the samples of
// glided edges on their edges' polylines (EdgeHeights.h), every other sample at its own
// height. What measureScreenError and sampleSurface take as drawnZ for an Engine used
// alone (FrameDriver::morph() gives the same for a driven frame).
inline std::vector<double> drawnHeights(const gmm::Engine& e)
{
  const gmm::Heightfield& hf = e.heightfield();
  gmm::MorphFrame f;
  gmm::drawnEdgeFrame(e.quadtree(), e.levels(), f, &e.drawnBlocks(), &e.drawnConfigs());
  std::vector<double> z(hf.heights(), hf.heights() + hf.sampleCount());
  for (uint32_t v : e.indices())
  {
    const int i = static_cast<int>(v % hf.nx), j = static_cast<int>(v / hf.nx);
    z[v] = gmm::morphedHeight(hf, e.quadtree(), e.levels(), f, i, j);
  }
  return z;
}

inline ScreenMeasure measureScreenError(const gmm::Heightfield& hf,
  const std::vector<uint32_t>& indices, const gmm::View* view, double tau,
  const MeasureTransform& toWorld = MeasureTransform(), const double* drawnZ = nullptr)
{
  ScreenMeasure m;
  const SurfaceSample surf = sampleSurface(hf, indices, drawnZ);
  MyCamera cam{};
  if (view)
    cam = makeCamera(*view);
  for (int j = 0; j < hf.ny; ++j)
    for (int i = 0; i < hf.nx; ++i)
    {
      const std::size_t k = hf.index(i, j);
      const double zp = hf.heights()[k];
      if (!std::isfinite(zp))
        continue;
      const bool drawn = !std::isnan(surf.z[k]);
      if (drawn)
        m.maxVertical = std::max(m.maxVertical, std::fabs(surf.z[k] - zp) * toWorld.heightScale);
      const double x = hf.worldX(i), y = hf.worldY(j);
      double pw[3], qw[3];
      toWorld.apply(x, y, zp, pw);
      if (!view || !insideFrustum(cam, pw[0], pw[1], pw[2]))
        continue;
      ++m.inFrustum;
      if (!drawn)
      {
        if (awayFromNodata(hf, i, j) && m.uncovered++ == 0 && m.first.empty())
          m.first = "in-frustum sample (" + std::to_string(i) + "," + std::to_string(j) + ") not covered";
        continue;
      }
      double px, py, qx, qy;
      project(cam, pw[0], pw[1], pw[2], px, py);
      toWorld.apply(x, y, surf.z[k], qw);
      if (project(cam, qw[0], qw[1], qw[2], qx, qy) < cam.nearD)
      {
        ++m.skippedNear; // surface point behind the near plane: not projectable
        continue;
      }
      const double dist = std::hypot(qx - px, qy - py);
      m.maxDist = std::max(m.maxDist, dist);
      if (dist > tau * (1 + 1e-6) + 1e-6 && m.violations++ == 0 && m.first.empty())
      {
        char buf[256];
        std::snprintf(buf, sizeof buf, "sample (%d,%d): z %.6f surface %.6f -> %.6g px > tau %.6g",
          i, j, zp, surf.z[k], dist, tau);
        m.first = buf;
      }
    }
  return m;
}

} // namespace gmmtest
