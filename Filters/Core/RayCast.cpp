#include "RayCast.h"

#include "Levels.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Segment
{
  glm::dvec3 p0, d; // p(t) = p0 + t d, t in [0, 1]
};

// Parameter range of the segment inside an axis-aligned box (slab test); empty when
// tEnter > tExit.
void clipToBox(const Segment& s, const glm::dvec3& lo, const glm::dvec3& hi, double& tEnter, double& tExit)
{
  tEnter = 0.0;
  tExit = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (s.d[a] == 0.0)
    {
      if (s.p0[a] < lo[a] || s.p0[a] > hi[a])
      {
        tEnter = 1.0;
        tExit = 0.0;
        return;
      }
      continue;
    }
    double ta = (lo[a] - s.p0[a]) / s.d[a], tb = (hi[a] - s.p0[a]) / s.d[a];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    tEnter = std::max(tEnter, ta);
    tExit = std::min(tExit, tb);
  }
}

class SurfaceWalker
{
public:
  SurfaceWalker(const Terrain& t, const Segment& s, double scale)
    : t_(t)
    , hf_(t.hf)
    , s_(s)
    , scale_(scale)
  {
  }

  SurfaceHit run()
  {
    if (!t_.qt.nodes.empty())
    {
      visit(0);
    }
    return best_;
  }

private:
  glm::dvec3 vertex(int i, int j) const
  {
    return { hf_.worldX(i), hf_.worldY(j), hf_.z0 + scale_ * hf_.height(i, j) };
  }

  // Data-frame box of a quadtree box (its z holds stored heights).
  void dataBox(const Box& b, glm::dvec3& lo, glm::dvec3& hi) const
  {
    lo = glm::dvec3(b.lo.x, b.lo.y, hf_.z0 + scale_ * b.lo.z);
    hi = glm::dvec3(b.hi.x, b.hi.y, hf_.z0 + scale_ * b.hi.z);
  }

  double entry(int node) const
  {
    glm::dvec3 lo, hi;
    dataBox(t_.qt.nodes[node].box, lo, hi);
    double a, b;
    clipToBox(s_, lo, hi, a, b);
    return a <= b ? a : kInf;
  }

  void visit(int node)
  {
    const QuadtreeNode& n = t_.qt.nodes[node];
    const double tIn = entry(node);
    if (tIn == kInf || (best_.hit && tIn > best_.t))
    {
      return;
    }
    if (n.childCount == 0)
    {
      walkBlock(n.block);
      return;
    }
    std::pair<double, int> order[4];
    int count = 0;
    for (int k = 0; k < n.childCount; ++k)
    {
      const double e = entry(n.firstChild + k);
      if (e != kInf)
      {
        order[count++] = { e, n.firstChild + k };
      }
    }
    // At most four: an insertion sort (std::sort here made GCC 12's -Warray-bounds see
    // its 16-element insertion pass run past the array).
    for (int k = 1; k < count; ++k)
    {
      for (int m = k; m > 0 && order[m] < order[m - 1]; --m)
      {
        std::swap(order[m], order[m - 1]);
      }
    }
    for (int k = 0; k < count; ++k)
    {
      if (best_.hit && order[k].first > best_.t)
      {
        break;
      }
      visit(order[k].second);
    }
  }

  // Grid quads of one block along the segment's x, y path (Amanatides & Woo), in order of t.
  void walkBlock(int block)
  {
    const int c = block % t_.qt.blockCols, r = block / t_.qt.blockCols;
    const int ci0 = t_.qt.colStart[c], ci1 = t_.qt.colStart[c + 1] - 1; // quad columns
    const int cj0 = t_.qt.rowStart[r], cj1 = t_.qt.rowStart[r + 1] - 1;
    glm::dvec3 lo, hi;
    dataBox(t_.qt.blockBox[block], lo, hi);
    double ta, tb;
    clipToBox(s_, lo, hi, ta, tb);
    if (ta > tb)
    {
      return;
    }
    // Grid coordinates along the segment: g(t) = g0 + t * dg.
    const double gx0 = (s_.p0.x - hf_.x0) / hf_.dx, gy0 = (s_.p0.y - hf_.y0) / hf_.dy;
    const double dgx = s_.d.x / hf_.dx, dgy = s_.d.y / hf_.dy;
    int i = std::clamp(static_cast<int>(std::floor(gx0 + ta * dgx)), ci0, ci1);
    int j = std::clamp(static_cast<int>(std::floor(gy0 + ta * dgy)), cj0, cj1);
    const int stepI = dgx > 0 ? 1 : -1, stepJ = dgy > 0 ? 1 : -1;
    auto nextCrossing = [](double g0, double dg, int cell, int step) {
      if (dg == 0.0)
      {
        return kInf;
      }
      const double line = step > 0 ? cell + 1 : cell;
      return (line - g0) / dg;
    };
    double tx = nextCrossing(gx0, dgx, i, stepI), ty = nextCrossing(gy0, dgy, j, stepJ);
    const double dtx = dgx != 0.0 ? std::abs(1.0 / dgx) : kInf;
    const double dty = dgy != 0.0 ? std::abs(1.0 / dgy) : kInf;
    for (;;)
    {
      if (testQuad(i, j))
      {
        return; // quads come in order of t: the first hit in this block is its nearest
      }
      if (tx < ty)
      {
        if (tx > tb)
          return;
        i += stepI;
        tx += dtx;
      }
      else
      {
        if (ty > tb || ty == kInf)
          return;
        j += stepJ;
        ty += dty;
      }
      if (i < ci0 || i > ci1 || j < cj0 || j > cj1)
      {
        return;
      }
    }
  }

  bool testQuad(int i, int j)
  {
    bool found = false;
    // The tessellation's split at full resolution (fullResolutionAntiDiagonal): (i, j)-(i+1, j)-
    // (i+1, j+1) and (i, j)-(i+1, j+1)-(i, j+1), or (i, j)-(i+1, j)-(i, j+1) and
    // (i+1, j)-(i+1, j+1)-(i, j+1).
    static constexpr int split[2][2][3][2] = {
      { { { 0, 0 }, { 1, 0 }, { 1, 1 } }, { { 0, 0 }, { 1, 1 }, { 0, 1 } } },
      { { { 0, 0 }, { 1, 0 }, { 0, 1 } }, { { 1, 0 }, { 1, 1 }, { 0, 1 } } },
    };
    for (const auto& v : split[fullResolutionAntiDiagonal(i, j) ? 1 : 0])
    {
      found = testTriangle(i, j, v) || found;
    }
    return found;
  }

  bool testTriangle(int i, int j, const int (&v)[3][2])
  {
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k)
    {
      if (std::isnan(hf_.height(i + v[k][0], j + v[k][1])))
      {
        return false; // a hole
      }
      p[k] = vertex(i + v[k][0], j + v[k][1]);
    }
    // Moller & Trumbore, relative to p[0] so that large coordinates keep their precision.
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::dvec3 pv = glm::cross(s_.d, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0 || !std::isfinite(det))
    {
      return false; // the segment is parallel to the triangle
    }
    const double inv = 1.0 / det;
    const glm::dvec3 tv = s_.p0 - p[0];
    const double u = glm::dot(tv, pv) * inv;
    constexpr double eps = 1e-12; // hits on a shared edge belong to both triangles
    if (u < -eps || u > 1.0 + eps)
    {
      return false;
    }
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double w = glm::dot(s_.d, qv) * inv;
    if (w < -eps || u + w > 1.0 + eps)
    {
      return false;
    }
    const double t = glm::dot(e2, qv) * inv;
    if (t < 0.0 || t > 1.0 || (best_.hit && t >= best_.t))
    {
      return false;
    }
    best_.hit = true;
    best_.t = t;
    best_.point = s_.p0 + t * s_.d;
    best_.cellI = i;
    best_.cellJ = j;
    best_.weights = glm::dvec3(1.0 - u - w, u, w);
    for (int k = 0; k < 3; ++k)
    {
      best_.vertex[k] = static_cast<uint32_t>(hf_.index(i + v[k][0], j + v[k][1]));
    }
    glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
    best_.normal = n.z < 0.0 ? -n : n;
    return true;
  }

  const Terrain& t_;
  const Heightfield& hf_;
  Segment s_;
  double scale_;
  SurfaceHit best_;
};

} // namespace

double heightAt(const Heightfield& hf, double x, double y, double heightScale)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double gx = (x - hf.x0) / hf.dx, gy = (y - hf.y0) / hf.dy;
  if (!(gx >= 0.0 && gx <= hf.nx - 1 && gy >= 0.0 && gy <= hf.ny - 1))
  {
    return nan;
  }
  const int i = std::min(static_cast<int>(gx), hf.nx - 2), j = std::min(static_cast<int>(gy), hf.ny - 2);
  const double fx = gx - i, fy = gy - j;
  const double h00 = hf.height(i, j), h10 = hf.height(i + 1, j), h01 = hf.height(i, j + 1);
  const double h11 = hf.height(i + 1, j + 1);
  const double h = splitQuadHeight(h00, h10, h01, h11, fx, fy, fullResolutionAntiDiagonal(i, j));
  return std::isnan(h) ? nan : hf.z0 + heightScale * h;
}

SurfaceHit intersectSegment(
  const Terrain& terrain, const glm::dvec3& p0, const glm::dvec3& p1, double heightScale)
{
  if (terrain.hf.nx < 2 || terrain.hf.ny < 2)
  {
    return SurfaceHit();
  }
  return SurfaceWalker(terrain, Segment{ p0, p1 - p0 }, heightScale).run();
}

} // namespace gmm
