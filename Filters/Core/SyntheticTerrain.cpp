#include "SyntheticTerrain.h"

#include "HugePages.h"
#include "Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gmm
{
namespace
{

constexpr double kPi = 3.14159265358979323846;

// 32-bit integer hash (lowbias32 by Chris Wellons): cheap, well mixed, stateless.
inline uint32_t mix32(uint32_t x)
{
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline uint32_t hash2(int32_t ix, int32_t iy, uint32_t seed)
{
  return mix32(static_cast<uint32_t>(ix) * 0x9E3779B1U ^ mix32(static_cast<uint32_t>(iy) + seed));
}

// 16 unit gradients: more directions than Perlin's 8 keep ridges from lining up.
struct GradientTable
{
  double gx[16], gy[16];
  GradientTable()
  {
    for (int k = 0; k < 16; ++k)
    {
      gx[k] = std::cos(2.0 * kPi * (k + 0.5) / 16.0);
      gy[k] = std::sin(2.0 * kPi * (k + 0.5) / 16.0);
    }
  }
};
const GradientTable kGrad;

inline double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// One octave: lattice coordinates (u, v) = R(angle) * (x, y) * freq + offset.
struct Octave
{
  double c = 1.0, s = 0.0; // rotation
  double freq = 1.0;       // lattice cells per metre
  double offU = 0.0, offV = 0.0;
  uint32_t seed = 0;
};

// Gradient noise of one row of samples (x = i * spacing, fixed y). Along a row the lattice
// coordinates move linearly, so the four corner gradients are looked up only when the cell
// changes: per sample only the interpolation remains. Output in about [-0.7, 0.7].
void noiseRow(const Octave& o, double y, double spacing, int nx, double* out)
{
  const double du = spacing * o.c * o.freq, dv = spacing * o.s * o.freq;
  const double u0 = -y * o.s * o.freq + o.offU, v0 = y * o.c * o.freq + o.offV;
  int64_t cu = std::numeric_limits<int64_t>::min(), cv = cu;
  double g00x = 0, g00y = 0, g10x = 0, g10y = 0, g01x = 0, g01y = 0, g11x = 0, g11y = 0;
  for (int i = 0; i < nx; ++i)
  {
    const double u = u0 + i * du, v = v0 + i * dv;
    const double fu = std::floor(u), fv = std::floor(v);
    const int64_t iu = static_cast<int64_t>(fu), iv = static_cast<int64_t>(fv);
    if (iu != cu || iv != cv)
    {
      cu = iu;
      cv = iv;
      const auto a = static_cast<int32_t>(iu), b = static_cast<int32_t>(iv);
      uint32_t h = hash2(a, b, o.seed) & 15;
      g00x = kGrad.gx[h], g00y = kGrad.gy[h];
      h = hash2(a + 1, b, o.seed) & 15;
      g10x = kGrad.gx[h], g10y = kGrad.gy[h];
      h = hash2(a, b + 1, o.seed) & 15;
      g01x = kGrad.gx[h], g01y = kGrad.gy[h];
      h = hash2(a + 1, b + 1, o.seed) & 15;
      g11x = kGrad.gx[h], g11y = kGrad.gy[h];
    }
    const double tx = u - fu, ty = v - fv;
    const double n00 = g00x * tx + g00y * ty;
    const double n10 = g10x * (tx - 1.0) + g10y * ty;
    const double n01 = g01x * tx + g01y * (ty - 1.0);
    const double n11 = g11x * (tx - 1.0) + g11y * (ty - 1.0);
    const double sx = fade(tx), sy = fade(ty);
    const double a = n00 + sx * (n10 - n00);
    const double b = n01 + sx * (n11 - n01);
    out[i] = a + sy * (b - a);
  }
}

Octave makeOctave(uint32_t seed, int index, double wavelength)
{
  Octave o;
  o.seed = mix32(seed * 0x85EBCA6BU + static_cast<uint32_t>(index) * 0xC2B2AE35U + 0x27D4EB2FU);
  const double angle = 2.0 * kPi * (mix32(o.seed ^ 0xA5A5A5A5U) / 4294967296.0);
  o.c = std::cos(angle);
  o.s = std::sin(angle);
  o.freq = 1.0 / wavelength;
  // Offsets move sample (0, 0) off the lattice points, where gradient noise is always 0.
  o.offU = 1000.0 * (mix32(o.seed ^ 0x1234567U) / 4294967296.0);
  o.offV = 1000.0 * (mix32(o.seed ^ 0x7654321U) / 4294967296.0);
  return o;
}

} // namespace

Heightfield makeSyntheticTerrain(
  int nx, int ny, double spacing, uint32_t seed, double amplitude, int threads)
{
  Heightfield hf;
  if (nx < 1 || ny < 1 || !std::isfinite(spacing) || spacing <= 0.0 || !std::isfinite(amplitude))
  {
    return hf;
  }
  hf.nx = nx;
  hf.ny = ny;
  hf.dx = hf.dy = spacing;
  resizeOnHugePages(hf.z, static_cast<std::size_t>(nx) * ny);
  fillSyntheticTerrain(hf.z.data(), nx, ny, spacing, seed, amplitude, threads);
  return hf;
}

bool fillSyntheticTerrain(
  float* out, int nx, int ny, double spacing, uint32_t seed, double amplitude, int threads)
{
  if (nx < 1 || ny < 1 || !std::isfinite(spacing) || spacing <= 0.0 || !std::isfinite(amplitude))
  {
    return false;
  }

  // Largest wavelength in metres (see header), then octaves down to two samples.
  const double extent = std::max(std::max(nx, ny) - 1, 1) * spacing;
  const double w0 = std::min(24000.0, extent);
  std::vector<Octave> base, ridged;
  for (int k = 0; k < 3; ++k)
  {
    base.push_back(makeOctave(seed, k, 2.0 * w0 / std::pow(2.0, k)));
  }
  double w = w0 * 0.5;
  for (int k = 0; k < 24 && w >= 2.0 * spacing; ++k, w *= 0.5)
  {
    ridged.push_back(makeOctave(seed, 100 + k, w));
  }

  // Rows in chunks over the cores (Parallel.h); each row depends on nothing but its index.
  constexpr std::size_t kRowsPerChunk = 8;
  std::vector<float> rowMin(ny), rowMax(ny);
  parallelChunks(static_cast<std::size_t>(ny), kRowsPerChunk, threads, [&](std::size_t first, std::size_t last) {
    std::vector<double> noise(nx), baseSum(nx), ridgeSum(nx), weight(nx);
    for (int j = static_cast<int>(first); j < static_cast<int>(last); ++j)
    {
      const double y = j * spacing;
      std::fill(baseSum.begin(), baseSum.end(), 0.0);
      std::fill(ridgeSum.begin(), ridgeSum.end(), 0.0);
      std::fill(weight.begin(), weight.end(), 1.0);
      double gain = 1.0;
      for (const Octave& o : base)
      {
        noiseRow(o, y, spacing, nx, noise.data());
        for (int i = 0; i < nx; ++i)
        {
          baseSum[i] += gain * noise[i];
        }
        gain *= 0.5;
      }
      // Ridged multifractal (Musgrave): crests where the noise crosses zero; each octave is
      // weighted by the previous one so detail gathers on ridges and valley floors stay smooth.
      gain = 1.0;
      for (const Octave& o : ridged)
      {
        noiseRow(o, y, spacing, nx, noise.data());
        for (int i = 0; i < nx; ++i)
        {
          double sig = 1.0 - std::abs(noise[i]); // > 0: |noise| < 0.75, no kinks but the crest
          sig = sig * sig * weight[i];
          ridgeSum[i] += gain * sig;
          weight[i] = std::min(1.0, 2.0 * sig);
        }
        gain *= 0.42; // H ~ 1.25: smoother than Brownian, like eroded ranges
      }
      // Raw height, unscaled: ridges lifted where the broad massif is high.
      float* row = out + static_cast<std::size_t>(j) * nx;
      float lo = std::numeric_limits<float>::max(), hi = -lo;
      for (int i = 0; i < nx; ++i)
      {
        const double massif = 0.5 + 0.7 * baseSum[i]; // about [0, 1]
        const float h = static_cast<float>(ridgeSum[i] * (0.3 + std::max(0.0, massif)) + 0.8 * massif);
        row[i] = h;
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
      rowMin[j] = lo;
      rowMax[j] = hi;
    }
  });

  // Normalise to [0, 1] over the whole DEM (deterministic: min/max do not depend on order),
  // then a power curve widens valley floors and sharpens summits.
  const float lo = *std::min_element(rowMin.begin(), rowMin.end());
  const float hi = *std::max_element(rowMax.begin(), rowMax.end());
  const double scale = hi > lo ? 1.0 / (static_cast<double>(hi) - lo) : 0.0;
  parallelChunks(static_cast<std::size_t>(ny), kRowsPerChunk, threads, [&](std::size_t first, std::size_t last) {
    for (int j = static_cast<int>(first); j < static_cast<int>(last); ++j)
    {
      float* row = out + static_cast<std::size_t>(j) * nx;
      for (int i = 0; i < nx; ++i)
      {
        const double t = (row[i] - lo) * scale;
        row[i] = static_cast<float>(amplitude * t * std::sqrt(t)); // t^1.5, pow is 5x slower
      }
    }
  });
  return true;
}

} // namespace gmm
