// Helpers for the geomorphing tests (TestMorph, TestMorphRamp).
#pragma once

#include "Engine.h"
#include "Morph.h"

#include <vector>

namespace gmmtest
{

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
