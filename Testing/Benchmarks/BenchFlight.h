// bench_core's flight, shared with bench_frame_instructions so that both measure the same
// frames: a straight diagonal line from 30 % of the DEM's diagonal, `step` metres a frame,
// the eye 200 m above the highest ground under it or up to 600 m ahead, looking forward and
// 15 degrees down, fov 60, 1280 x 720, near 1 m, far 10^6 m (everything ahead is in view).
#pragma once

#include "Heightfield.h"
#include "View.h"

#include <algorithm>
#include <cmath>
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

inline std::vector<gmm::View> makeFlight(const gmm::Heightfield& hf, int frames, double step)
{
  std::vector<gmm::View> path;
  const double ext = (hf.nx - 1) * hf.dx;
  const double dir[2] = { std::sqrt(0.5), std::sqrt(0.5) };
  const double x0 = hf.x0 + 0.3 * ext, y0 = hf.y0 + 0.3 * ext;
  const double pitch = -15.0 * 3.14159265358979323846 / 180.0;
  for (int f = 0; f < frames; ++f)
  {
    gmm::View v;
    const double x = x0 + dir[0] * step * f, y = y0 + dir[1] * step * f;
    double ground = 0;
    for (double ahead = 0; ahead <= 600; ahead += 60)
      ground = std::max(ground, groundAt(hf, x + dir[0] * ahead, y + dir[1] * ahead));
    v.eye = { x, y, ground + kFlightAltitude };
    v.forward = { dir[0] * std::cos(pitch), dir[1] * std::cos(pitch), std::sin(pitch) };
    v.up = { 0, 0, 1 };
    v.fovYDegrees = 60;
    v.viewportWidth = 1280;
    v.viewportHeight = 720;
    v.nearDistance = 1.0;
    v.farDistance = 1e6;
    path.push_back(v);
  }
  return path;
}

} // namespace gmmbench
