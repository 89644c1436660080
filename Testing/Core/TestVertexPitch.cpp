// Drawing ids (VertexPitch.h): j * pitch + i for sample index j * nx + i, exact over the
// whole grid, the restart index kept, and a pitch that a cache keyed by id % 256 (Mesa's
// draw module, modelled below from draw_pt_vsplit.c) reuses far better than nx on the
// grid widths users have (every 2^k + 1).
#include "CoreTestUtil.h"
#include "Engine.h"
#include "IndexArena.h"
#include "SyntheticTerrain.h"
#include "VertexPitch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace
{

// Vertex shader runs of an indexed triangle draw in Mesa's draw module: the list is cut into
// segments of at most 1 023 indices (whole triangles of a 1 024 segment), each starting with
// an empty direct-mapped cache of 256 entries keyed by id % 256; an id not in its entry is
// shaded (and replaces the entry).
long modelledVertexRuns(const std::vector<uint32_t>& ids)
{
  long runs = 0;
  std::vector<int64_t> cache(256);
  for (std::size_t s = 0; s < ids.size(); s += 1023)
  {
    std::fill(cache.begin(), cache.end(), -1);
    for (std::size_t k = s; k < std::min(ids.size(), s + 1023); ++k)
    {
      int64_t& entry = cache[ids[k] % 256];
      if (entry != ids[k])
      {
        entry = ids[k];
        ++runs;
      }
    }
  }
  return runs;
}

} // namespace

TEST(VertexPitch, PitchIsAtLeastTheWidthWithTheChosenResidue)
{
  for (int nx : { 1, 2, 93, 94, 255, 256, 257, 513, 600, 1025, 3601, 4097, 16385 })
  {
    const uint32_t p = gmm::drawPitch(nx, nx);
    EXPECT_GE(p, static_cast<uint32_t>(nx)) << nx;
    EXPECT_LT(p, static_cast<uint32_t>(nx) + 256u) << nx;
    EXPECT_EQ(p % 256u, gmm::kDrawPitchResidue) << nx;
  }
  // 513 -> 605 by hand: 513 = 2 * 256 + 1, and 605 = 2 * 256 + 93.
  EXPECT_EQ(gmm::drawPitch(513, 513), 605u);
}

TEST(VertexPitch, FallsBackToTheWidthWhereIdsWouldReachTheRestartIndex)
{
  // 65 536 x 65 535 samples: the last id with pitch 65 536 + 93 passes 2^32 - 1.
  EXPECT_EQ(gmm::drawPitch(65536, 65535), 65536u);
  // With pitch nx the last sample index is below the restart index, as for any grid the
  // engine takes (fewer than 2^32 - 1 samples).
  const uint32_t nx = 65536, ny = 65535;
  EXPECT_LT(static_cast<uint64_t>(ny - 1) * nx + (nx - 1), static_cast<uint64_t>(gmm::kRestartIndex));
  // Just inside: the padded last id fits.
  EXPECT_EQ(gmm::drawPitch(60000, 60000) % 256u, gmm::kDrawPitchResidue);
}

TEST(VertexPitch, DrawIdsAreExactAndKeepTheRestartIndex)
{
  std::mt19937 rng(11);
  for (int nx : { 1, 3, 513, 600, 4097, 16385, 65535 })
  {
    const int ny = static_cast<int>(std::min<uint64_t>(UINT32_MAX / static_cast<uint64_t>(nx + 256), 70000));
    const uint32_t pitch = gmm::drawPitch(nx, ny);
    std::vector<uint32_t> in = { 0u, static_cast<uint32_t>(nx - 1), gmm::kRestartIndex,
      static_cast<uint32_t>(static_cast<uint64_t>(ny) * nx - 1) };
    std::uniform_int_distribution<uint64_t> any(0, static_cast<uint64_t>(ny) * nx - 1);
    for (int k = 0; k < 20000; ++k)
    {
      in.push_back(static_cast<uint32_t>(any(rng)));
    }
    for (int j : { 1, ny / 2, ny - 1 }) // row starts and ends
    {
      in.push_back(static_cast<uint32_t>(static_cast<uint64_t>(j) * nx));
      in.push_back(static_cast<uint32_t>(static_cast<uint64_t>(j) * nx - 1));
    }
    std::vector<uint32_t> out(in.size());
    gmm::toDrawIds(in.data(), in.size(), nx, pitch, out.data());
    for (std::size_t k = 0; k < in.size(); ++k)
    {
      if (in[k] == gmm::kRestartIndex)
      {
        EXPECT_EQ(out[k], gmm::kRestartIndex);
        continue;
      }
      const uint64_t i = in[k] % static_cast<uint64_t>(nx), j = in[k] / static_cast<uint64_t>(nx);
      ASSERT_EQ(out[k], j * pitch + i) << "nx " << nx << " index " << in[k];
    }
    std::vector<uint32_t> inPlace = in; // the mapper converts a scratch copy in place
    gmm::toDrawIds(inPlace.data(), inPlace.size(), nx, pitch, inPlace.data());
    EXPECT_EQ(inPlace, out);
  }
}

TEST(VertexPitch, ModelledCacheShadesEachVertexAboutOnce)
{
  // The engine's triangles of a wide view, as the mapper draws them (the plain list; the
  // arena's slots split it at restarts, which changes the figures by under 1 %).
  for (int block : { 16, 32, 64 })
  {
    const int n = 1025; // nx % 256 == 1, as every 2^k + 1 DEM
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(gmm::makeSyntheticTerrain(n, n, 30.0, 1), block, 0), "");
    const gmm::Heightfield& hf = e.heightfield();
    const double ext = (n - 1) * hf.dx;
    gmm::View v;
    v.eye = { 0.05 * ext, 0.1 * ext, 2500.0 };
    const glm::dvec3 ahead = glm::dvec3(0.5 * ext, 0.5 * ext, 0.0) - v.eye;
    v.forward = ahead / glm::length(ahead);
    v.up = { 0, 0, 1 };
    v.fovYDegrees = 50.0;
    v.viewportWidth = 1280;
    v.viewportHeight = 720;
    v.nearDistance = 1.0;
    v.farDistance = 4.0 * ext;
    e.update(v, 1.0);
    const std::vector<uint32_t>& samples = e.indices();
    ASSERT_GT(samples.size(), 3u * 20000u) << block;
    std::vector<uint32_t> padded(samples.size());
    gmm::toDrawIds(samples.data(), samples.size(), n, gmm::drawPitch(n, n), padded.data());
    const double triangles = samples.size() / 3.0;
    const double plain = modelledVertexRuns(samples) / triangles;
    const double drawn = modelledVertexRuns(padded) / triangles;
    std::printf("block %d: %.0f triangles, %.3f vertex runs a triangle with ids j * nx + i, %.3f with the "
                "drawing pitch\n",
      block, triangles, plain, drawn);
    // A regular grid has half a vertex a triangle; each segment restarts its cache.
    EXPECT_GT(plain, 1.3) << block;
    EXPECT_LT(drawn, 0.8) << block;
  }
}
