// bench_core's flight, shared with bench_frame_instructions so that both measure the same
// frames: a straight diagonal line from 30 % of the DEM's diagonal, `step` metres a frame,
// the eye 200 m above the highest ground under it or up to 600 m ahead, looking forward and
// 15 degrees down, fov 60, 1280 x 720, near 1 m, far 10^6 m (everything ahead is in view);
// and bench_core's jumps around the DEM (makeOrbitJumps).
#pragma once

#include "Heightfield.h"
#include "View.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gmmbench
{

constexpr double kFlightAltitude = 200.0; // metres above the ground under/ahead of the camera

// Height of the sample nearest (x, y), clamped to the DEM; 0 over nodata.
inline double groundAt(const gmm::Heightfield& hf, double x, double y)
{
  int i = static_cast<int>(std::lround((x - hf.x0) / hf.dx));
  int j = static_cast<int>(std::lround((y - hf.y0) / hf.dy));
  i = std::max(0, std::min(hf.nx - 1, i));
  j = std::max(0, std::min(hf.ny - 1, j));
  const float z = hf.height(i, j);
  return std::isfinite(z) ? z : 0.0;
}

// The benchmarks' camera at `eye` looking along `forward` (unit): z up, fov 60, 1280 x 720,
// near 1 m, far plane at `far`.
inline gmm::View benchView(const glm::dvec3& eye, const glm::dvec3& forward, double far)
{
  gmm::View v;
  v.eye = eye;
  v.forward = forward;
  v.up = { 0, 0, 1 };
  v.fovYDegrees = 60;
  v.viewportWidth = 1280;
  v.viewportHeight = 720;
  v.nearDistance = 1.0;
  v.farDistance = far;
  return v;
}

inline std::vector<gmm::View> makeFlight(const gmm::Heightfield& hf, int frames, double step)
{
  std::vector<gmm::View> path;
  const double ext = (hf.nx - 1) * hf.dx;
  const double dir[2] = { std::sqrt(0.5), std::sqrt(0.5) };
  const double x0 = hf.x0 + 0.3 * ext, y0 = hf.y0 + 0.3 * ext;
  const double pitch = -15.0 * 3.14159265358979323846 / 180.0;
  for (int f = 0; f < frames; ++f)
  {
    const double x = x0 + dir[0] * step * f, y = y0 + dir[1] * step * f;
    double ground = 0;
    for (double ahead = 0; ahead <= 600; ahead += 60)
      ground = std::max(ground, groundAt(hf, x + dir[0] * ahead, y + dir[1] * ahead));
    path.push_back(benchView({ x, y, ground + kFlightAltitude },
      { dir[0] * std::cos(pitch), dir[1] * std::cos(pitch), std::sin(pitch) }, 1e6));
  }
  return path;
}

// bench_core's jumps: `count` views evenly spaced on an orbit around the DEM's centre
// (radius 35 % of its smaller side), the eye 4 % of that side above its highest sample,
// looking 20 degrees inward of the tangent and 15 degrees down, far plane at 10^7 m. At 12
// views, 30 degrees apart, as geomipmap-bench's orbit at 12 frames.
inline std::vector<gmm::View> makeOrbitJumps(const gmm::Heightfield& hf, int count)
{
  const double ext = std::min((hf.nx - 1) * hf.dx, (hf.ny - 1) * hf.dy);
  const double cx = hf.x0 + 0.5 * (hf.nx - 1) * hf.dx, cy = hf.y0 + 0.5 * (hf.ny - 1) * hf.dy;
  float top = -std::numeric_limits<float>::infinity();
  for (float z : hf.z)
    top = std::isfinite(z) ? std::max(top, z) : top;
  const double pi = 3.14159265358979323846, pitch = -15.0 * pi / 180.0;
  std::vector<gmm::View> views;
  for (int k = 0; k < count; ++k)
  {
    const double a = 2.0 * pi * k / count, heading = a + pi / 2.0 + 20.0 * pi / 180.0;
    views.push_back(benchView({ cx + 0.35 * ext * std::cos(a), cy + 0.35 * ext * std::sin(a), top + 0.04 * ext },
      { std::cos(heading) * std::cos(pitch), std::sin(heading) * std::cos(pitch), std::sin(pitch) }, 1e7));
  }
  return views;
}

} // namespace gmmbench
