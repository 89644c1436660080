// Shared checks for the stress-matrix tests (issue #6): one call validates everything a
// rendered frame must satisfy, using only the independent helpers of CoreTestUtil.h.
//
//   expectGoodFrame(engine, &view, tau, "what");   // view mode: certification too
//   expectGoodFrame(engine, nullptr, 0.0, "what"); // updateForError / updateWithLevels
//
// Checked: index count = 3 * triangles, every index < nx*ny and on a finite sample; the mesh
// is manifold, counter-clockwise, free of T-junctions (exact area too when there is no
// nodata); finite statistics; no NaN in the error table and finite entries for every valid
// level of a hole-free block; and, with a view, the certified screen-space bound measured
// sample by sample (same method and tolerance as TestErrorCertification.cpp), coverage of
// every in-frustum sample away from nodata, and the geometric bound over drawn samples.
#pragma once

#include "CoreTestUtil.h"
#include "Engine.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace gmmtest
{

// No NaN anywhere in the table; finite own errors for every valid level of a block without
// nodata (Inf there would mean an overflow, not "level not allowed").
inline void expectSaneErrorTable(const gmm::Engine& e, const std::string& what)
{
  const gmm::ErrorTable& t = e.errorTable();
  const gmm::Quadtree& qt = e.quadtree();
  for (float v : t.stripError)
    ASSERT_FALSE(std::isnan(v)) << what << ": NaN strip error";
  for (int b = 0; b < qt.blockCount(); ++b)
    for (int m = 0; m < t.levels; ++m)
    {
      ASSERT_FALSE(std::isnan(t.own(b, m))) << what << ": NaN error, block " << b << " level " << m;
      const int w = qt.blockWidth(b), h = qt.blockHeight(b);
      if (!qt.blockHasNodata[b] && m <= refTopLevel(w, h) && refLevelValid(w, h, m))
      {
        ASSERT_TRUE(std::isfinite(t.own(b, m)) && std::isfinite(t.ownExact(b, m)))
          << what << ": non-finite error, block " << b << " level " << m;
      }
    }
}

// Everything a rendered frame must satisfy (see the file comment).
inline void expectGoodFrame(const gmm::Engine& e, const gmm::View* view, double tau, const std::string& what)
{
  ASSERT_EQ(e.lastError(), "") << what;
  const gmm::FrameStats& st = e.stats();
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  ASSERT_EQ(st.triangles * 3, e.indices().size()) << what;
  ASSERT_TRUE(std::isfinite(st.maxGeometricError) && std::isfinite(st.maxScreenError)) << what;
  bool nodata = false;
  for (float z : hf.z)
    nodata = nodata || std::isnan(z);
  const std::size_t n = hf.z.size();
  for (uint32_t k : e.indices())
  {
    ASSERT_LT(k, n) << what << ": index out of range";
    ASSERT_TRUE(std::isfinite(hf.z[k])) << what << ": triangle on a nodata sample " << k;
  }
  MeshCheckOptions opt;
  opt.drawn.assign(qt.blockCount(), true);
  for (int b = 0; b < qt.blockCount(); ++b)
    opt.drawn[b] = gmm::drawnLevel(e.levels()[b]) && !(nodata && qt.blockHasNodata[b]);
  opt.allowNodataHoles = nodata;
  opt.checkArea = !nodata;
  const MeshCheckResult mesh = checkMesh(hf, qt.colStart, qt.rowStart, e.indices(), opt);
  EXPECT_EQ(mesh.error, "") << what;
  expectSaneErrorTable(e, what);
  const ScreenMeasure m = measureScreenError(hf, e.indices(), view, tau, MeasureTransform(), drawnHeights(e).data());
  EXPECT_LE(m.maxVertical, st.maxGeometricError * (1 + 1e-6) + 1e-5 * (1 + st.maxGeometricError))
    << what << ": drawn surface further from the samples than the certified geometric bound";
  if (view)
  {
    EXPECT_EQ(m.uncovered, 0u) << what << ": " << m.first;
    EXPECT_EQ(m.violations, 0u) << what << ": " << m.first;
    EXPECT_LE(st.maxScreenError, tau * (1 + 1e-12)) << what;
  }
}

// A DEM of the given size: smooth hills, a ridge, a tilted plane and a plateau, amp high.
// Heights are rounded to `quantum` (0: not rounded); with the defaults every height is a
// multiple of 0.5 m, so adding an offset up to 2^23 m keeps it exact in float
// (TestStressLargeCoordinates).
inline gmm::Heightfield hillsDem(int nx, int ny, double dx = 30.0, double dy = 30.0,
  double amp = 800.0, double quantum = 0.5)
{
  gmm::Heightfield hf;
  hf.nx = nx;
  hf.ny = ny;
  hf.dx = dx;
  hf.dy = dy;
  hf.z.resize(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const double h = amp * (0.5 + 0.3 * std::sin(0.11 * i) * std::cos(0.07 * j) +
                               0.2 * std::exp(-0.01 * (i - j) * (i - j)) + 0.004 * std::sin(1.7 * i + 2.3 * j));
      hf.z[hf.index(i, j)] = static_cast<float>(quantum > 0 ? std::round(h / quantum) * quantum : h);
      if (4 * i < nx) // a tilted plane (exactly planar in float with the defaults)
        hf.z[hf.index(i, j)] = static_cast<float>(amp * (0.25 + (i + 3.0 * j) / 1600.0));
      else if (4 * j > 3 * ny) // a flat plateau
        hf.z[hf.index(i, j)] = static_cast<float>(amp);
    }
  return hf;
}

// A camera over the DEM's south edge looking north and down (dy < 0 looks the other way).
inline gmm::View overview(const gmm::Heightfield& hf, double height = 1500.0)
{
  gmm::View v;
  v.eye = { hf.worldX(0.5 * (hf.nx - 1)), hf.worldY(-0.15 * (hf.ny - 1)), height };
  v.forward = { 0.0, hf.dy > 0 ? 1.0 : -1.0, -0.5 };
  v.fovYDegrees = 60.0;
  v.nearDistance = 1.0;
  v.farDistance = 1e7;
  return v;
}

} // namespace gmmtest
