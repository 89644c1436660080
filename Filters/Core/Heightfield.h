// Heightfield: a regular grid of heights, the engine's only input data.
//
// Sample (i, j) sits at world (x0 + i*dx, y0 + j*dy, z0 + z[j*nx + i]). Any size
// nx x ny >= 2 x 2 is accepted (no 2^k+1 rule). Nodata is NaN; +-Inf is treated as nodata
// too (see infinitiesToNodata). Negative spacing flips an axis; the engine keeps triangles
// counter-clockwise seen from +z in world coordinates either way.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gmm
{

struct Heightfield
{
  int nx = 0;
  int ny = 0;
  double x0 = 0.0, y0 = 0.0; // world position of sample (0, 0)
  double dx = 1.0, dy = 1.0; // spacing; negative flips the axis
  double z0 = 0.0;           // height datum: sample (i, j) is at z0 + height(i, j)
  std::vector<float> z;      // nx*ny heights, row-major (i fastest); NaN = nodata
  // Heights held elsewhere instead of z (e.g. the input image's array, so that a large
  // DEM is not held twice): when set, z stays empty and `owner` keeps the storage alive.
  const float* external = nullptr;
  std::shared_ptr<const void> owner;

  const float* heights() const { return external ? external : z.data(); }
  std::size_t sampleCount() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx + i; }
  float height(int i, int j) const { return heights()[index(i, j)]; }
  double worldX(double i) const { return x0 + i * dx; }
  double worldY(double j) const { return y0 + j * dy; }
  // True when (i, j) -> (x, y) mirrors orientation, so index winding must be flipped.
  bool mirrored() const { return (dx < 0) != (dy < 0); }
};

// The slope of the heights at sample (i, j) along x (alongX) or y, in height units per unit
// of spacing: the central difference between the two neighbours when both are valid, else
// one-sided with the sample itself, else 0 (border, nodata). The one rule for lit normals:
// the filter's (vtkGeoMipMapConversion::SampleNormal), the mapper's slope texture and its
// per-fragment slopes (GLSL, kSlopeFromHeights in vtkGeoMipMapShaders.cxx, which mirrors it).
inline double sampleSlope(const Heightfield& hf, int i, int j, bool alongX)
{
  const float* z = hf.heights();
  const std::size_t k = hf.index(i, j), step = alongX ? 1 : static_cast<std::size_t>(hf.nx);
  const bool hasA = alongX ? i > 0 : j > 0, hasB = alongX ? i + 1 < hf.nx : j + 1 < hf.ny;
  const double spacing = alongX ? hf.dx : hf.dy;
  const bool okA = hasA && std::isfinite(z[k - step]), okB = hasB && std::isfinite(z[k + step]);
  const bool okC = std::isfinite(z[k]);
  if (okA && okB)
    return (static_cast<double>(z[k + step]) - z[k - step]) / (2.0 * spacing);
  if (okB && okC)
    return (static_cast<double>(z[k + step]) - z[k]) / spacing;
  if (okA && okC)
    return (static_cast<double>(z[k]) - z[k - step]) / spacing;
  return 0.0;
}

// Largest accepted |height| of a finite sample. The difference of two heights is the
// largest geometric error the error table can hold, and it must stay a finite float (+inf
// there means "level not allowed"): 2 * 1e38 < FLT_MAX = 3.4e38. A DEM beyond it is almost
// always an undeclared nodata value such as -FLT_MAX, which the message suggests.
constexpr double kMaxHeight = 1e38;

// Checks a heightfield for use by the engine. Returns an empty string when it is usable,
// otherwise a sentence that says what is wrong (size below 2 x 2, more samples than 2^32 - 1
// indices, height count that does not match the size (owned heights) or no heights at all
// (external), zero or non-finite spacing, origin or datum, an extent that overflows, a
// finite height beyond +-kMaxHeight, the first such sample named). The size checks come
// before anything touches the heights, so an absurd size allocates nothing. The heights
// are scanned by up to `threads` threads (0 = the hardware's).
std::string validateHeightfield(const Heightfield& hf, int threads = 1);

// Replaces +-Inf by NaN (nodata) and returns how many samples were replaced. External
// heights are never written: when they hold an infinity they are first copied into z. The
// search for one is spread over up to `threads` threads (0 = the hardware's).
std::size_t infinitiesToNodata(Heightfield& hf, int threads = 1);

} // namespace gmm
