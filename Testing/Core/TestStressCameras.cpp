// Cameras (issue #6): odd but valid views render and keep the certified bound (or see
// nothing, without error); invalid ones are refused by validateView with a clear message
// and leave no stale triangles. DEM: 129 x 111 samples at 30 m (3840 x 3300 m), hills up to
// ~1 km, a plane and a plateau (StressUtil.h).
#include "StressUtil.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

gmm::View looking(glm::dvec3 eye, glm::dvec3 forward, glm::dvec3 up = { 0, 0, 1 })
{
  gmm::View v;
  v.eye = eye;
  v.forward = forward;
  v.up = up;
  v.fovYDegrees = 60.0;
  v.nearDistance = 0.5;
  v.farDistance = 1e6;
  return v;
}

struct Fixture
{
  gmm::Engine e;
  Fixture() { EXPECT_EQ(e.setHeightfield(hillsDem(129, 111), 16, 1), ""); }
};
} // namespace

TEST(StressCameras, OddValidViewsRenderCertified)
{
  Fixture f;
  const double cx = 1920.0, cy = 1650.0;
  const float ground = f.e.heightfield().height(64, 55);
  std::vector<std::pair<std::string, gmm::View>> cases = {
    { "inside the terrain", looking({ cx, cy, ground - 20.0 }, { 0.3, 1, 0.05 }) },
    { "below the terrain, looking up", looking({ cx, 200.0, -5000.0 }, { 0, 0.3, 1 }) },
    { "straight down", looking({ cx, cy, 4000.0 }, { 0, 0, -1 }, { 0, 1, 0 }) },
    { "straight up from below", looking({ cx, cy, -3000.0 }, { 0, 0, 1 }, { 0, 1, 0 }) },
    { "along the horizon", looking({ cx, -500.0, 500.0 }, { 0, 1, 0 }) },
    { "near plane 1e-6", looking({ cx, -300.0, 1500.0 }, { 0, 1, -0.5 }) },
    { "fov 1 degree", looking({ cx, -20000.0, 3000.0 }, { 0, 1, -0.12 }) },
    { "fov 170 degrees", looking({ cx, -100.0, 1200.0 }, { 0, 1, -0.4 }) },
    { "viewport 1 x 1", looking({ cx, -300.0, 1500.0 }, { 0, 1, -0.5 }) },
    { "viewport 8192 x 4320", looking({ cx, -300.0, 1500.0 }, { 0, 1, -0.5 }) },
    { "parallel", looking({ cx, -3000.0, 4000.0 }, { 0, 1, -1 }) },
  };
  cases[5].second.nearDistance = 1e-6;
  cases[6].second.fovYDegrees = 1.0;
  cases[7].second.fovYDegrees = 170.0;
  cases[8].second.viewportWidth = cases[8].second.viewportHeight = 1;
  cases[9].second.viewportWidth = 8192;
  cases[9].second.viewportHeight = 4320;
  cases[10].second.parallel = true;
  cases[10].second.parallelScale = 2000.0;
  for (const auto& [name, v] : cases)
  {
    ASSERT_EQ(gmm::validateView(v), "") << name;
    for (double tau : { 0.5, 2.0 })
    {
      const gmm::FrameStats s = f.e.update(v, tau);
      expectGoodFrame(f.e, &v, tau, name + " tau " + std::to_string(tau));
      EXPECT_GT(s.triangles, 0u) << name;
    }
  }
}

// Views that see no terrain: zero triangles, no error, nothing left from the frame before.
TEST(StressCameras, ViewsThatSeeNothing)
{
  Fixture f;
  const gmm::View good = looking({ 1920, -300, 1500 }, { 0, 1, -0.5 });
  gmm::View shortFar = looking({ 1920, -100000, 1500 }, { 0, 1, 0 });
  shortFar.farDistance = 1000.0; // far plane ends 95 km before the terrain
  std::vector<std::pair<std::string, gmm::View>> cases = {
    { "far plane short of the terrain", shortFar },
    { "straight up from above", looking({ 1920, 1650, 5000 }, { 0, 0, 1 }, { 0, 1, 0 }) },
    { "looking away", looking({ 1920, -300, 1500 }, { 0, -1, 0 }) },
  };
  for (const auto& [name, v] : cases)
  {
    ASSERT_GT(f.e.update(good, 1.0).triangles, 0u);
    const gmm::FrameStats s = f.e.update(v, 1.0);
    EXPECT_EQ(f.e.lastError(), "") << name;
    EXPECT_EQ(s.triangles, 0u) << name;
    EXPECT_EQ(s.visibleBlocks, 0) << name;
    EXPECT_TRUE(f.e.indices().empty()) << name;
  }
}

// 1e9 m away (the DEM spans ~4e-6 rad): the coarsest frame (the root drawn whole); the
// same at an absurd 1e300 m. forward and up of any finite non-zero length give
// the same frame as unit ones.
TEST(StressCameras, FarAwayAndUnnormalisedDirections)
{
  Fixture f;
  gmm::View far = looking({ 1920, -1e9, 1e8 }, { 0, 1e9, -1e8 });
  far.farDistance = 2e9;
  const gmm::FrameStats s = f.e.update(far, 1.0);
  expectGoodFrame(f.e, &far, 1.0, "1e9 m away");
  const gmm::Quadtree& qt = f.e.quadtree();
  EXPECT_EQ(s.visibleBlocks, qt.blockCount());
  EXPECT_EQ(s.triangles, coarsestTriangles(qt));
  // 1e300 m: |eye - corner|^2 overflows a double; the blocks must still be drawn (coarsest),
  // not dropped by a NaN factor.
  gmm::View absurd = looking({ 1920, -1e300, 1000 }, { 0, 1, 0 });
  absurd.farDistance = 1e308;
  const gmm::FrameStats a = f.e.update(absurd, 1.0);
  expectGoodFrame(f.e, &absurd, 1.0, "1e300 m away");
  EXPECT_EQ(a.visibleBlocks, qt.blockCount());
  EXPECT_EQ(a.triangles, coarsestTriangles(qt));
  // near plane 1e-300: factors overflow to +inf next to the eye; those blocks get a zero
  // budget (finest level) and the statistics stay finite.
  gmm::View tinyNear = looking({ 1920, 1650, 1200 }, { 0, 1, -0.3 });
  tinyNear.nearDistance = 1e-300;
  f.e.update(tinyNear, 1.0);
  expectGoodFrame(f.e, &tinyNear, 1.0, "near plane 1e-300");

  const gmm::View unit = looking({ 1920, -300, 1500 }, { 0, 1, -0.5 });
  f.e.update(unit, 1.0);
  const std::vector<int8_t> expected = f.e.levels();
  for (double scale : { 1e-200, 1e-30, 1e30, 1e200 })
  {
    gmm::View v = unit;
    v.forward *= scale;
    v.up *= scale;
    ASSERT_EQ(gmm::validateView(v), "") << scale;
    f.e.update(v, 1.0);
    EXPECT_EQ(f.e.lastError(), "") << scale;
    EXPECT_EQ(f.e.levels(), expected) << "forward and up scaled by " << scale;
  }
}

// Every invalid view is refused with a message naming the problem.
TEST(StressCameras, InvalidViewsGiveClearErrors)
{
  Fixture f;
  const gmm::View good = looking({ 1920, -300, 1500 }, { 0, 1, -0.5 });
  std::vector<std::tuple<std::string, gmm::View, std::string>> cases;
  auto add = [&](const std::string& name, auto edit, const std::string& expect) {
    gmm::View v = good;
    edit(v);
    cases.emplace_back(name, v, expect);
  };
  for (double bad : { kNaN, kInf, -kInf })
  {
    const std::string b = std::to_string(bad);
    for (int k = 0; k < 3; ++k)
    {
      add("eye[" + std::to_string(k) + "] " + b, [&](gmm::View& v) { v.eye[k] = bad; }, "must be finite");
      add("forward[" + std::to_string(k) + "] " + b, [&](gmm::View& v) { v.forward[k] = bad; }, "must be finite");
      add("up[" + std::to_string(k) + "] " + b, [&](gmm::View& v) { v.up[k] = bad; }, "must be finite");
    }
    add("fov " + b, [&](gmm::View& v) { v.fovYDegrees = bad; }, "field of view");
    add("fov " + b + " (parallel view)", [&](gmm::View& v) { v.parallel = true; v.fovYDegrees = bad; }, "field of view");
    add("parallel scale " + b, [&](gmm::View& v) { v.parallel = true; v.parallelScale = bad; }, "parallel scale");
    add("parallel scale " + b + " (perspective view)", [&](gmm::View& v) { v.parallelScale = bad; }, "parallel scale");
    add("near " + b, [&](gmm::View& v) { v.nearDistance = bad; }, "clipping range");
    add("far " + b, [&](gmm::View& v) { v.farDistance = bad; }, "clipping range");
  }
  add("up parallel to forward", [](gmm::View& v) { v.up = v.forward * 7.0; }, "parallel to the view direction");
  add("up opposite to forward", [](gmm::View& v) { v.up = -v.forward; }, "parallel to the view direction");
  add("up zero", [](gmm::View& v) { v.up = { 0, 0, 0 }; }, "view-up is zero");
  add("straight down with default up (+z)", [](gmm::View& v) { v.forward = { 0, 0, -1 }; },
    "parallel to the view direction");
  add("forward zero", [](gmm::View& v) { v.forward = { 0, 0, 0 }; }, "zero length");
  add("fov 0", [](gmm::View& v) { v.fovYDegrees = 0; }, "field of view");
  add("fov 180", [](gmm::View& v) { v.fovYDegrees = 180; }, "field of view");
  add("near 0", [](gmm::View& v) { v.nearDistance = 0; }, "clipping range");
  add("far < near", [](gmm::View& v) { v.farDistance = 0.1; }, "clipping range");
  add("viewport 0 x 720", [](gmm::View& v) { v.viewportWidth = 0; }, "viewport");
  add("viewport 1280 x -1", [](gmm::View& v) { v.viewportHeight = -1; }, "viewport");
  for (const auto& [name, v, expect] : cases)
  {
    ASSERT_GT(f.e.update(good, 1.0).triangles, 0u);
    const gmm::FrameStats s = f.e.update(v, 1.0);
    EXPECT_NE(f.e.lastError().find(expect), std::string::npos) << name << ": \"" << f.e.lastError() << "\"";
    EXPECT_EQ(f.e.lastError(), gmm::validateView(v)) << name;
    EXPECT_EQ(s.triangles, 0u) << name;
    EXPECT_TRUE(f.e.indices().empty()) << name;
  }
}
