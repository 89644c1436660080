// Large coordinates (issue #6): the same DEM and camera at the origin, at UTM-like
// (500000, 5000000) and at an ECEF-like (6.4e6, 6.4e6, +6.4e6 m heights) offset must give the
// very same levels and triangles, and a slow camera creep at the ECEF offset must change
// levels smoothly.
//
// Exactness: heights are float, whose resolution at 6.4e6 m is 0.5 m, so the test DEM is
// quantised to 0.5 m (hillsDem) and the offset heights are the same DEM exactly; spacing
// (30 m), offsets and camera positions are multiples of 2^-3 m, exact in double at these
// magnitudes. Any difference in levels is then the engine's own arithmetic, not the input.
#include "StressUtil.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{
struct Offset
{
  double x, y, z;
  const char* name;
};
const Offset kOffsets[] = { { 0, 0, 0, "origin" }, { 500000, 5000000, 0, "UTM" },
  { 6.4e6, 6.4e6, 6.4e6, "ECEF" } };

gmm::Heightfield shifted(const gmm::Heightfield& base, const Offset& o)
{
  gmm::Heightfield hf = base;
  hf.x0 += o.x;
  hf.y0 += o.y;
  for (float& z : hf.z)
    z = static_cast<float>(z + o.z);
  return hf;
}

gmm::View moved(gmm::View v, const Offset& o)
{
  v.eye += glm::dvec3(o.x, o.y, o.z);
  return v;
}

std::vector<gmm::View> cameras(const gmm::Heightfield& hf)
{
  std::vector<gmm::View> out;
  gmm::View v = overview(hf, 1500.0);
  out.push_back(v);
  v.eye = { 2000.5, 1500.25, 1200.0 }; // inside the DEM's footprint, looking north-east
  v.forward = { 0.6, 0.8, -0.3 };
  v.fovYDegrees = 75.0;
  out.push_back(v);
  v.eye = { 3840.0, 3840.0, 9000.0 }; // high, straight down (up = +y)
  v.forward = { 0, 0, -1 };
  v.up = { 0, 1, 0 };
  out.push_back(v);
  v = overview(hf, 800.0);
  v.parallel = true;
  v.parallelScale = 2500.0;
  out.push_back(v);
  return out;
}
} // namespace

TEST(StressLargeCoordinates, SameLevelsAtOriginUtmAndEcef)
{
  const gmm::Heightfield base = hillsDem(231, 214);
  gmm::Engine ref;
  ASSERT_EQ(ref.setHeightfield(base, 32, 1), "");
  for (const Offset& o : kOffsets)
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(shifted(base, o), 32, 1), "") << o.name;
    // The error table only sees height differences: identical bit for bit.
    EXPECT_EQ(e.errorTable().ownErrorExact, ref.errorTable().ownErrorExact) << o.name;
    EXPECT_EQ(e.errorTable().stripError, ref.errorTable().stripError) << o.name;
    for (double err : { 0.0, 0.5, 3.0, 40.0 })
    {
      e.updateForError(err);
      ref.updateForError(err);
      EXPECT_EQ(e.levels(), ref.levels()) << o.name << " maxError " << err;
    }
    int cam = 0;
    for (const gmm::View& v : cameras(base))
    {
      for (double tau : { 0.0, 0.5, 2.0, 8.0 })
      {
        const std::string what =
          std::string(o.name) + " camera " + std::to_string(cam) + " tau " + std::to_string(tau);
        const gmm::View mv = moved(v, o);
        const gmm::FrameStats s = e.update(mv, tau);
        const gmm::FrameStats r = ref.update(v, tau);
        ASSERT_EQ(e.lastError(), "") << what;
        EXPECT_GT(r.triangles, 0u) << what;
        EXPECT_EQ(e.levels(), ref.levels()) << what;
        EXPECT_EQ(s.triangles, r.triangles) << what;
        EXPECT_EQ(s.visibleBlocks, r.visibleBlocks) << what;
        EXPECT_EQ(e.indices(), ref.indices()) << what;
        if (tau == 2.0)
          expectGoodFrame(e, &mv, tau, what);
      }
      ++cam;
    }
  }
}

// A slow creep at the ECEF offset: the camera moves 100 frames along its view direction.
// Levels must be those of the same creep at the origin (no precision noise) and must not
// flicker: no block changes back within kFlickerFrames of its last change. A block may jump
// coarser when a finer neighbour releases the stitching constraint that held it down
// (fixStrips) and later refine again as its own budget shrinks, so a monotone level
// sequence is not an invariant (one such return, 14 frames apart, since the tight
// projection factor), nor is "at most one level per frame": both are only reported.
TEST(StressLargeCoordinates, SlowCreepAtEcefIsSmooth)
{
  const gmm::Heightfield base = hillsDem(231, 214);
  const Offset& ecef = kOffsets[2];
  gmm::Engine e, ref;
  ASSERT_EQ(e.setHeightfield(shifted(base, ecef), 32, 1), "");
  ASSERT_EQ(ref.setHeightfield(base, 32, 1), "");
  gmm::View v = overview(base, 5000.0);
  v.forward = { 0.0, 2.0, -1.0 };
  const glm::dvec3 step(0.0, 8.0, -4.0); // 8.9 m a frame, exact in double at 6.4e6
  const int blocks = e.quadtree().blockCount();
  std::vector<int8_t> previous;
  std::vector<int> direction(blocks, 0); // sign of each block's last change
  std::vector<int> changedAt(blocks, -1000);
  constexpr int kFlickerFrames = 4;
  int changes = 0, bigSteps = 0, reversals = 0, flickers = 0;
  for (int f = 0; f < 100; ++f)
  {
    const gmm::View mv = moved(v, ecef);
    e.update(mv, 2.0);
    ref.update(v, 2.0);
    ASSERT_EQ(e.lastError(), "");
    ASSERT_EQ(e.levels(), ref.levels()) << "frame " << f;
    if (f % 33 == 0)
      expectGoodFrame(e, &mv, 2.0, "creep frame " + std::to_string(f));
    const std::vector<int8_t>& now = e.levels();
    for (int b = 0; b < blocks && !previous.empty(); ++b)
      if (previous[b] >= 0 && now[b] >= 0 && previous[b] != now[b])
      {
        const int d = now[b] > previous[b] ? 1 : -1;
        ++changes;
        bigSteps += std::abs(previous[b] - now[b]) > 1;
        reversals += direction[b] == -d;
        flickers += direction[b] == -d && f - changedAt[b] <= kFlickerFrames;
        direction[b] = d;
        changedAt[b] = f;
      }
    previous = now;
    v.eye += step;
  }
  std::printf("[ creep ] %d level changes over %d blocks in 100 frames, %d by more than one level, "
              "%d back to an earlier direction\n",
    changes, blocks, bigSteps, reversals);
  EXPECT_GT(changes, 0) << "test setup: the creep should change some levels";
  EXPECT_EQ(flickers, 0) << "a block went back and forth within " << kFlickerFrames << " frames: flicker";
}

// Random cameras whose ECEF eye is not exactly the origin eye + offset (coordinates that
// double cannot hold exactly at 6.4e6 m, ~1e-9 m rounding): culling and factors are then
// not bit-identical, yet no level or visibility decision may change (it would take a
// budget within ~1e-15 relative of a table entry).
TEST(StressLargeCoordinates, RandomInexactEcefCamerasGiveSameLevels)
{
  const gmm::Heightfield base = hillsDem(231, 214);
  gmm::Engine e, ref;
  ASSERT_EQ(e.setHeightfield(shifted(base, kOffsets[2]), 32, 1), "");
  ASSERT_EQ(ref.setHeightfield(base, 32, 1), "");
  Rng rng(3);
  int drawn = 0;
  for (int k = 0; k < 300; ++k)
  {
    gmm::View v;
    v.eye = { randReal(rng, -2000, 9000), randReal(rng, -2000, 9000), randReal(rng, 100, 6000) };
    const double az = randReal(rng, 0, 6.283);
    v.forward = { std::cos(az), std::sin(az), -randReal(rng, 0.05, 1.5) };
    v.fovYDegrees = randReal(rng, 20, 90);
    v.farDistance = randReal(rng, 2000, 20000);
    const double tau = randReal(rng, 0.3, 4);
    const gmm::FrameStats r = ref.update(v, tau);
    const gmm::FrameStats s = e.update(moved(v, kOffsets[2]), tau);
    ASSERT_EQ(e.levels(), ref.levels()) << "view " << k;
    ASSERT_EQ(s.visibleBlocks, r.visibleBlocks) << "view " << k;
    drawn += r.triangles > 0;
  }
  EXPECT_GT(drawn, 150) << "test setup: most random views should see the terrain";
}
