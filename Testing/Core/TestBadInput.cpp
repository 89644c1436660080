// Bad views and tau: lastError set, no crash, zero triangles; a good frame afterwards works.
#include "CoreTestUtil.h"
#include "Engine.h"

#include <gtest/gtest.h>

using namespace gmmtest;

TEST(BadInput, BadViewsAndTau)
{
  Rng rng(3);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(roughTerrain(65, 65, rng, 10.0, 10.0, 300.0, 0.0), 16, 1), "");
  gmm::View good;
  good.eye = { e.heightfield().worldX(32), e.heightfield().worldY(-30), 800.0 };
  good.forward = { 0, 1, -0.5 };
  good.fovYDegrees = 60;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();

  std::vector<std::pair<std::string, std::pair<gmm::View, double>>> cases;
  auto add = [&](const std::string& name, gmm::View v, double tau) { cases.push_back({ name, { v, tau } }); };
  add("NaN tau", good, nan);
  add("negative tau", good, -1.0);
  add("infinite tau", good, inf);
  add("-infinite tau", good, -inf);
  gmm::View v = good;
  v.forward = { 0, 0, 0 };
  add("zero forward", v, 1.0);
  v = good;
  v.fovYDegrees = 0;
  add("fov 0", v, 1.0);
  v.fovYDegrees = 180;
  add("fov 180", v, 1.0);
  v.fovYDegrees = -30;
  add("fov -30", v, 1.0);
  v = good;
  v.viewportWidth = 0;
  add("viewport width 0", v, 1.0);
  v = good;
  v.viewportHeight = 0;
  add("viewport height 0", v, 1.0);
  v = good;
  v.up = v.forward * 3.0;
  add("up parallel to forward", v, 1.0);
  v = good;
  v.nearDistance = 0;
  add("near 0", v, 1.0);
  v = good;
  v.farDistance = v.nearDistance;
  add("far == near", v, 1.0);
  v = good;
  v.eye.x = nan;
  add("NaN eye", v, 1.0);
  v = good;
  v.forward.z = inf;
  add("Inf forward", v, 1.0);
  v = good;
  v.parallel = true;
  v.parallelScale = 0;
  add("parallel scale 0", v, 1.0);

  for (auto& c : cases)
  {
    // a good frame first so that stale triangles would be visible
    e.update(good, 1.0);
    ASSERT_EQ(e.lastError(), "");
    ASSERT_GT(e.indices().size(), 0u);
    // every case is bad: a bad view, or a tau that is not finite and >= 0
    EXPECT_FALSE(gmm::validateView(c.second.first).empty() && std::isfinite(c.second.second) && c.second.second >= 0)
      << c.first;
    const gmm::FrameStats& st = e.update(c.second.first, c.second.second);
    // Refused (robustness.md: tau negative, NaN or +-Inf refuses the frame), infinite tau
    // included: it would otherwise certify nothing while claiming a bound.
    EXPECT_FALSE(e.lastError().empty()) << c.first;
    EXPECT_EQ(st.triangles, 0u) << c.first;
    EXPECT_TRUE(e.indices().empty()) << c.first << ": stale indices left after a refused frame";
    EXPECT_FALSE(st.reused) << c.first;
  }
  // the view-independent mode refuses the same values of its error bound (metres)
  for (double bad : { nan, -1.0, inf, -inf })
  {
    e.update(good, 1.0);
    ASSERT_GT(e.indices().size(), 0u);
    const gmm::FrameStats& st = e.updateForError(bad);
    EXPECT_FALSE(e.lastError().empty()) << "updateForError(" << bad << ")";
    EXPECT_EQ(st.triangles, 0u) << "updateForError(" << bad << ")";
    EXPECT_TRUE(e.indices().empty()) << "updateForError(" << bad << ")";
  }
  // recovers
  const gmm::FrameStats& st = e.update(good, 1.0);
  EXPECT_EQ(e.lastError(), "");
  EXPECT_GT(st.triangles, 0u);
}

TEST(BadInput, ValidateViewDirect)
{
  gmm::View v;
  EXPECT_EQ(gmm::validateView(v), "");
  v.fovYDegrees = 179.9;
  EXPECT_EQ(gmm::validateView(v), "");
  v.fovYDegrees = 180.0;
  EXPECT_NE(gmm::validateView(v), "");
  v = gmm::View();
  v.viewportWidth = 1;
  v.viewportHeight = 1;
  EXPECT_EQ(gmm::validateView(v), "");
  v.viewportHeight = -5;
  EXPECT_NE(gmm::validateView(v), "");
}
