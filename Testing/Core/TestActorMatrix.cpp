// Culling and the certified bound under any affine actor matrix, a height scale and a datum.
//
// The engine draws the heightfield through toWorld = model * (x, y, z0 + s * h). For random
// terrains, random invertible affine models (rotation, non-uniform scale from 0.3 to 5,
// shear), height scales 0.5 .. 10 and datums 0 / 1000 / 6.4e6, and random cameras looking
// at the transformed terrain, every sample inside the world frustum must be covered, and
// the drawn point above/below it must project within tau of it. Both are measured sample by
// sample with the test's own transform and projection (CoreTestUtil.h), not the engine's.
// The regression it guards: a non-uniform scale used to be reduced to the cube root of the
// determinant, which culled visible blocks and let the error reach several times tau.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "SelectLevels.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace gmmtest;

namespace
{

glm::dmat4 randomAffine(Rng& rng)
{
  glm::dmat4 m(1.0);
  m = glm::translate(m, glm::dvec3(randReal(rng, -5e3, 5e3), randReal(rng, -5e3, 5e3), randReal(rng, -500, 500)));
  m = glm::rotate(m, randReal(rng, 0, 6.283), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, randReal(rng, -0.3, 0.3), glm::dvec3(1, 0, 0));
  glm::dmat4 shear(1.0);
  shear[2][0] = randReal(rng, -0.5, 0.5); // x += k z
  shear[1][0] = randReal(rng, -0.3, 0.3); // x += k y
  m = m * shear;
  return glm::scale(m, glm::dvec3(std::exp(randReal(rng, std::log(0.3), std::log(5.0))),
                         std::exp(randReal(rng, std::log(0.3), std::log(5.0))),
                         std::exp(randReal(rng, std::log(0.3), std::log(5.0)))));
}

MeasureTransform measureTransform(const glm::dmat4& m, double z0, double s)
{
  MeasureTransform t;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      t.m[r][c] = m[c][r]; // glm is column-major
  t.z0 = z0;
  t.heightScale = s;
  return t;
}

// A camera looking at a random sample of the terrain as the world sees it.
gmm::View worldView(Rng& rng, const gmm::Heightfield& hf, const MeasureTransform& t, bool parallel)
{
  int i = randInt(rng, 0, hf.nx - 1), j = randInt(rng, 0, hf.ny - 1);
  const double h = std::isfinite(hf.height(i, j)) ? hf.height(i, j) : 0.0;
  double target[3], corner0[3], corner1[3];
  t.apply(hf.worldX(i), hf.worldY(j), h, target);
  t.apply(hf.worldX(0), hf.worldY(0), 0, corner0);
  t.apply(hf.worldX(hf.nx - 1), hf.worldY(hf.ny - 1), 0, corner1);
  const double ext = std::hypot(corner1[0] - corner0[0], corner1[1] - corner0[1]) + 1.0;
  const double dist = ext * std::exp(randReal(rng, std::log(0.2), std::log(3.0)));
  const double az = randReal(rng, 0, 6.283), el = randReal(rng, 0.05, 1.4);
  gmm::View v;
  const glm::dvec3 tgt(target[0], target[1], target[2]);
  const glm::dvec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  v.eye = tgt + dist * dir;
  v.forward = -dir;
  v.up = { 0, 0, 1 };
  v.fovYDegrees = randReal(rng, 20, 80);
  v.nearDistance = 0.01 * dist;
  v.farDistance = 50 * (dist + ext);
  v.viewportWidth = 640;
  v.viewportHeight = 400;
  if (parallel)
  {
    v.parallel = true;
    v.parallelScale = 0.3 * dist;
  }
  return v;
}

} // namespace

TEST(ActorMatrix, CoveredAndCertifiedUnderAffineModels)
{
  Rng rng(2024);
  const double datums[] = { 0.0, 1000.0, 6.4e6 };
  const double scales[] = { 0.5, 1.0, 3.0, 10.0 };
  int frames = 0, coarse = 0;
  double worst = 0.0;
  for (int k = 0; k < 240; ++k)
  {
    gmm::Heightfield hf = roughTerrain(randInt(rng, 20, 70), randInt(rng, 20, 70), rng, 10.0, 10.0, 300.0, 0.002);
    hf.z0 = datums[k % 3];
    const double s = scales[(k / 3) % 4];
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, randInt(rng, 0, 1) ? 8 : 16), "");
    ASSERT_EQ(e.setHeightScale(s), "");
    const glm::dmat4 model = randomAffine(rng);
    const MeasureTransform t = measureTransform(model, hf.z0, s);
    gmm::View v = worldView(rng, hf, t, k % 5 == 0);
    v.model = model;
    const double tau = k % 2 ? 1.0 : 3.0;
    const gmm::FrameStats& st = e.update(v, tau);
    ASSERT_EQ(e.lastError(), "");
    const ScreenMeasure m = measureScreenError(e.heightfield(), e.indices(), &v, tau, t, drawnHeights(e).data());
    ++frames;
    coarse += st.visibleBlocks > 0 && m.maxVertical > 0 ? 1 : 0;
    if (tau > 0)
      worst = std::max(worst, m.maxDist / tau);
    EXPECT_EQ(m.uncovered, 0u) << "frame " << k << ": " << m.first;
    EXPECT_EQ(m.violations, 0u) << "frame " << k << ": " << m.first;
  }
  std::printf("affine models: %d frames, %d with simplified blocks, worst measured/tau %.3f\n", frames,
    coarse, worst);
  EXPECT_GT(coarse, frames / 4); // the check must have had coarse levels to measure
}

TEST(ActorMatrix, HeightScaleScalesTheBound)
{
  // The same terrain at scale 1 and 4: the geometric bound of the view-independent mode is
  // in data units, so a 4x exaggeration needs 4x the error budget for the same levels.
  Rng rng(7);
  gmm::Heightfield hf = roughTerrain(65, 65, rng, 10.0, 10.0, 300.0, 0.002);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 16), "");
  const auto a = e.updateForError(5.0);
  const std::vector<int8_t> levels1 = e.levels();
  ASSERT_EQ(e.setHeightScale(4.0), "");
  const auto b = e.updateForError(20.0);
  EXPECT_EQ(e.levels(), levels1);
  EXPECT_NEAR(b.maxGeometricError, 4.0 * a.maxGeometricError, 1e-9 * (1 + b.maxGeometricError));
  const ScreenMeasure m = measureScreenError(e.heightfield(), e.indices(), nullptr, 0.0,
    measureTransform(glm::dmat4(1.0), 0.0, 4.0), drawnHeights(e).data());
  EXPECT_LE(m.maxVertical, 20.0 * (1 + 1e-6));
  EXPECT_GT(m.maxVertical, 0.0);
}

// The projection factor of a box (SelectLevels.h, BoxProjector) against its definition,
// written out plainly: the 8 corners through the full matrix (glm's matrix-vector product),
// the smallest depth along the unit view direction, and the pixels per unit at depth 1
// from the field of view; beyond the near plane the largest ratio of a corner's offset
// across the vertical to its depth, else the largest eye distance over the near depth. Random affine models, datums, height
// scales, boxes (flat ones included) and cameras; the engine computes the corners term by
// term, so the two agree to rounding, not bit for bit.
TEST(ActorMatrix, ProjectionFactorIsItsCornerFormula)
{
  Rng rng(2718);
  int compared = 0, diagonalCompared = 0, tightCompared = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    // Every other trial a diagonal frame (translation and per-axis scale, mirrored on some
    // axes), as a DEM's own frame usually is: BoxProjector takes its extremes axis by axis.
    const bool diagonalFrame = trial % 2 == 0;
    glm::dmat4 model = randomAffine(rng);
    if (diagonalFrame)
    {
      model = glm::translate(glm::dmat4(1.0), glm::dvec3(randReal(rng, -5e3, 5e3), randReal(rng, -5e3, 5e3), randReal(rng, -500, 500)));
      model = glm::scale(model, glm::dvec3(randReal(rng, 0.3, 5.0) * (trial % 8 == 0 ? -1 : 1),
                                  randReal(rng, 0.3, 5.0) * (trial % 12 == 2 ? -1 : 1), randReal(rng, 0.3, 5.0)));
    }
    const double z0 = trial % 3 == 0 ? 6.4e6 : (trial % 3 == 1 ? 1000.0 : 0.0);
    const double scale = randReal(rng, 0.5, 10.0);
    gmm::View v;
    v.model = model;
    v.eye = glm::dvec3(randReal(rng, -2e4, 2e4), randReal(rng, -2e4, 2e4), z0 + randReal(rng, 100, 5e3));
    v.forward = glm::dvec3(randReal(rng, -1, 1), randReal(rng, -1, 1), randReal(rng, -1, -0.05));
    v.fovYDegrees = randReal(rng, 20, 80);
    v.nearDistance = randReal(rng, 0.1, 50.0);
    v.viewportHeight = 400 + trial;
    const glm::dmat4 toWorld = gmm::heightfieldToWorld(v, z0, scale);
    const gmm::BoxProjector projector(v, toWorld, gmm::ErrorMetric::Certified);
    const glm::dvec3 fwd = glm::normalize(v.forward);
    const double ppu = 0.5 * v.viewportHeight / std::tan(v.fovYDegrees * 3.14159265358979323846 / 360.0);
    const double unitError = glm::length(glm::dvec3(toWorld * glm::dvec4(0, 0, 1, 0)));
    const glm::dvec3 vertical = glm::dvec3(toWorld * glm::dvec4(0, 0, 1, 0)) / unitError;
    for (int k = 0; k < 20; ++k)
    {
      gmm::Box box;
      box.lo = glm::dvec3(randReal(rng, -3e4, 3e4), randReal(rng, -3e4, 3e4), randReal(rng, -500, 3000));
      box.hi = box.lo + glm::dvec3(std::exp(randReal(rng, 0, 9)), std::exp(randReal(rng, 0, 9)),
                          k % 4 == 0 ? 0.0 : std::exp(randReal(rng, -2, 7)));
      double maxDist = 0.0, minDepth = INFINITY, maxRatio = 0.0;
      for (int c = 0; c < 8; ++c)
      {
        const glm::dvec3 p(toWorld * glm::dvec4(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                                       c & 4 ? box.hi.z : box.lo.z, 1.0));
        maxDist = std::max(maxDist, glm::length(p - v.eye));
        minDepth = std::min(minDepth, glm::dot(p - v.eye, fwd));
        maxRatio = std::max(maxRatio, glm::length(glm::cross(vertical, p - v.eye)) / glm::dot(p - v.eye, fwd));
      }
      const double depth = std::max(minDepth, v.nearDistance);
      const bool tight = minDepth >= v.nearDistance;
      tightCompared += tight ? 1 : 0;
      const double expected = tight ? ppu * unitError * maxRatio / minDepth : ppu * unitError * maxDist / (depth * depth);
      // Relative to the terms' magnitude: a datum of 6.4e6 leaves ~1e-9 m of rounding in
      // each corner, which a depth of a metre magnifies.
      const double slack = 1e-9 * (1.0 + std::abs(z0) * scale / depth);
      EXPECT_NEAR(projector.factor(box), expected, slack * expected) << "trial " << trial << " box " << k;
      // The axis-by-axis extremes of a diagonal frame (SSE2 lanes where there are) give the
      // corner loop's double, bit for bit.
      EXPECT_EQ(projector.factor(box), projector.cornerFactor(box)) << "trial " << trial << " box " << k;
      diagonalCompared += diagonalFrame ? 1 : 0;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 8000);
  EXPECT_EQ(diagonalCompared, 4000);
  EXPECT_GT(tightCompared, 2000); // both branches compared
  EXPECT_LT(tightCompared, 7000);
}

// The factor is a bound: a vertical segment anywhere in the box, projected with the test's
// own camera (CoreTestUtil.h, from View.h's definition), spans at most factor x its length
// in pixels. Random frames (diagonal and affine), cameras (low and oblique, steep, looking
// down) and boxes; segments between random heights at random (x, y), the box's corners
// and the point straight below the eye included. Also reports how close the bound comes.
TEST(ActorMatrix, ProjectionFactorBoundsTheProjectedSegments)
{
  Rng rng(1618);
  int segments = 0;
  double closest = 0.0;
  for (int trial = 0; trial < 300; ++trial)
  {
    glm::dmat4 model = randomAffine(rng);
    if (trial % 2 == 0)
    {
      model = glm::translate(glm::dmat4(1.0), glm::dvec3(randReal(rng, -500, 500), randReal(rng, -500, 500), randReal(rng, -50, 50)));
      model = glm::scale(model, glm::dvec3(randReal(rng, 0.3, 5.0) * (trial % 8 == 0 ? -1 : 1),
                                  randReal(rng, 0.3, 5.0), randReal(rng, 0.3, 5.0) * (trial % 6 == 2 ? -1 : 1)));
    }
    const double scale = randReal(rng, 0.5, 4.0);
    gmm::View v;
    v.model = model;
    v.eye = glm::dvec3(randReal(rng, -300, 300), randReal(rng, -300, 300), randReal(rng, 5, 400));
    const double down = trial % 3 == 0 ? randReal(rng, -8, -1) : randReal(rng, -0.6, -0.02);
    v.forward = glm::dvec3(randReal(rng, -1, 1), randReal(rng, -1, 1), down);
    v.up = std::abs(down) > 4 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    v.fovYDegrees = randReal(rng, 20, 90);
    v.nearDistance = randReal(rng, 0.05, 5.0);
    v.viewportHeight = 720;
    const glm::dmat4 toWorld = gmm::heightfieldToWorld(v, 0.0, scale);
    const gmm::BoxProjector projector(v, toWorld, gmm::ErrorMetric::Certified);
    const MyCamera cam = makeCamera(v);
    const glm::dmat4 toStored = glm::inverse(toWorld);
    const glm::dvec3 below(toStored * glm::dvec4(v.eye, 1.0));
    for (int k = 0; k < 20; ++k)
    {
      gmm::Box box;
      const glm::dvec3 centre(toStored * glm::dvec4(v.eye + glm::normalize(v.forward) * std::exp(randReal(rng, 0, 7)), 1.0));
      const glm::dvec3 half(std::exp(randReal(rng, -1, 5)), std::exp(randReal(rng, -1, 5)), std::exp(randReal(rng, -2, 4)));
      box.lo = centre - half;
      box.hi = centre + half;
      const double factor = projector.factor(box);
      for (int n = 0; n < 60; ++n)
      {
        double x = randReal(rng, box.lo.x, box.hi.x), y = randReal(rng, box.lo.y, box.hi.y);
        if (n < 4)
        {
          x = n & 1 ? box.hi.x : box.lo.x;
          y = n & 2 ? box.hi.y : box.lo.y;
        }
        else if (n == 4)
        {
          x = std::min(std::max(below.x, box.lo.x), box.hi.x);
          y = std::min(std::max(below.y, box.lo.y), box.hi.y);
        }
        const double h0 = n < 4 ? box.lo.z : randReal(rng, box.lo.z, box.hi.z);
        const double h1 = n < 4 ? box.hi.z : randReal(rng, box.lo.z, box.hi.z);
        const glm::dvec3 a(toWorld * glm::dvec4(x, y, h0, 1.0)), b(toWorld * glm::dvec4(x, y, h1, 1.0));
        double ax, ay, bx, by;
        if (project(cam, a.x, a.y, a.z, ax, ay) < v.nearDistance || project(cam, b.x, b.y, b.z, bx, by) < v.nearDistance)
        {
          continue; // the bound is for points in front of the near plane
        }
        const double pixels = std::hypot(ax - bx, ay - by), bound = factor * std::abs(h1 - h0);
        ++segments;
        EXPECT_LE(pixels, bound * (1.0 + 1e-9) + 1e-12) << "trial " << trial << " box " << k << " segment " << n;
        if (bound > 0.0)
        {
          closest = std::max(closest, pixels / bound);
        }
      }
    }
  }
  std::printf("%d segments, largest measured / bound %.3f\n", segments, closest);
  EXPECT_GT(segments, 100000);
  EXPECT_GT(closest, 0.5); // the bound is not vacuous
}

TEST(ActorMatrix, RefusesBadInput)
{
  Rng rng(3);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(roughTerrain(17, 17, rng), 8), "");
  for (double s : { 0.0, -1.0, std::nan(""), HUGE_VAL })
  {
    EXPECT_NE(e.setHeightScale(s), "") << s;
    EXPECT_EQ(e.heightScale(), 1.0);
  }
  gmm::View v;
  v.eye = { 8, -40, 30 };
  v.forward = { 0, 1, -0.5 };
  v.model[0][3] = 0.1; // projective row
  e.update(v, 1.0);
  EXPECT_NE(e.lastError().find("projective"), std::string::npos) << e.lastError();
  v.model = glm::dmat4(1.0);
  v.model[2][2] = 0.0; // singular
  e.update(v, 1.0);
  EXPECT_NE(e.lastError().find("singular"), std::string::npos) << e.lastError();
  gmm::Heightfield bad = roughTerrain(9, 9, rng);
  bad.z0 = std::nan("");
  EXPECT_NE(e.setHeightfield(bad, 8), "");
}
