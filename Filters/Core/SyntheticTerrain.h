// SyntheticTerrain: deterministic, seeded fractal mountains of any size, for tests and
// benchmarks at sizes no real DEM in ../shared/data reaches (16 M .. 270 M samples).
//
//   gmm::Heightfield hf = gmm::makeSyntheticTerrain(16385, 16385, 30.0, 42);
//
// The terrain is hash-based gradient noise (no RNG state), so a sample depends only on
// (seed, i, j, spacing, size) and the result is bit-identical whatever the thread count.
// Shape: a few octaves of smooth fBm (broad massifs and basins) plus a ridged multifractal
// (Musgrave) for sharp crests and incised valleys, then a power curve that widens valley
// floors. Octaves run from the largest wavelength down to two samples, each rotated by a
// seed-derived angle so no lattice axis shows in the ridges.
//
// Scale: the largest wavelength is min(24 km, the DEM's longest side), so a large DEM at
// 30 m spacing looks like a mountain range spread over a region (realistic slopes at every
// size) and a small one still holds at least one full mountain.
#pragma once

#include "Heightfield.h"

#include <cstdint>

namespace gmm
{

// Returns an nx x ny heightfield with origin (0, 0) and dx = dy = spacing, heights in
// [0, amplitude] metres (most of the range is used). nx, ny >= 1 and a finite positive
// spacing are required; otherwise an empty heightfield (nx = ny = 0) is returned.
// threads = 0 uses the hardware concurrency; the result does not depend on it.
Heightfield makeSyntheticTerrain(int nx, int ny, double spacing, uint32_t seed,
  double amplitude = 1500.0, int threads = 0);

// The same heights written into `out` (nx * ny floats, row-major), e.g. straight into a VTK
// array so that a large DEM is never held twice. Returns false (nothing written) for the
// arguments makeSyntheticTerrain refuses.
bool fillSyntheticTerrain(float* out, int nx, int ny, double spacing, uint32_t seed,
  double amplitude = 1500.0, int threads = 0);

} // namespace gmm
