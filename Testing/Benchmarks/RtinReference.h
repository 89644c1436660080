// Right-triangulated irregular network (RTIN) reference mesher: the yardstick of issue #11,
// benchmark-only (nothing in the product uses it).
//
// View-independent mode: the algorithm of Mapbox's `martini` (Agafonkin 2019, after Evans,
// Kirkpatrick and Townsend 2001), reimplemented from its published description so that our
// counts can be checked against martini's own on its Fuji fixture (bench_rtin --validate).
// The grid is (2^k + 1)^2; every triangle of the longest-edge bisection hierarchy is split
// at the midpoint of its hypotenuse, and the error of that midpoint vertex is the vertical
// distance of the sample to the hypotenuse's mean height, made nested (the maximum over the
// vertex's descendants, so a split forces its ancestors). A mesh for maxError splits every
// triangle whose midpoint error exceeds it.
//
// View-dependent mode (Lindstrom and Pascucci 2001, "Visualization of large terrains made
// easy"): each vertex also has a nested bounding sphere (radius = the largest distance to a
// descendant's sphere, so a vertex's sphere holds every descendant's). A vertex is active
// when its sphere meets the view frustum and its error, projected at the sphere's nearest
// distance from the eye, exceeds tau pixels: f * e > tau * (|eye - p| - r), f the pixels
// per unit at depth 1. Nesting makes activity monotone (an active vertex's ancestors are
// active), so the top-down split gives the least RTIN whose every vertex not drawn projects
// within tau by that measure. It is the measure the issue quotes; it ignores the off-axis
// magnification our certified bound covers (up to about 1.5x at a 60 degree field of view).
// Triangles wholly outside one frustum plane are not counted (ours culls whole blocks).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rtin
{

// Heights of a (2^k + 1)^2 grid, row-major (x fastest), at (x * dx, y * dy, h).
struct Grid
{
  int size = 0;
  std::vector<float> h;
  double dx = 1.0, dy = 1.0;
};

// "" when size is 2^k + 1 (k >= 1) and the heights match it, else the reason.
inline std::string validateGrid(const Grid& g)
{
  const int tile = g.size - 1;
  if (g.size < 3 || (tile & (tile - 1)) != 0)
  {
    return "RTIN grids are (2^k + 1) x (2^k + 1) samples; got " + std::to_string(g.size);
  }
  if (g.h.size() != static_cast<std::size_t>(g.size) * g.size)
  {
    return "height count does not match the grid size";
  }
  return "";
}

// A camera for the view-dependent count: eye, frustum planes (a, b, c, d), inside where
// a x + b y + c z + d >= 0, and pixels per unit at depth 1.
struct Camera
{
  glm::dvec3 eye{ 0.0 };
  std::array<glm::dvec4, 6> planes{};
  double pixelsPerUnit = 1.0;
};

class Mesher
{
public:
  explicit Mesher(const Grid& grid)
    : g_(grid)
    , errors_(grid.h.size(), 0.0f)
    , radius_(grid.h.size(), 0.0f)
  {
    computeErrors();
  }

  // martini's getMesh(maxError) triangle count.
  std::size_t countForError(double maxError) const
  {
    const int m = g_.size - 1;
    std::size_t n = 0;
    countStatic(0, 0, m, m, m, 0, maxError, n);
    countStatic(m, m, 0, 0, 0, m, maxError, n);
    return n;
  }

  // View-dependent count for tau pixels (see the header comment).
  std::size_t countForView(const Camera& cam, double tau) const
  {
    const int m = g_.size - 1;
    std::size_t n = 0;
    countView(0, 0, m, m, m, 0, cam, tau, n);
    countView(m, m, 0, 0, 0, m, cam, tau, n);
    return n;
  }

  float error(int x, int y) const { return errors_[index(x, y)]; }

private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * g_.size + x; }
  glm::dvec3 point(int x, int y) const { return { x * g_.dx, y * g_.dy, g_.h[index(x, y)] }; }

  // Triangle i of the bisection hierarchy (martini's numbering: 0 and 1 are the two
  // halves of the square, children of triangle t are 2t + 2 and 2t + 3): its hypotenuse
  // a-b; the right-angle corner follows from it.
  void triangleCoords(std::size_t i, int& ax, int& ay, int& bx, int& by) const
  {
    const int tile = g_.size - 1;
    std::size_t id = i + 2;
    int cx = 0, cy = 0;
    ax = ay = bx = by = 0;
    if (id & 1)
    {
      bx = by = cx = tile; // bottom-left triangle
    }
    else
    {
      ax = ay = cy = tile; // top-right triangle
    }
    while ((id >>= 1) > 1)
    {
      const int mx = (ax + bx) >> 1, my = (ay + by) >> 1;
      if (id & 1)
      { // left half
        bx = ax;
        by = ay;
        ax = cx;
        ay = cy;
      }
      else
      { // right half
        ax = bx;
        ay = by;
        bx = cx;
        by = cy;
      }
      cx = mx;
      cy = my;
    }
  }

  // Finest triangles first, so that a vertex's error and sphere are final before a parent
  // reads them (both triangles of a diamond are on the same level).
  void computeErrors()
  {
    const std::size_t tile = static_cast<std::size_t>(g_.size - 1);
    const std::size_t numTriangles = tile * tile * 2 - 2;
    const std::size_t numParents = numTriangles - tile * tile;
    for (std::size_t t = numTriangles; t-- > 0;)
    {
      int ax, ay, bx, by;
      triangleCoords(t, ax, ay, bx, by);
      const int mx = (ax + bx) >> 1, my = (ay + by) >> 1;
      const int cx = mx + my - ay, cy = my + ax - mx;
      const double mean = (static_cast<double>(g_.h[index(ax, ay)]) + g_.h[index(bx, by)]) / 2;
      const std::size_t mid = index(mx, my);
      double e = std::max<double>(errors_[mid], std::abs(mean - g_.h[mid]));
      double r = radius_[mid];
      if (t < numParents)
      {
        const int lx = (ax + cx) >> 1, ly = (ay + cy) >> 1;
        const int rx = (bx + cx) >> 1, ry = (by + cy) >> 1;
        const std::size_t left = index(lx, ly), right = index(rx, ry);
        e = std::max<double>({ e, errors_[left], errors_[right] });
        const glm::dvec3 p = point(mx, my);
        r = std::max({ r, glm::length(point(lx, ly) - p) + radius_[left],
          glm::length(point(rx, ry) - p) + radius_[right] });
      }
      errors_[mid] = static_cast<float>(e);
      // Rounded up so that float storage never shrinks a sphere below its children's.
      radius_[mid] = std::nextafter(static_cast<float>(r), HUGE_VALF);
    }
  }

  void countStatic(int ax, int ay, int bx, int by, int cx, int cy, double maxError,
    std::size_t& n) const
  {
    const int mx = (ax + bx) >> 1, my = (ay + by) >> 1;
    if (std::abs(ax - cx) + std::abs(ay - cy) > 1 && errors_[index(mx, my)] > maxError)
    {
      countStatic(cx, cy, ax, ay, mx, my, maxError, n);
      countStatic(bx, by, cx, cy, mx, my, maxError, n);
    }
    else
    {
      ++n;
    }
  }

  bool active(int x, int y, const Camera& cam, double tau) const
  {
    const std::size_t k = index(x, y);
    const double e = errors_[k];
    if (e <= 0.0)
    {
      return false;
    }
    const glm::dvec3 p = point(x, y);
    const double r = radius_[k];
    for (const glm::dvec4& pl : cam.planes)
    {
      if (pl.x * p.x + pl.y * p.y + pl.z * p.z + pl.w < -r)
      {
        return false; // the sphere, hence every descendant, is outside the view
      }
    }
    const double near = glm::length(cam.eye - p) - r;
    return near <= 0.0 || cam.pixelsPerUnit * e > tau * near;
  }

  bool outside(int ax, int ay, int bx, int by, int cx, int cy, const Camera& cam) const
  {
    const glm::dvec3 a = point(ax, ay), b = point(bx, by), c = point(cx, cy);
    for (const glm::dvec4& pl : cam.planes)
    {
      auto d = [&](const glm::dvec3& q) { return pl.x * q.x + pl.y * q.y + pl.z * q.z + pl.w; };
      if (d(a) < 0 && d(b) < 0 && d(c) < 0)
      {
        return true;
      }
    }
    return false;
  }

  void countView(int ax, int ay, int bx, int by, int cx, int cy, const Camera& cam, double tau,
    std::size_t& n) const
  {
    const int mx = (ax + bx) >> 1, my = (ay + by) >> 1;
    if (std::abs(ax - cx) + std::abs(ay - cy) > 1 && active(mx, my, cam, tau))
    {
      countView(cx, cy, ax, ay, mx, my, cam, tau, n);
      countView(bx, by, cx, cy, mx, my, cam, tau, n);
    }
    else if (!outside(ax, ay, bx, by, cx, cy, cam))
    {
      ++n;
    }
  }

  const Grid& g_;
  std::vector<float> errors_;
  std::vector<float> radius_;
};

} // namespace rtin
