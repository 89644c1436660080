// Certified screen-space error, measured independently of the engine's own error logic.
//
// For random rough terrains and random perspective/orthographic cameras, after
// Engine::update(view, tau) every full-resolution sample P inside the view frustum (our own
// projection, CoreTestUtil.h) must be covered by a drawn triangle, and the drawn surface's
// point Q vertically above/below P (exact lattice point-in-triangle, barycentric z in double
// from the float heights) must project within tau pixels of P.
//
// Float tolerance: the heights are floats and the error table stores floats, so the test
// accepts dist <= tau * (1 + 1e-6) + 1e-6 px. Samples whose Q lies behind the near plane
// (the vertical segment P-Q crosses it) cannot be projected and are skipped (counted).
#include "../Benchmarks/BenchFlight.h"
#include "CoreTestUtil.h"
#include "Engine.h"
#include "SyntheticTerrain.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace gmmtest;

namespace
{
constexpr double kRelTol = 1e-6;

gmm::View randomView(Rng& rng, const gmm::Heightfield& hf, bool parallel)
{
  double xmin = std::min(hf.worldX(0), hf.worldX(hf.nx - 1)), xmax = std::max(hf.worldX(0), hf.worldX(hf.nx - 1));
  double ymin = std::min(hf.worldY(0), hf.worldY(hf.ny - 1)), ymax = std::max(hf.worldY(0), hf.worldY(hf.ny - 1));
  double zmax = -1e30;
  for (float z : hf.z)
    if (std::isfinite(z))
      zmax = std::max(zmax, double(z));
  const double ext = std::max(xmax - xmin, ymax - ymin);
  gmm::View v;
  const int vps[][2] = { { 640, 480 }, { 1280, 720 }, { 300, 900 }, { 1920, 1080 }, { 97, 61 } };
  const int vp = randInt(rng, 0, 4);
  v.viewportWidth = vps[vp][0];
  v.viewportHeight = vps[vp][1];
  const double pi = 3.14159265358979323846;
  const double az = randReal(rng, 0, 2 * pi);
  double pitch;
  if (!parallel)
  {
    double ex = randReal(rng, xmin - 0.2 * (xmax - xmin), xmax + 0.2 * (xmax - xmin));
    double ey = randReal(rng, ymin - 0.2 * (ymax - ymin), ymax + 0.2 * (ymax - ymin));
    // ground under the eye (nearest sample, clamped), then a random altitude above it
    int i = static_cast<int>(std::lround((ex - hf.x0) / hf.dx)), j = static_cast<int>(std::lround((ey - hf.y0) / hf.dy));
    i = std::clamp(i, 0, hf.nx - 1);
    j = std::clamp(j, 0, hf.ny - 1);
    double ground = std::isfinite(hf.height(i, j)) ? hf.height(i, j) : zmax;
    if (randInt(rng, 0, 3) == 0)
      ground = zmax; // above everything
    const double alt = std::exp(randReal(rng, std::log(2.0), std::log(std::max(10.0, 3 * ext))));
    v.eye = { ex, ey, ground + alt };
    pitch = -randReal(rng, 3, 75) * pi / 180;
    v.fovYDegrees = randReal(rng, 20, 90);
    v.nearDistance = randReal(rng, 0.1, 2.0);
    v.farDistance = randInt(rng, 0, 3) == 0 ? ext * randReal(rng, 0.3, 1.0) : 1e6;
  }
  else
  {
    v.parallel = true;
    v.parallelScale = ext * randReal(rng, 0.05, 0.7);
    pitch = -randReal(rng, 20, 89) * pi / 180;
    const double cx = 0.5 * (xmin + xmax) + randReal(rng, -0.3, 0.3) * ext;
    const double cy = 0.5 * (ymin + ymax) + randReal(rng, -0.3, 0.3) * ext;
    const double back = 2 * ext + 1000;
    v.eye = { cx - back * std::cos(pitch) * std::cos(az), cy - back * std::cos(pitch) * std::sin(az),
      zmax + 10 - back * std::sin(pitch) };
    v.nearDistance = 1.0;
    v.farDistance = 1e7;
  }
  v.forward = { std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch) };
  v.up = { 0, 0, 1 };
  return v;
}

ScreenMeasure measure(const gmm::Engine& e, const gmm::View& view, double tau)
{
  return measureScreenError(e.heightfield(), e.indices(), &view, tau, MeasureTransform(), drawnHeights(e).data());
}

void describe(std::ostream& os, const gmm::Heightfield& hf, const gmm::View& v, double tau, int maxQ)
{
  os << hf.nx << "x" << hf.ny << " d(" << hf.dx << "," << hf.dy << ") block " << maxQ << " tau " << tau
     << (v.parallel ? " ortho scale " + std::to_string(v.parallelScale) : " fov " + std::to_string(v.fovYDegrees))
     << " eye(" << v.eye.x << "," << v.eye.y << "," << v.eye.z << ") fwd(" << v.forward.x << ","
     << v.forward.y << "," << v.forward.z << ") vp " << v.viewportWidth << "x" << v.viewportHeight
     << " near " << v.nearDistance << " far " << v.farDistance;
}
} // namespace

TEST(ErrorCertification, ProjectionMatchesEngine)
{
  Rng rng(5);
  for (int k = 0; k < 2000; ++k)
  {
    gmm::Heightfield hf = roughTerrain(20, 20, rng);
    gmm::View v = randomView(rng, hf, k % 3 == 0);
    v.up = { randReal(rng, -0.3, 0.3), randReal(rng, -0.3, 0.3), 1.0 };
    const MyCamera cam = makeCamera(v);
    const glm::dvec3 p = v.eye + glm::dvec3(randReal(rng, -500, 500), randReal(rng, -500, 500), randReal(rng, -500, 500));
    double mx, my, ex, ey;
    const double d = project(cam, p.x, p.y, p.z, mx, my);
    const bool inFront = gmm::projectToPixels(v, p, ex, ey);
    if (d > v.nearDistance * 1.000001)
    {
      EXPECT_TRUE(inFront) << "depth " << d;
      EXPECT_NEAR(ex, mx, 1e-7 * (1 + std::fabs(mx)));
      EXPECT_NEAR(ey, my, 1e-7 * (1 + std::fabs(my)));
    }
    else if (d < v.nearDistance * 0.999999)
    {
      EXPECT_FALSE(inFront) << "depth " << d << " near " << v.nearDistance;
    }
    // pixelsPerUnit against the definition
    EXPECT_NEAR(gmm::pixelsPerUnit(v), cam.scale, 1e-9 * cam.scale);
  }
}

namespace
{
struct Totals
{
  int frames = 0, framesViolating = 0, framesUncovered = 0, framesCoarse = 0;
  double worstRatioToTau = 0.0; // measured / tau
  double sumTightness = 0.0;    // measured / certified bound
  int tightnessFrames = 0;
  double minTightness = 1e30, maxTightness = 0.0;
  std::size_t samplesChecked = 0, skippedNear = 0;
};

void runCampaign(gmm::ErrorMetric metric, bool assertBound, Totals& T, uint64_t seed, int terrains)
{
  Rng rng(seed);
  for (int t = 0; t < terrains; ++t)
  {
    const int nx = randInt(rng, 65, 300), ny = randInt(rng, 65, 200);
    const double sp = randReal(rng, 2.0, 30.0);
    // terrain kinds: 0 synthetic mountains, 1 smooth + steps + spikes, 2 rough noise
    const int kind = t % 3;
    gmm::Heightfield hf;
    if (kind == 0)
    {
      hf = gmm::makeSyntheticTerrain(nx, ny, sp, static_cast<uint32_t>(seed + t), randReal(rng, 100, 1500), 1);
      if (randInt(rng, 0, 2) == 0)
        hf.dx = -hf.dx;
      // plus a few spikes
      for (int s = 0; s < 5; ++s)
        hf.z[randInt(rng, 0, nx * ny - 1)] += static_cast<float>(randReal(rng, -300, 300));
    }
    else
      hf = roughTerrain(nx, ny, rng, randInt(rng, 0, 3) ? sp : -sp,
        randInt(rng, 0, 3) ? sp * randReal(rng, 0.7, 1.3) : -sp, randReal(rng, 50, 1500),
        kind == 1 ? 0.002 : 0.1);
    const int maxQ = 1 << randInt(rng, 3, 6);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    e.setErrorMetric(metric);
    for (int c = 0; c < 6; ++c)
    {
      const gmm::View v = randomView(rng, hf, c == 5);
      for (double tau : { 0.5, 1.0, 2.0, 4.0 })
      {
        const gmm::FrameStats st = e.update(v, tau);
        ASSERT_EQ(e.lastError(), "");
        ASSERT_EQ(st.triangles * 3, e.indices().size());
        const ScreenMeasure m = measure(e, v, tau);
        ++T.frames;
        if (st.triangles < 2 * static_cast<std::size_t>(nx - 1) * (ny - 1) / 2)
          ++T.framesCoarse;
        T.samplesChecked += m.inFrustum;
        T.skippedNear += m.skippedNear;
        T.worstRatioToTau = std::max(T.worstRatioToTau, m.maxDist / tau);
        if (m.violations)
          ++T.framesViolating;
        if (m.uncovered)
          ++T.framesUncovered;
        std::ostringstream what;
        describe(what, hf, v, tau, maxQ);
        // coverage holds for both metrics
        EXPECT_EQ(m.uncovered, 0u) << what.str() << "\n  " << m.first;
        if (assertBound)
        {
          EXPECT_EQ(m.violations, 0u) << what.str() << "\n  measured max " << m.maxDist << " px; "
                                      << m.first;
          EXPECT_LE(st.maxScreenError, tau * (1 + 1e-12)) << what.str();
          // the engine's geometric bound (metres) must hold over every drawn sample
          EXPECT_LE(m.maxVertical, st.maxGeometricError * (1 + kRelTol) + 1e-5) << what.str();
          if (st.maxScreenError > 0 && m.maxDist > 0)
          {
            const double r = m.maxDist / st.maxScreenError;
            T.sumTightness += r;
            ++T.tightnessFrames;
            T.minTightness = std::min(T.minTightness, r);
            T.maxTightness = std::max(T.maxTightness, r);
          }
        }
        if (::testing::Test::HasFailure())
          return;
      }
    }
  }
}
} // namespace

TEST(ErrorCertification, CertifiedMetricHoldsEverywhere)
{
  Totals T;
  runCampaign(gmm::ErrorMetric::Certified, true, T, 2024, 30);
  std::printf("[ certified ] %d frames (%d with < half the full-resolution triangles), %zu in-frustum samples checked (%zu skipped: surface point behind near)\n"
              "[ certified ] worst measured/tau = %.4f; measured/certified-bound: mean %.3f min %.3f max %.3f over %d frames\n",
    T.frames, T.framesCoarse, T.samplesChecked, T.skippedNear, T.worstRatioToTau,
    T.tightnessFrames ? T.sumTightness / T.tightnessFrames : 0.0, T.minTightness, T.maxTightness, T.tightnessFrames);
  RecordProperty("worst_measured_over_tau", std::to_string(T.worstRatioToTau));
  RecordProperty("mean_measured_over_bound",
    std::to_string(T.tightnessFrames ? T.sumTightness / T.tightnessFrames : 0.0));
  EXPECT_GT(T.samplesChecked, 100000u); // the campaign really looked at something
}

// de Boer's centre-distance metric is not a bound: report (not assert) how often and by how
// much it exceeds tau on the same kind of scenes.
// Merged nodes split for a neighbour's strip (SelectNodes.h): when the split node's children
// are drawn whole again, the block that asked must be looked at again, or its strip stays
// beside a corner-only edge over its budget (found on bench_core's 4097^2 flight: a bound of
// 1.013 px at tau 1). That flight, with and without geomorphing's level path: every
// frame's certified bound within tau, and every 500th frame measured.
TEST(ErrorCertification, SplitNodesKeepTheirNeighboursWithinTau)
{
  const gmm::Heightfield hf = gmm::makeSyntheticTerrain(4097, 4097, 30.0, 42, 1500.0, 0);
  for (const bool path : { false, true })
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 32, 0), "");
    e.setMorphRange(path ? gmm::kDefaultMorphRange : 0.0);
    int frames = 0;
    double worst = 0.0;
    for (const gmm::View& v : gmmbench::makeFlight(hf, 2000, 5.0))
    {
      const gmm::FrameStats st = e.update(v, 1.0);
      ASSERT_EQ(e.lastError(), "");
      worst = std::max(worst, st.maxScreenError);
      EXPECT_LE(st.maxScreenError, 1.0 + 1e-12) << "frame " << frames << (path ? " on the level path" : "");
      if (frames % 500 == 0)
      {
        const ScreenMeasure m = measure(e, v, 1.0);
        EXPECT_EQ(m.violations, 0u) << "frame " << frames << ": " << m.first;
      }
      ++frames;
    }
    std::printf("[ split ] %d frames%s, largest certified bound %.4f px\n", frames, path ? " (level path)" : "", worst);
  }
}

TEST(ErrorCertification, CenterDistanceMetricReport)
{
  Totals T;
  runCampaign(gmm::ErrorMetric::CenterDistance, false, T, 2024, 30);
  std::printf("[ center-distance ] %d frames, %d (%.1f%%) exceed tau somewhere; worst measured/tau = %.3f\n",
    T.frames, T.framesViolating, 100.0 * T.framesViolating / std::max(1, T.frames), T.worstRatioToTau);
  RecordProperty("frames_exceeding_tau", T.framesViolating);
  RecordProperty("worst_measured_over_tau", std::to_string(T.worstRatioToTau));
}

// A deliberately wrong check must fail: with the mesh of a coarser tau measured against a
// finer tau, violations appear (shows the measurement can see errors at all).
TEST(ErrorCertification, MeasurementDetectsCoarserMesh)
{
  Rng rng(11);
  gmm::Heightfield hf = roughTerrain(200, 150, rng, 10.0, 10.0, 800.0);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 32, 1), "");
  gmm::View v;
  v.eye = { hf.worldX(100), hf.worldY(-20), 1500.0 };
  v.forward = { 0, 1, -0.6 };
  v.fovYDegrees = 60;
  v.viewportWidth = 1280;
  v.viewportHeight = 720;
  e.update(v, 16.0);
  const ScreenMeasure m = measure(e, v, 1.0);
  EXPECT_GT(m.violations, 0u) << "a tau=16 mesh should violate tau=1 somewhere; max " << m.maxDist;
  EXPECT_GT(m.maxDist, 1.0);
}
