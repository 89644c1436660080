// Void filling (Filters/TerrainFill.cxx, GDAL's GDALFillNodata over a MEM dataset that
// points at the heights), on synthetic DEMs whose holes and true heights are known:
// - a void is filled exactly when a valid sample lies within the search distance
//   (Euclidean, in samples; brute force here), and stays NaN otherwise;
// - every valid sample keeps its bits; `filled` marks exactly the filled samples;
// - a filled value is a weighted mean of valid samples within the distance (so within
//   their range), and close to the true plane / paraboloid;
// - smoothing leaves no NaN (filled samples whose neighbours are all filled included);
// - `inside` keeps samples outside a footprint NaN; bad options are refused;
// - through gmm::readTerrain: off by default, and a lon/lat raster's resampled grid keeps
//   its corners (outside the source's footprint) NaN while its voids are filled.
#include "GdalTestRaster.h" // writeGdalRaster
#include "TerrainFill.h"
#include "TerrainGeographic.h" // localToGeographic
#include "TerrainIO.h"

#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{

const float kNaN = std::numeric_limits<float>::quiet_NaN();

struct Grid
{
  int nx = 0, ny = 0;
  gmm::HeightBuffer z;
  float& at(int i, int j) { return z[static_cast<std::size_t>(j) * nx + i]; }
};

// nx x ny samples of f(i, j), with disks of NaN (centre i, j, radius) punched in.
Grid holes(int nx, int ny, const std::function<double(int, int)>& f,
  const std::vector<std::array<double, 3>>& disks)
{
  Grid g;
  g.nx = nx;
  g.ny = ny;
  g.z.assign(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      bool hole = false;
      for (const auto& d : disks)
        hole = hole || std::hypot(i - d[0], j - d[1]) <= d[2];
      g.at(i, j) = hole ? kNaN : static_cast<float>(f(i, j));
    }
  return g;
}

std::uint32_t bits(float v)
{
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Range of the valid samples of `before` within `distance` of (i, j); empty (lo > hi) when
// there is none.
void validRange(const Grid& before, int i, int j, double distance, float& lo, float& hi)
{
  lo = std::numeric_limits<float>::infinity();
  hi = -lo;
  const int r = static_cast<int>(std::floor(distance));
  for (int b = std::max(0, j - r); b <= std::min(before.ny - 1, j + r); ++b)
    for (int a = std::max(0, i - r); a <= std::min(before.nx - 1, i + r); ++a)
    {
      const float v = before.z[static_cast<std::size_t>(b) * before.nx + a];
      if (!std::isnan(v) && std::hypot(a - i, b - j) <= distance)
      {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
}

struct FillCheck
{
  std::size_t voids = 0, filled = 0;
  double worstTruth = 0.0; // largest |filled - truth|
};

// Every check of the header comment on one fill of `before` (truth: the unholed heights).
FillCheck checkFill(const Grid& before, const Grid& after, const std::vector<unsigned char>& filled,
  double distance, bool inRange, const std::function<double(int, int)>& truth,
  const std::string& what)
{
  FillCheck c;
  EXPECT_EQ(filled.size(), before.z.size()) << what;
  for (int j = 0; j < before.ny; ++j)
    for (int i = 0; i < before.nx; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * before.nx + i;
      const float was = before.z[k], now = after.z[k];
      if (!std::isnan(was))
      {
        EXPECT_EQ(bits(was), bits(now)) << what << ": valid sample (" << i << ", " << j
                                        << ") changed from " << was << " to " << now;
        EXPECT_EQ(filled[k], 0) << what << ": valid sample (" << i << ", " << j << ") marked";
        continue;
      }
      ++c.voids;
      float lo, hi;
      validRange(before, i, j, distance, lo, hi);
      const bool reachable = lo <= hi;
      EXPECT_EQ(!std::isnan(now), reachable)
        << what << ": void (" << i << ", " << j << ") "
        << (reachable ? "has a valid sample within the distance but stayed NaN"
                      : "has no valid sample within the distance but was filled");
      EXPECT_EQ(filled[k], std::isnan(now) ? 0 : 1)
        << what << ": mask of void (" << i << ", " << j << ")";
      if (!std::isnan(now))
      {
        ++c.filled;
        if (inRange)
        {
          EXPECT_TRUE(now >= lo && now <= hi) << what << ": filled (" << i << ", " << j << ") = "
                                              << now << " outside [" << lo << ", " << hi << "]";
        }
        c.worstTruth = std::max(c.worstTruth, std::abs(now - truth(i, j)));
      }
    }
  return c;
}

const std::function<void(double)> kNoProgress = [](double) {};

double plane(int i, int j)
{
  return 100.0 + 0.5 * i + 0.25 * j;
}
const double kSlope = std::hypot(0.5, 0.25); // the plane's, metres a sample

double paraboloid(int i, int j)
{
  return 2000.0 - 0.02 * ((i - 90.0) * (i - 90.0) + (j - 70.0) * (j - 70.0));
}

// Holes of several sizes, one on the border and one larger than the search distance.
const std::vector<std::array<double, 3>> kDisks = { { 20, 20, 1.5 }, { 60, 40, 3 },
  { 100, 30, 8 }, { 0, 90, 5 }, { 199, 0, 4 }, { 140, 110, 30 } };

} // namespace

TEST(TerrainFill, PlaneWithHolesFilledWithinTheDistanceOnly)
{
  const Grid before = holes(200, 160, plane, kDisks);
  Grid after = before;
  std::vector<unsigned char> filled;
  double last = -1.0;
  ASSERT_EQ(gmm::fillNodata(after.z, after.nx, after.ny, 10.0, 0, nullptr, filled,
              [&](double f) { last = f; }),
    "");
  EXPECT_EQ(last, 1.0) << "progress should end at 1";
  const FillCheck c = checkFill(before, after, filled, 10.0, true, plane, "plane, distance 10");
  // The 30-sample hole keeps its middle: a real test of the distance, not a full fill.
  EXPECT_GT(c.filled, 0u);
  EXPECT_LT(c.filled, c.voids);
  // Inverse distance weighting is not exact on a plane, but a weighted mean of samples
  // within the distance d differs from the plane at the void by at most slope * d.
  std::printf("plane: %zu voids, %zu filled, largest error against the plane %.3f m\n",
    c.voids, c.filled, c.worstTruth);
  EXPECT_LE(c.worstTruth, kSlope * 10.0 + 1e-3);
}

TEST(TerrainFill, SmallHolesOfAParaboloidCloseToTheTruth)
{
  // Holes of radius <= 3 only: every void is filled, close to the smooth surface.
  const std::vector<std::array<double, 3>> small = { { 20, 20, 1.5 }, { 60, 40, 3 },
    { 120, 100, 2 }, { 0, 50, 2 } };
  const Grid before = holes(180, 140, paraboloid, small);
  Grid after = before;
  std::vector<unsigned char> filled;
  ASSERT_EQ(gmm::fillNodata(after.z, after.nx, after.ny, 100.0, 0, nullptr, filled, kNoProgress), "");
  const FillCheck c = checkFill(before, after, filled, 100.0, true, paraboloid, "paraboloid");
  EXPECT_EQ(c.filled, c.voids);
  // Per hole: the error against the truth within half the relief of the hole and its ring
  // of valid samples (radius + 1). Exact reproduction is not expected (inverse distance
  // weighting flattens a slope towards its nearest samples), a fill from the wrong place
  // or with a nodata value is far outside.
  double worstRatio = 0.0;
  for (const auto& d : small)
  {
    double lo = 1e300, hi = -1e300;
    for (int j = 0; j < before.ny; ++j)
      for (int i = 0; i < before.nx; ++i)
        if (std::hypot(i - d[0], j - d[1]) <= d[2] + 1.0)
        {
          lo = std::min(lo, paraboloid(i, j));
          hi = std::max(hi, paraboloid(i, j));
        }
    for (int j = 0; j < before.ny; ++j)
      for (int i = 0; i < before.nx; ++i)
        if (std::hypot(i - d[0], j - d[1]) <= d[2])
        {
          const double err = std::abs(after.at(i, j) - paraboloid(i, j));
          worstRatio = std::max(worstRatio, err / (hi - lo));
          EXPECT_LE(err, 0.5 * (hi - lo)) << "void (" << i << ", " << j << ")";
        }
  }
  std::printf("paraboloid: %zu voids filled, largest error %.3f m, at most %.2f of the local "
              "relief\n",
    c.filled, c.worstTruth, worstRatio);
}

TEST(TerrainFill, SmoothingLeavesNoNaNAndKeepsValidSamples)
{
  // Smoothing passes over filled samples whose 3 x 3 neighbours are all filled too (the
  // middle of the 8-sample hole): no NaN may come out of them, and no valid sample may
  // change.
  const Grid before = holes(200, 160, plane, kDisks);
  Grid after = before;
  std::vector<unsigned char> filled;
  ASSERT_EQ(gmm::fillNodata(after.z, after.nx, after.ny, 10.0, 5, nullptr, filled, kNoProgress), "");
  const FillCheck c = checkFill(before, after, filled, 10.0, false, plane, "plane, smoothed");
  EXPECT_GT(c.filled, 0u);
  // Each pass averages neighbours at most sqrt(2) samples away: the bound above grows by
  // slope * sqrt(2) a pass.
  EXPECT_LE(c.worstTruth, kSlope * (10.0 + 5 * std::sqrt(2.0)) + 1e-3);
}

TEST(TerrainFill, InsideMaskKeepsTheOutsideNaN)
{
  Grid before = holes(64, 48, plane, { { 30, 20, 3 } });
  std::vector<unsigned char> inside(before.z.size(), 1);
  for (int j = 0; j < before.ny; ++j)
    for (int i = 0; i < 6; ++i) // a strip outside the "footprint": nodata, not a void
    {
      before.at(i, j) = kNaN;
      inside[static_cast<std::size_t>(j) * before.nx + i] = 0;
    }
  Grid after = before;
  std::vector<unsigned char> filled;
  ASSERT_EQ(gmm::fillNodata(after.z, after.nx, after.ny, 20.0, 2, &inside, filled, kNoProgress), "");
  for (std::size_t k = 0; k < before.z.size(); ++k)
  {
    if (!inside[k])
    {
      EXPECT_TRUE(std::isnan(after.z[k])) << "outside sample " << k << " was filled";
      EXPECT_EQ(filled[k], 0);
    }
    else
    {
      EXPECT_FALSE(std::isnan(after.z[k])) << "void " << k << " inside was not filled";
      EXPECT_EQ(filled[k], std::isnan(before.z[k]) ? 1 : 0);
    }
  }
}

TEST(TerrainFill, NothingToFillOrNothingToFillFrom)
{
  Grid full = holes(16, 12, plane, {});
  const gmm::HeightBuffer was = full.z;
  std::vector<unsigned char> filled;
  ASSERT_EQ(gmm::fillNodata(full.z, full.nx, full.ny, 5.0, 0, nullptr, filled, kNoProgress), "");
  EXPECT_EQ(std::memcmp(was.data(), full.z.data(), was.size() * sizeof(float)), 0);
  EXPECT_EQ(std::count(filled.begin(), filled.end(), 1), 0);
  gmm::HeightBuffer empty(16 * 12, kNaN);
  ASSERT_EQ(gmm::fillNodata(empty, 16, 12, 5.0, 0, nullptr, filled, kNoProgress), "");
  EXPECT_TRUE(std::all_of(empty.begin(), empty.end(), [](float v) { return std::isnan(v); }));
  EXPECT_EQ(std::count(filled.begin(), filled.end(), 1), 0);
}

TEST(TerrainFill, BadOptionsAreRefused)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double d : { -1.0, 0.0, nan, inf, -inf })
  {
    const std::string problem = gmm::checkFillOptions(d, 0);
    EXPECT_NE(problem.find("FillSearchDistance"), std::string::npos) << d << ": " << problem;
    Grid g = holes(8, 8, plane, { { 4, 4, 1 } });
    std::vector<unsigned char> filled;
    EXPECT_EQ(gmm::fillNodata(g.z, 8, 8, d, 0, nullptr, filled, kNoProgress), problem);
    EXPECT_TRUE(std::isnan(g.at(4, 4))) << "a refused fill must not fill";
  }
  for (int n : { -1, gmm::kMaxFillSmoothingIterations + 1 })
  {
    const std::string problem = gmm::checkFillOptions(10.0, n);
    EXPECT_NE(problem.find("FillSmoothingIterations"), std::string::npos) << n << ": " << problem;
  }
  EXPECT_EQ(gmm::checkFillOptions(1e300, gmm::kMaxFillSmoothingIterations), "");
  // A huge distance is the whole raster, not an overflow.
  Grid g = holes(8, 8, plane, { { 4, 4, 1 } });
  std::vector<unsigned char> filled;
  EXPECT_EQ(gmm::fillNodata(g.z, 8, 8, 1e300, 0, nullptr, filled, kNoProgress), "");
  EXPECT_FALSE(std::isnan(g.at(4, 4)));
}

namespace
{
// A GeoTIFF of the plane over nx x ny samples with a nodata disk; geographic: lon/lat
// from (-122, 47) at `step` degrees, else UTM 10N at 30 m.
std::string writeTiff(const std::string& path, int nx, int ny, bool geographic, double step,
  const std::array<double, 3>& disk)
{
  gmmtest::GdalRaster r;
  r.nx = nx;
  r.ny = ny;
  r.values.resize(static_cast<std::size_t>(nx) * ny);
  for (int row = 0; row < ny; ++row)
    for (int c = 0; c < nx; ++c)
      r.values[static_cast<std::size_t>(row) * nx + c] =
        std::hypot(c - disk[0], row - disk[1]) <= disk[2] ? -9999.0 : plane(c, row);
  r.hasNodata = true;
  r.nodata = -9999.0;
  r.geographic = geographic;
  if (geographic)
  {
    r.west = -122.0;
    r.north = 47.0;
    r.step = step;
  }
  return gmmtest::writeGdalRaster(path, r);
}
} // namespace

TEST(TerrainFill, ThroughTheReadOffByDefaultAndGeographicCornersKept)
{
  char tmpl[] = "/tmp/geomipmap-fill-test-XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  for (bool geographic : { false, true })
  {
    const std::string path = writeTiff(dir + (geographic ? "/ll.tif" : "/utm.tif"), 121, 101,
      geographic, 1.0 / 1200, { 60, 50, 6 });
    gmm::TerrainReadOptions opt;
    EXPECT_FALSE(opt.fillNodata) << "filling must be off by default";
    gmm::TerrainRaster plain, with;
    ASSERT_EQ(gmm::readTerrain(path, opt, plain, kNoProgress), "");
    EXPECT_TRUE(plain.filled.empty());
    opt.fillNodata = true;
    opt.fillSearchDistance = 10.0;
    ASSERT_EQ(gmm::readTerrain(path, opt, with, kNoProgress), "");
    ASSERT_EQ(with.z.size(), plain.z.size());
    ASSERT_EQ(with.filled.size(), plain.z.size());
    std::size_t voids = 0, corners = 0;
    for (int j = 0; j < plain.ny; ++j)
      for (int i = 0; i < plain.nx; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * plain.nx + i;
        if (!std::isnan(plain.z[k]))
        {
          EXPECT_EQ(bits(plain.z[k]), bits(with.z[k])) << path << " sample " << k;
          EXPECT_EQ(with.filled[k], 0);
          continue;
        }
        bool inFootprint = true;
        if (geographic)
        {
          double lon, lat;
          gmm::localToGeographic(plain.centralMeridian, plain.lon0, plain.lat0,
            plain.x0 + i * plain.dx, plain.y0 + j * plain.dy, lon, lat);
          const double u = (lon - plain.lon0) / plain.lonStep, v = (lat - plain.lat0) / plain.latStep;
          inFootprint = u >= -1e-6 && u <= 120 + 1e-6 && v >= -1e-6 && v <= 100 + 1e-6;
        }
        if (inFootprint)
        {
          ++voids;
          EXPECT_FALSE(std::isnan(with.z[k])) << path << ": void " << i << ", " << j;
          EXPECT_EQ(with.filled[k], 1);
        }
        else
        {
          ++corners;
          EXPECT_TRUE(std::isnan(with.z[k])) << path << ": corner node " << i << ", " << j
                                             << " outside the footprint was filled";
          EXPECT_EQ(with.filled[k], 0);
        }
      }
    EXPECT_GT(voids, 90u) << path;
    if (geographic)
    {
      EXPECT_GT(corners, 0u) << "the lon/lat grid should have corners outside the footprint";
    }
    std::remove(path.c_str());
  }
  rmdir(dir.c_str());
}
