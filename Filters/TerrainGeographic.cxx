#include "TerrainGeographic.h"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace gmm
{
namespace
{

const float kNaN = std::numeric_limits<float>::quiet_NaN();

constexpr double kMaxGeographicSpan = 40.0; // degrees of longitude (TM within 20 deg of its meridian)
// Exact inverse projection every 4 nodes, bilinear in between: positions within 1e-8 deg
// (1 mm) at 3 arc-seconds (16 nodes gave 2 cm, 9 cm at 6 arc-seconds).
constexpr int kLattice = 4;

const GeographicLib::TransverseMercator& localTM()
{
  static const GeographicLib::TransverseMercator tm(
    GeographicLib::Constants::WGS84_a(), GeographicLib::Constants::WGS84_f(), 1.0);
  return tm;
}

} // namespace

std::string geoGrid(TerrainRaster& r, bool withHeights, std::vector<unsigned char>* inside)
{
  const int sx = r.nx, sy = r.ny;
  const double west = r.lon0, south = r.lat0;
  const double east = west + (sx - 1) * r.lonStep, north = south + (sy - 1) * r.latStep;
  if (!(south >= -90.0 && north <= 90.0))
  {
    return "has a georeference out of range (latitudes beyond the poles)";
  }
  if (!(east - west <= kMaxGeographicSpan))
  {
    return "spans " + std::to_string(east - west) + " degrees of longitude; lon/lat rasters are "
      "mapped to a local transverse Mercator frame, which this reader allows up to " +
      std::to_string(static_cast<int>(kMaxGeographicSpan)) +
      " degrees wide: reproject it first (e.g. gdalwarp -t_srs to a UTM zone)";
  }
  const double cm = r.centralMeridian;
  const auto& tm = localTM();
  double ox, oy;
  tm.Forward(cm, south, west, ox, oy);
  // Footprint: the image of the source's boundary (extremes of a smooth map lie on it).
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  constexpr int kEdge = 64;
  for (int k = 0; k < 4 * (kEdge + 1); ++k)
  {
    const int e = k / (kEdge + 1), t = k % (kEdge + 1);
    const double f = static_cast<double>(t) / kEdge;
    const double lon = e == 0 || e == 2 ? west + f * (east - west) : (e == 1 ? east : west);
    const double lat = e == 1 || e == 3 ? south + f * (north - south) : (e == 0 ? south : north);
    double x, y;
    tm.Forward(cm, lat, lon, x, y);
    x -= ox;
    y -= oy;
    xmin = k ? std::min(xmin, x) : x;
    xmax = k ? std::max(xmax, x) : x;
    ymin = k ? std::min(ymin, y) : y;
    ymax = k ? std::max(ymax, y) : y;
  }
  const double i0 = std::floor(xmin / r.dx + 1e-7), j0 = std::floor(ymin / r.dy + 1e-7);
  const double nxd = std::ceil(xmax / r.dx - 1e-7) - i0 + 1;
  const double nyd = std::ceil(ymax / r.dy - 1e-7) - j0 + 1;
  // A curved footprint's bounding rectangle holds more nodes than the source has samples;
  // refuse shapes where that would run away (a long thin strip far from the meridian).
  const double limit = std::min(static_cast<double>(kMaxRasterSamples),
    2.0 * sx * static_cast<double>(sy) + 16.0 * (sx + sy) + 64.0);
  if (!(nxd >= 1 && nyd >= 1 && nxd * nyd <= limit))
  {
    return "cannot be resampled onto a regular grid in its local transverse Mercator frame (" +
      std::to_string(nxd) + " x " + std::to_string(nyd) + " nodes for " + std::to_string(sx) +
      " x " + std::to_string(sy) + " samples): reproject it first";
  }
  const int nx = static_cast<int>(nxd), ny = static_cast<int>(nyd);
  r.x0 = i0 * r.dx;
  r.y0 = j0 * r.dy;
  r.nx = nx;
  r.ny = ny;
  if (!withHeights)
  {
    return std::string();
  }
  HeightBuffer src;
  src.swap(r.z);
  r.z.assign(static_cast<std::size_t>(nx) * ny, kNaN);
  if (inside)
  {
    inside->assign(r.z.size(), 0);
  }
  // Source index (u, v) at the lattice nodes: every kLattice nodes and the last one.
  auto lattice = [](int n) {
    std::vector<int> at;
    for (int k = 0; k < n - 1; k += kLattice)
      at.push_back(k);
    at.push_back(n - 1);
    return at;
  };
  const std::vector<int> li = lattice(nx), lj = lattice(ny);
  const std::size_t w = li.size();
  std::vector<double> lu(w * lj.size()), lv(w * lj.size());
  for (std::size_t b = 0; b < lj.size(); ++b)
    for (std::size_t a = 0; a < w; ++a)
    {
      double lat, lon;
      tm.Reverse(cm, ox + r.x0 + li[a] * r.dx, oy + r.y0 + lj[b] * r.dy, lat, lon);
      // longitude relative to the meridian: no wrap at +-180 between lattice nodes
      lu[b * w + a] = (GeographicLib::Math::AngDiff(cm, lon) + (cm - west)) / r.lonStep;
      lv[b * w + a] = (lat - south) / r.latStep;
    }
  // Per node column / row: its lattice cell and the fraction across it.
  auto cells = [](const std::vector<int>& at, int n, std::vector<int>& cell, std::vector<double>& frac) {
    cell.resize(n);
    frac.resize(n);
    const int last = static_cast<int>(at.size()) - 1;
    for (int k = 0; k < n; ++k)
    {
      const int c = last == 0 ? 0 : std::min(k / kLattice, last - 1);
      cell[k] = c;
      frac[k] = last == 0 ? 0.0 : static_cast<double>(k - at[c]) / (at[c + 1] - at[c]);
    }
  };
  std::vector<int> ca, cb;
  std::vector<double> fa, fb;
  cells(li, nx, ca, fa);
  cells(lj, ny, cb, fb);
  const double tol = 1e-6;
  for (int j = 0; j < ny; ++j)
  {
    const std::size_t b0 = static_cast<std::size_t>(cb[j]), b1 = std::min(b0 + 1, lj.size() - 1);
    const double fy = fb[j];
    for (int i = 0; i < nx; ++i)
    {
      const std::size_t a0 = static_cast<std::size_t>(ca[i]), a1 = std::min(a0 + 1, w - 1);
      const double fx = fa[i];
      auto at = [&](const std::vector<double>& q) {
        return (1 - fy) * ((1 - fx) * q[b0 * w + a0] + fx * q[b0 * w + a1]) +
          fy * ((1 - fx) * q[b1 * w + a0] + fx * q[b1 * w + a1]);
      };
      const double u = at(lu), v = at(lv);
      if (!(u >= -tol && u <= sx - 1 + tol && v >= -tol && v <= sy - 1 + tol))
      {
        continue; // outside the footprint: nodata
      }
      if (inside)
      {
        (*inside)[static_cast<std::size_t>(j) * nx + i] = 1;
      }
      const double uc = std::min(std::max(u, 0.0), sx - 1.0), vc = std::min(std::max(v, 0.0), sy - 1.0);
      const int ia = std::min(static_cast<int>(uc), std::max(sx - 2, 0));
      const int ja = std::min(static_cast<int>(vc), std::max(sy - 2, 0));
      const int ib = std::min(ia + 1, sx - 1), jb = std::min(ja + 1, sy - 1);
      const double tu = uc - ia, tv = vc - ja;
      const float h00 = src[static_cast<std::size_t>(ja) * sx + ia];
      const float h10 = src[static_cast<std::size_t>(ja) * sx + ib];
      const float h01 = src[static_cast<std::size_t>(jb) * sx + ia];
      const float h11 = src[static_cast<std::size_t>(jb) * sx + ib];
      float h;
      if (std::isfinite(h00) && std::isfinite(h10) && std::isfinite(h01) && std::isfinite(h11))
      {
        h = static_cast<float>(
          (1 - tv) * ((1 - tu) * h00 + tu * h10) + tv * ((1 - tu) * h01 + tu * h11));
      }
      else
      {
        h = tv < 0.5 ? (tu < 0.5 ? h00 : h10) : (tu < 0.5 ? h01 : h11); // nearest sample
      }
      r.z[static_cast<std::size_t>(j) * nx + i] = h;
    }
  }
  return std::string();
}

void geographicToLocal(double centralMeridian, double lon0, double lat0, double lon, double lat,
  double& x, double& y)
{
  double ox, oy;
  localTM().Forward(centralMeridian, lat0, lon0, ox, oy);
  localTM().Forward(centralMeridian, lat, lon, x, y);
  x -= ox;
  y -= oy;
}

void localToGeographic(double centralMeridian, double lon0, double lat0, double x, double y,
  double& lon, double& lat)
{
  double ox, oy;
  localTM().Forward(centralMeridian, lat0, lon0, ox, oy);
  localTM().Reverse(centralMeridian, ox + x, oy + y, lat, lon);
  // in the source's own longitude range (e.g. beyond 180 across the antimeridian)
  lon = centralMeridian + GeographicLib::Math::AngDiff(centralMeridian, lon);
}

} // namespace gmm
