// Nodata (NaN) handling: no emitted triangle references a NaN sample, whatever the levels;
// every cell whose four samples are valid is covered exactly once (area check) in the
// engine's own frames at any error or view, and in hole-free blocks at any forced levels;
// all-nodata emits nothing; the mesh around holes stays free of T-junctions and folds.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "Levels.h"
#include "RasterError.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace gmmtest;

namespace
{
const float kNaN = std::numeric_limits<float>::quiet_NaN();

void expectNoNaNReferenced(const gmm::Heightfield& hf, const std::vector<uint32_t>& idx,
  const std::string& what)
{
  std::size_t bad = 0;
  for (uint32_t k : idx)
    if (!std::isfinite(hf.z[k]))
      ++bad;
  EXPECT_EQ(bad, 0u) << what << ": indices referencing nodata";
}

// True when block b's samples, borders included, are all finite (computed here from the
// heights, not from the quadtree's own flag).
bool blockFree(const gmm::Heightfield& hf, const gmm::Quadtree& qt, int b)
{
  const int c = b % qt.blockCols, r = b / qt.blockCols;
  for (int j = qt.rowStart[r]; j <= qt.rowStart[r + 1]; ++j)
    for (int i = qt.colStart[c]; i <= qt.colStart[c + 1]; ++i)
      if (!std::isfinite(hf.height(i, j)))
        return false;
  return true;
}

// Checks a frame: no NaN referenced; manifold and T-junction-free (boundary edges may
// border holes); and the area coverage (CoreTestUtil.h checkCoverage): no cell covered
// twice, nothing in an undrawn block, and every cell whose four samples are valid covered
// exactly once
// - in every drawn block, when the levels are the engine's own choice (`selected`): a
//   coarser configuration touching nodata has an infinite error, so the engine must never
//   pick one that drops a valid cell next to a hole;
// - in every drawn block free of nodata, for levels forced with updateWithLevels (there a
//   coarse triangle touching a hole is dropped whole, by design).
void checkFrame(const gmm::Engine& e, const std::string& what, bool selected)
{
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  expectNoNaNReferenced(hf, e.indices(), what);
  MeshCheckOptions opt;
  opt.allowNodataHoles = true;
  opt.checkArea = false; // the exact coverage below replaces it
  // blocks with holes and their neighbours may lose any triangle touching nodata at coarse
  // levels: allow boundary edges along any axis line next to a drawn-but-holed region by
  // treating blocks that contain or touch nodata as "not drawn" for the border rule.
  opt.drawn.assign(qt.blockCount(), true);
  for (int b = 0; b < qt.blockCount(); ++b)
    if (!blockFree(hf, qt, b) || !gmm::drawnLevel(e.levels()[b]))
      opt.drawn[b] = false;
  MeshCheckResult res = checkMesh(hf, qt.colStart, qt.rowStart, e.indices(), opt);
  EXPECT_EQ(res.error, "") << what;
  std::vector<bool> drawn(qt.blockCount()), mustCover(qt.blockCount());
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    drawn[b] = gmm::drawnLevel(e.levels()[b]);
    mustCover[b] = selected || blockFree(hf, qt, b);
  }
  EXPECT_EQ(checkCoverage(hf, qt.colStart, qt.rowStart, e.indices(), drawn, mustCover), "") << what;
}
// The engine's own frames at these view-independent errors, then from an oblique view
// at tau 1, each checked by checkFrame.
void checkSelectedFrames(gmm::Engine& e, std::initializer_list<double> errors)
{
  const gmm::Heightfield& hf = e.heightfield();
  for (double err : errors)
  {
    e.updateForError(err);
    checkFrame(e, "updateForError " + std::to_string(err), true);
  }
  gmm::View v;
  v.eye = { hf.worldX(hf.nx / 2.0), hf.worldY(-5.0), 800.0 };
  v.forward = { 0, hf.dy, -0.6 * std::fabs(hf.dy) };
  v.fovYDegrees = 60;
  e.update(v, 1.0);
  ASSERT_EQ(e.lastError(), "");
  checkFrame(e, "update", true);
}
} // namespace

TEST(Nodata, SingleSampleHole)
{
  Rng rng(1);
  for (int trial = 0; trial < 20; ++trial)
  {
    const int nx = randInt(rng, 5, 90), ny = randInt(rng, 5, 90);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    const int hi = randInt(rng, 0, nx - 1), hj = randInt(rng, 0, ny - 1);
    hf.z[hf.index(hi, hj)] = kNaN;
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, randInt(rng, 4, 32), 1), "");
    checkSelectedFrames(e, { 0.0, 1.0, 50.0, 1e9 });
  }
}

TEST(Nodata, WholeBlockHoleAndRandomLevels)
{
  Rng rng(2);
  for (int trial = 0; trial < 20; ++trial)
  {
    const int nx = randInt(rng, 20, 150), ny = randInt(rng, 20, 150), maxQ = randInt(rng, 4, 16);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    gmm::Quadtree qt0 = gmm::buildQuadtree(hf, maxQ);
    const int c = randInt(rng, 0, qt0.blockCols - 1), r = randInt(rng, 0, qt0.blockRows - 1);
    for (int j = qt0.rowStart[r]; j <= qt0.rowStart[r + 1]; ++j)
      for (int i = qt0.colStart[c]; i <= qt0.colStart[c + 1]; ++i)
        hf.z[hf.index(i, j)] = kNaN;
    // plus scattered holes
    for (int k = 0; k < 10; ++k)
      hf.z[randInt(rng, 0, nx * ny - 1)] = kNaN;
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    const gmm::Quadtree& qt = e.quadtree();
    for (double err : { 0.0, 5.0, 1e9 })
    {
      e.updateForError(err);
      checkFrame(e, "updateForError " + std::to_string(err), true);
    }
    // random levels: tessellation itself must drop every triangle touching nodata
    for (int f = 0; f < 10; ++f)
    {
      std::vector<int8_t> lv(qt.blockCount());
      for (int rr = 0; rr < qt.blockRows; ++rr)
        for (int cc = 0; cc < qt.blockCols; ++cc)
        {
          const int w = qt.colStart[cc + 1] - qt.colStart[cc], h = qt.rowStart[rr + 1] - qt.rowStart[rr];
          std::vector<int> v;
          for (int m = 0; m <= gmm::topLevel(w, h); ++m)
            if (gmm::blockShape(w, h, m) != gmm::BlockShape::Invalid)
              v.push_back(m);
          lv[qt.blockIndex(cc, rr)] = static_cast<int8_t>(v[randInt(rng, 0, static_cast<int>(v.size()) - 1)]);
        }
      e.updateWithLevels(lv);
      checkFrame(e, "updateWithLevels", false);
    }
    // At full resolution (error 0) every cell with 4 valid corners gives 2 triangles and a
    // cell with exactly one nodata corner at most 1: the count is bounded by hand.
    e.updateForError(0.0);
    std::size_t validCells = 0, oneMissing = 0;
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
      {
        const int bad = std::isnan(hf.height(i, j)) + std::isnan(hf.height(i + 1, j)) +
          std::isnan(hf.height(i, j + 1)) + std::isnan(hf.height(i + 1, j + 1));
        validCells += bad == 0;
        oneMissing += bad == 1;
      }
    EXPECT_GE(e.stats().triangles, 2 * validCells);
    EXPECT_LE(e.stats().triangles, 2 * validCells + oneMissing);
  }
}

TEST(Nodata, AllNodataEmitsNothing)
{
  for (auto [nx, ny] : { std::pair{ 2, 2 }, std::pair{ 9, 9 }, std::pair{ 70, 33 } })
  {
    gmm::Heightfield hf;
    hf.nx = nx;
    hf.ny = ny;
    hf.z.assign(static_cast<std::size_t>(nx) * ny, kNaN);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 16, 1), "");
    EXPECT_EQ(e.updateForError(0.0).triangles, 0u);
    EXPECT_TRUE(e.indices().empty());
    EXPECT_EQ(e.updateForError(1e9).triangles, 0u);
    gmm::View v;
    v.eye = { nx / 2.0, -10.0, 10.0 };
    v.forward = { 0, 1, -0.5 };
    const gmm::FrameStats& s = e.update(v, 1.0);
    EXPECT_EQ(s.triangles, 0u);
    EXPECT_TRUE(e.indices().empty());
    std::vector<int8_t> lv(e.quadtree().blockCount(), 0);
    EXPECT_EQ(e.updateWithLevels(lv).triangles, 0u);
  }
}

TEST(Nodata, BorderWedgesStayInTheirCollars)
{
  // A reprojected raster's nodata wedges along its borders (Quadtree.h, nodataCollar). Row
  // j starts with a run of nodata growing from 0 to tW along the west border and ends with
  // one shrinking from tE to 0; columns start with up to tS nodata samples from the south.
  // Every block outside the collar bands must then be free to coarsen: at an error of 1e9
  // the frame draws at most 2 triangles per quad of the collar bands (they hold all the
  // nodata) and a few per other block, where without the collars each border block would
  // be drawn whole at full resolution (2 per quad of every border block).
  Rng rng(5);
  for (int trial = 0; trial < 20; ++trial)
  {
    const int maxQ = 8 << randInt(rng, 0, 2);
    const int nx = randInt(rng, 3 * maxQ, 8 * maxQ), ny = randInt(rng, 3 * maxQ, 8 * maxQ);
    const int tW = randInt(rng, 1, maxQ - 5), tE = randInt(rng, 0, maxQ - 5);
    const int tS = randInt(rng, 0, 3);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng);
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < tW * j / (ny - 1); ++i)
        hf.z[hf.index(i, j)] = kNaN;
      for (int i = 0; i < tE * (ny - 1 - j) / (ny - 1); ++i)
        hf.z[hf.index(nx - 1 - i, j)] = kNaN;
    }
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < tS * i / (nx - 1); ++j)
        hf.z[hf.index(i, j)] = kNaN;
    SCOPED_TRACE(std::to_string(nx) + "x" + std::to_string(ny) + " block " + std::to_string(maxQ) +
      " wedges " + std::to_string(tW) + " " + std::to_string(tE) + " " + std::to_string(tS));
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    const gmm::Quadtree& qt = e.quadtree();
    checkSelectedFrames(e, { 0.0, 5.0, 1e9 });

    // The bound, from the heights: quads of the blocks holding nodata (found here by
    // scanning) at 2 triangles each, 8 for every other block (a one-quad block, or its
    // share of a merged fan, with a strip fanned towards a finer neighbour).
    std::size_t holedQuads = 0, otherBlocks = 0, borderQuads = 0;
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      const std::size_t quads = static_cast<std::size_t>(qt.blockWidth(b)) * qt.blockHeight(b);
      if (blockFree(hf, qt, b))
        ++otherBlocks;
      else
        holedQuads += quads;
    }
    for (int r = 0; r < qt.blockRows; ++r)
      for (int c = 0; c < qt.blockCols; ++c)
        if (r == 0 || c == 0 || c + 1 == qt.blockCols)
          borderQuads += static_cast<std::size_t>(qt.blockWidth(qt.blockIndex(c, r))) *
            qt.blockHeight(qt.blockIndex(c, r));
    // the nodata lies in the collar bands (one more than the wedge, widened by one where
    // the next band would start on an odd sample): a fraction of the border blocks' quads
    const int collarW = (tW + 1) + (tW + 1) % 2, collarE = (tE + 1) + (nx - 1 - (tE + 1)) % 2;
    const int collarS = (tS + 1) + (tS + 1) % 2;
    EXPECT_LE(holedQuads, static_cast<std::size_t>(collarW * ny + collarE * ny + collarS * nx));
    const std::size_t triangles = e.updateForError(1e9).triangles;
    EXPECT_LE(triangles, 2 * holedQuads + 8 * otherBlocks) << "border blocks " << borderQuads;
  }
}

namespace
{
// A 65 x 65 plane z = a i + b j with one nodata sample at (vi, vj).
gmm::Heightfield planeWithOneVoid(float a, float b, int vi, int vj)
{
  gmm::Heightfield hf;
  hf.nx = hf.ny = 65;
  hf.z.resize(65 * 65);
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i)
      hf.z[hf.index(i, j)] = a * i + b * j;
  hf.z[hf.index(vi, vj)] = kNaN;
  return hf;
}

// A frame over such a plane: no nodata referenced, checkFrame's watertightness and
// coverage, and every drawn triangle exact (a plane is drawn exactly wherever it is drawn).
void expectPlaneDrawnExactly(const gmm::Engine& e, const gmm::Heightfield& hf, const std::string& what)
{
  EXPECT_EQ(e.indices().size(), 3 * e.stats().triangles) << what;
  expectNoNaNReferenced(hf, e.indices(), what);
  checkFrame(e, what, true);
  std::vector<gmm::GridTriangle> tris;
  for (std::size_t t = 0; t < e.indices().size(); t += 3)
  {
    gmm::GridTriangle g;
    for (int k = 0; k < 3; ++k)
      g.v[k] = { static_cast<int>(e.indices()[t + k] % hf.nx), static_cast<int>(e.indices()[t + k] / hf.nx) };
    tris.push_back(g);
  }
  EXPECT_EQ(gmm::trianglesError(hf, tris, true), 0.0f) << what;
}
} // namespace

TEST(Nodata, InteriorVoidCoarsensAroundItsCells)
{
  // A 65 x 65 plane, block 32 (2 x 2 blocks), one nodata sample at (16, 16), the centre of
  // block 0. By hand (HoleCells.h): block 0 is drawn as cells around the nodata, but for
  // the border rows of its level's cells that hold none, which side strips draw to the
  // cells' vertices. (16, 16) is 16 lines in from every side: at level 3 (8-quad cells)
  // no border row holds it, at level 4 every one does. (16, 16) is a corner of the four
  // cells around it at every level, and each of those is split towards it down to the quad
  // that holds it. A cell is drawn over its vertices (its corners and every other cell's
  // corner on its sides) in two triangles fewer than it has vertices.
  // - Level 3: cells over [8, 24]^2, 2 x 2 cells of 8 quads. The cell south-west of the
  //   void, [8, 16]^2, splits into three clean 4-quad cells ([8, 12]^2: 2 triangles; the
  //   two beside [12, 16]^2, whose side has that cell's split point at 14: 3 each),
  //   [12, 16]^2 into three clean 2-quad cells (2, 3, 3) and [14, 16]^2 into three clean
  //   quads (2 each) and the quad holding (16, 16): 22 triangles; the other three cells
  //   are its mirror images. The four quads with (16, 16) as a corner are split on the
  //   diagonals through it (16 + 16 is even: the union-jack rule, Levels.h), so all 8 of
  //   their triangles touch it: cells 4 x 22 = 88. Strips (one triangle per step
  //   along either line, Tessellate.h): the inner lines have the cells' corners 8, 12, 16,
  //   20, 24 (4 steps); the south and west edges lie on the DEM's border, at the level (4
  //   steps): 8 each; the east and north edges beside the one-quad blocks 1 and 2 are
  //   glided (Tessellate.h, BlockConfig::sampleLevel): at the level too, their samples
  //   drawn on those blocks' sides (4 steps): 8 each. 88 + 4 x 8 = 120.
  // - Level 4 is cells over the whole block, 234 triangles (levels 4 and 5 split into the
  //   same cells and draw the border at full resolution), more than level 3: not allowed,
  //   nor is 5. Level 2 draws more than 3 (cells over [4, 28]^2 of 4 quads).
  // So at any error block 0 takes level 3. Blocks 1, 2 and 3 take their one-quad level, 2
  // triangles each (the root cannot merge over nodata), those of blocks 1 and 2 cut at the
  // glided edge's 3 samples between their corners: 5 each. Without the cells block 0 would
  // draw its 2 048 full-resolution triangles less 6.
  const gmm::Heightfield hf = planeWithOneVoid(3.0f, 2.0f, 16, 16);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 32, 1), "");
  const gmm::FrameStats& s = e.updateForError(1e9);
  EXPECT_EQ(e.levels()[0], 3);
  EXPECT_EQ(e.levels()[1], 5);
  EXPECT_EQ(e.levels()[2], 5);
  EXPECT_EQ(e.levels()[3], 5);
  EXPECT_EQ(s.triangles, (4u * 22 + 4 * (4 + 4)) + 2 * (2 + 3) + 2);
  expectPlaneDrawnExactly(e, hf, "interior void");
}

TEST(Nodata, VoidOnABlockBorderCoarsensBothBlocks)
{
  // A 65 x 65 plane, block 32 (2 x 2 blocks), one nodata sample at (32, 16): on the side
  // blocks 0 and 1 share. Before the cells reached the border, a strip could not pass it
  // and both blocks were drawn at full resolution. By hand (HoleCells.h, cells, fans and
  // strips as in the test above), block 0 at level 3: the east border row holds the void,
  // the south, north and west ones (16, 16 and 32 lines from it) do not.
  // - Cells over [8, 32] x [8, 24], its east side at full resolution. [8, 16] x [8, 24]:
  //   two clean cells with only their corners, 2 each; [16, 24] x [8, 16] and its mirror
  //   image have the split point 12 (20) on their east side: 3 each. [24, 32] x [8, 16]
  //   splits towards (32, 16): [24, 28] x [8, 12] (2), [28, 32] x [8, 12] (3 border
  //   samples and the split point 30 above it: 6), [24, 28] x [12, 16] (split point 14 on
  //   its east side: 3); [28, 32] x [12, 16] into [28, 30] x [12, 14] (2), [30, 32] x [12, 14]
  //   (border sample 13 and split point 31: 4), [28, 30] x [14, 16] (split point 15: 3) and
  //   [30, 32] x [14, 16] into three clean quads (2 each) and the quad holding (32, 16),
  //   both of whose triangles touch it: 26. Its mirror image [24, 32] x [16, 24]: 26, its
  //   quad at the void split on the diagonal through it too (32 + 16 is even: the
  //   union-jack rule, Levels.h). Cells: 2 x 2 + 2 x 3 + 2 x 26.
  // - Strips: the south one's edge on the DEM's border at the level (0 to 32: 4 steps), its
  //   inner line the cells' corners 8, 16, 24, 28, 32 (4 steps), and its east end on the
  //   block's border, j = 0 to 8 at full resolution, fanned from (28, 8): 7 triangles more:
  //   15. The north one's edge beside the one-quad block 2 is glided (Tessellate.h,
  //   BlockConfig::sampleLevel): at the level, on block 2's side (4 steps), 4 steps inside,
  //   7 at its end: 15. The west one's edge on the DEM's border (4 steps), its inner line
  //   24, 16, 8 (2 steps): 6.
  // 98 triangles. Level 4 has strips on the west side alone, and its cells split as
  //   before (the two eastern 16-quad cells alone 55 each): more, not allowed, nor is 5;
  //   level 2 has more cells. Block 1 is block 0's mirror image, its two quads at the void
  //   split on diagonals through it as well: 98. Blocks 2 and 3 take their one-quad level, 2
  //   triangles each, cut at the glided edge's 3 samples between their corners: 5 each.
  const gmm::Heightfield hf = planeWithOneVoid(2.0f, -3.0f, 32, 16);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 32, 1), "");
  const gmm::FrameStats& s = e.updateForError(1e9);
  EXPECT_EQ(e.levels()[0], 3);
  EXPECT_EQ(e.levels()[1], 3);
  EXPECT_EQ(e.levels()[2], 5);
  EXPECT_EQ(e.levels()[3], 5);
  EXPECT_EQ(s.triangles, 2u * ((2 * 2 + 2 * 3 + 2 * 26) + 15 + 15 + 6) + 2 * (2 + 3));
  expectPlaneDrawnExactly(e, hf, "void on a border");
}

TEST(Nodata, VoidBlocksAreNeitherWalkedNorDrawn)
{
  // A coastal SRTM tile is about half sea (nodata): a block whose every sample is nodata
  // draws nothing at any level, and counting it as drawn made the void most of what a frame
  // walked. 65 x 65 samples in blocks of 8 quads (8 x 8 blocks); samples 16..40 x 8..32
  // are void, so blocks (2..4, 1..3) are nodata to their borders: 9 of 64, counted by hand.
  Rng rng(7);
  gmm::Heightfield hf = roughTerrain(65, 65, rng);
  for (int j = 8; j <= 32; ++j)
    for (int i = 16; i <= 40; ++i)
      hf.z[hf.index(i, j)] = kNaN;
  for (bool merged : { false, true })
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 8, 1), "");
    e.setMergedNodes(merged);
    const gmm::Quadtree& qt = e.quadtree();
    ASSERT_EQ(qt.blockCount(), 64);
    auto expectVoidNotDrawn = [&](const std::string& what) {
      for (int r = 0; r < qt.blockRows; ++r)
        for (int c = 0; c < qt.blockCols; ++c)
        {
          const bool isVoid = c >= 2 && c <= 4 && r >= 1 && r <= 3;
          EXPECT_EQ(e.levels()[qt.blockIndex(c, r)] == -1, isVoid) << what << " block (" << c << ", " << r << ")";
        }
      EXPECT_EQ(e.stats().visibleBlocks, 55) << what;
      checkFrame(e, what, true); // every valid cell still drawn once, nothing over nodata
    };
    for (double err : { 0.0, 3.0, 1e9 })
    {
      e.updateForError(err);
      expectVoidNotDrawn("merged " + std::to_string(merged) + ", updateForError " + std::to_string(err));
    }
    gmm::View v; // the whole DEM (640 m a side) in view, from high above its centre
    v.eye = { hf.worldX(32), hf.worldY(32), 3000.0 };
    v.forward = { 0.0, 0.05, -1.0 };
    v.up = { 0.0, 1.0, 0.0 };
    v.fovYDegrees = 60;
    for (double tau : { 0.5, 4.0 })
    {
      e.update(v, tau);
      ASSERT_EQ(e.lastError(), "");
      expectVoidNotDrawn("merged " + std::to_string(merged) + ", update tau " + std::to_string(tau));
    }
  }
}
