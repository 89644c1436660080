// Helpers for the geomorphing tests (TestMorph, TestMorphRamp).
#pragma once

#include "Engine.h"
#include "Morph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gmmtest
{

// The highest sample of `hf`, nodata (NaN) aside: the height poppingFlightView flies above.
inline double highestSample(const gmm::Heightfield& hf)
{
  double top = -std::numeric_limits<double>::infinity();
  for (float z : hf.z)
  {
    top = std::isfinite(z) ? std::max(top, static_cast<double>(z)) : top;
  }
  return top;
}

// Frame `frame` of the slow, low flight of Testing/Benchmarks/measure_popping.py over `hf`
// (highest sample `top`): a straight line across the middle from a tenth of the way in,
// `stepBlocks` blocks of `block` quads a frame, 250 m above the highest sample, looking
// ahead and 20 degrees down, fov 50, 1280 x 720 (TestMorphRamp, measure_pop_causes).
inline gmm::View poppingFlightView(const gmm::Heightfield& hf, double top, int block, double stepBlocks, int frame)
{
  const double ext = (hf.nx - 1) * hf.dx, pitch = 20.0 * 3.14159265358979323846 / 180.0;
  gmm::View v;
  v.eye = { 0.1 * ext + frame * stepBlocks * block * hf.dx, 0.5 * (hf.ny - 1) * hf.dy, top + 250.0 };
  v.forward = { std::cos(pitch), 0.0, -std::sin(pitch) };
  v.up = { 0, 0, 1 };
  v.fovYDegrees = 50.0;
  v.viewportWidth = 1280;
  v.viewportHeight = 720;
  v.nearDistance = 1.0;
  v.farDistance = 4.0 * ext;
  return v;
}

// The height the drawn surface gives every sample under `f` (gmm::morphedHeight), for the
// engine's last frame: what measureScreenError and sampleSurface take as drawnZ.
inline std::vector<double> morphedHeights(const gmm::Engine& e, const gmm::MorphFrame& f)
{
  const gmm::Heightfield& hf = e.heightfield();
  std::vector<double> z(hf.sampleCount());
  for (int j = 0; j < hf.ny; ++j)
    for (int i = 0; i < hf.nx; ++i)
      z[hf.index(i, j)] = gmm::morphedHeight(hf, e.quadtree(), e.levels(), f, i, j);
  return z;
}

} // namespace gmmtest
