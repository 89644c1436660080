// Full-resolution surface queries (RayCast.h) against brute force and hand-computed cases.
//
// heightAt: on a 3 x 3 grid with known heights, points inside each triangle of the
// (i, j)-(i+1, j+1) split give the plane through its three vertices (worked out by hand);
// holes and points outside give NaN. intersectSegment: for random terrains with holes,
// random spacing signs, datums and height scales, the first hit equals the nearest hit of
// a brute-force loop over every level-0 triangle (independent Moller-Trumbore in this
// file), and a miss is a miss.
#include "CoreTestUtil.h"
#include "RayCast.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gmmtest;

namespace
{

// Nearest hit of the segment over all triangles, written independently of RayCast.cpp.
double bruteForce(const gmm::Heightfield& hf, double s, const double p0[3], const double p1[3])
{
  double best = 2.0;
  auto P = [&](int i, int j, double out[3]) {
    out[0] = hf.x0 + i * hf.dx;
    out[1] = hf.y0 + j * hf.dy;
    out[2] = hf.z0 + s * hf.height(i, j);
    return std::isfinite(hf.height(i, j));
  };
  const double d[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  for (int j = 0; j + 1 < hf.ny; ++j)
    for (int i = 0; i + 1 < hf.nx; ++i)
    {
      // The union jack: quad (i, j) split along (i, j)-(i+1, j+1) where i + j is even, along
      // (i+1, j)-(i, j+1) where it is odd.
      const int tris[2][2][3][2] = { { { { 0, 0 }, { 1, 0 }, { 1, 1 } }, { { 0, 0 }, { 1, 1 }, { 0, 1 } } },
        { { { 0, 0 }, { 1, 0 }, { 0, 1 } }, { { 1, 0 }, { 1, 1 }, { 0, 1 } } } };
      for (const auto& tri : tris[(i + j) % 2])
      {
        double a[3], b[3], c[3];
        if (!P(i + tri[0][0], j + tri[0][1], a) || !P(i + tri[1][0], j + tri[1][1], b) || !P(i + tri[2][0], j + tri[2][1], c))
          continue;
        // Solve p0 + t d = a + u (b - a) + v (c - a) by Cramer's rule.
        const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
        const double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        const double r[3] = { p0[0] - a[0], p0[1] - a[1], p0[2] - a[2] };
        auto det3 = [](const double x[3], const double y[3], const double z[3]) {
          return x[0] * (y[1] * z[2] - y[2] * z[1]) - y[0] * (x[1] * z[2] - x[2] * z[1]) +
            z[0] * (x[1] * y[2] - x[2] * y[1]);
        };
        const double nd[3] = { -d[0], -d[1], -d[2] };
        const double D = det3(e1, e2, nd);
        if (D == 0.0)
          continue;
        const double u = det3(r, e2, nd) / D, v = det3(e1, r, nd) / D, t = det3(e1, e2, r) / D;
        if (u >= -1e-9 && v >= -1e-9 && u + v <= 1 + 1e-9 && t >= 0 && t <= 1)
          best = std::min(best, t);
      }
    }
  return best;
}

} // namespace

TEST(RayCast, HeightAtHandComputed)
{
  // Heights (row j = 0 first): 0 1 2 / 10 20 30 / 5 5 5, spacing 2 x 3, origin (100, 200).
  gmm::Heightfield hf;
  hf.nx = 3;
  hf.ny = 3;
  hf.x0 = 100;
  hf.y0 = 200;
  hf.dx = 2;
  hf.dy = 3;
  hf.z = { 0, 1, 2, 10, 20, 30, 5, 5, 5 };
  // Cell (0, 0), lower triangle (0,0)=0, (1,0)=1, (1,1)=20 at fx 0.5, fy 0.25:
  // 0 + 0.5 * (1 - 0) + 0.25 * (20 - 1) = 5.25.
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 101.0, 200.75), 5.25);
  // Upper triangle (0,0)=0, (1,1)=20, (0,1)=10 at fx 0.25, fy 0.5: 0 + 0.5 * 10 + 0.25 * 10 = 7.5.
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 100.5, 201.5), 7.5);
  // Vertices, with a datum and a scale: 1000 + 3 * 30.
  hf.z0 = 1000;
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 104.0, 203.0, 3.0), 1090.0);
  hf.z0 = 0;
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 99.0, 201.0)));
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 101.0, 206.5)));
  // Cell (1, 0) (1 + 0 odd) is split along (2,0)-(1,1): at fx 0.5, fy 0.5 on that diagonal,
  // (2 + 20) / 2 = 11.
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 103.0, 201.5), 11.0);
  hf.z[4] = std::nanf(""); // (1, 1): all four cells' diagonals end there (1 + 1 even): every
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 101.0, 200.75))); // triangle touching it is a hole
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 100.0, 200.0)));
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 104.0, 200.0))); // (2, 0): cell (1, 0) touches (1, 1) too
  hf.z[4] = 20;
  hf.z[3] = std::nanf(""); // (0, 1): only cell (0, 0)'s upper and cell (0, 1)'s lower triangle
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 101.0, 200.75), 5.25); // cell (0, 0)'s lower one stays
  EXPECT_TRUE(std::isnan(gmm::heightAt(hf, 100.5, 201.5)));
  EXPECT_DOUBLE_EQ(gmm::heightAt(hf, 103.0, 201.5), 11.0);
}

TEST(RayCast, FirstHitEqualsBruteForce)
{
  Rng rng(99);
  int hits = 0, misses = 0;
  for (int k = 0; k < 400; ++k)
  {
    const int nx = randInt(rng, 2, 40), ny = randInt(rng, 2, 40);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, randInt(rng, 0, 1) ? 10.0 : -7.0,
      randInt(rng, 0, 1) ? 10.0 : -13.0, 200.0, 0.3);
    hf.z0 = k % 3 == 0 ? 6.4e6 : 0.0;
    for (int h = randInt(rng, 0, 5); h > 0; --h)
      hf.z[randInt(rng, 0, nx * ny - 1)] = std::nanf("");
    const double s = k % 4 == 0 ? 4.0 : 1.0;
    std::shared_ptr<const gmm::Terrain> t;
    ASSERT_EQ(gmm::buildTerrain(hf, randInt(rng, 0, 1) ? 4 : 16, 1, t), "");
    const double xa = std::min(hf.worldX(0), hf.worldX(nx - 1)), xb = std::max(hf.worldX(0), hf.worldX(nx - 1));
    const double ya = std::min(hf.worldY(0), hf.worldY(ny - 1)), yb = std::max(hf.worldY(0), hf.worldY(ny - 1));
    for (int r = 0; r < 20; ++r)
    {
      double p0[3] = { randReal(rng, xa - 50, xb + 50), randReal(rng, ya - 50, yb + 50), hf.z0 + s * randReal(rng, 300, 900) };
      double p1[3] = { randReal(rng, xa - 50, xb + 50), randReal(rng, ya - 50, yb + 50), hf.z0 + s * randReal(rng, -900, 0) };
      if (r % 5 == 0) // vertical
      {
        p1[0] = p0[0];
        p1[1] = p0[1];
      }
      const double want = bruteForce(hf, s, p0, p1);
      const gmm::SurfaceHit got = gmm::intersectSegment(*t, { p0[0], p0[1], p0[2] }, { p1[0], p1[1], p1[2] }, s);
      if (want > 1.0)
      {
        EXPECT_FALSE(got.hit) << "case " << k << "." << r << ": hit at t " << got.t << ", brute force misses";
        ++misses;
        continue;
      }
      ++hits;
      ASSERT_TRUE(got.hit) << "case " << k << "." << r << ": missed, brute force hits at t " << want;
      const double len = std::hypot(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
      EXPECT_NEAR(got.t * len, want * len, 1e-6) << "case " << k << "." << r;
      // The hit lies on the surface under it.
      EXPECT_NEAR(gmm::heightAt(hf, got.point.x, got.point.y, s), got.point.z, 1e-6 * (1 + std::abs(hf.z0)));
    }
  }
  std::printf("segments: %d hits, %d misses\n", hits, misses);
  EXPECT_GT(hits, 2000);
  EXPECT_GT(misses, 200);
}
