// Geomorphing's pops by cause: the popping flight of measure_popping.py replayed through the
// engine (Engine::update, then computeMorph with one cache, as the mapper draws a frame),
// and every full-resolution sample in view that moves on screen between two frames classed
// by what changed at its block:
//   merge      the block was under a merged node (or not drawn) in one of the two frames;
//   switch     its level changed, split by the coarser level's cell the sample lies in: a
//              south-east / north-west corner cell of the ring (split along its
//              anti-diagonal, which the finer level does not follow), another ring cell
//              (side strips, fans toward the edge level), or an inner-grid cell;
//   neighbour  a neighbour's level changed (the fans of the strip between them);
//   factor     none of those: only the morph factors moved (the camera's own motion).
// Each class also counts apart the samples of blocks with nodata or beside one
// (Quadtree::anySideAtFullResolution): blocks with nodata do not morph, and neither their
// cells around the nodata (HoleCells.h) nor the sides at full resolution that they share
// nest in the next level's drawing.
// A switch whose morphed surface at factor 1 were the next level's would move nothing, so
// the switch and neighbour classes measure where the levels do not nest, which geomorphing's
// level path hides by switching blocks far below their budget (benchmarks-core.md, session
// 26). The flight, terrain and camera are measure_popping.py's (fractal n x n, 30 m, seed 1
// unless --seed; a straight line across the middle, 250 m above the highest sample, 20
// degrees down, 1280 x 720, fov 50), and its worst pop, mean of frames' worst and triangles come out the
// same here (the screen measure is Testing/Core's, independent of the engine's bound).
//
//   measure_pop_causes [--tau 2] [--range 3] [--block 32] [--n 1025] [--seed 1] [--step 0.04]
//                      [--frames 120] [--threshold 0.3] [--no-merges] [--measure-samples N]
//                      [--amplitude 1500] [--hgt FILE] [--list]
//
// --list also prints each frame whose worst pop is over the threshold: where (sample, block),
// its cause, and the block's level and morph factor in the two frames, to start from.
//
// --amplitude sets the fractal's (metres); --hgt flies over an SRTM tile instead
// (Testing/Core/HgtTile.h: its samples on a metric grid of its spacing).
//
// --range 0 turns geomorphing off (levels switch at once); --no-merges lets merges skip the
// path's levels (the mapper's SetGeomorphMerges off; on by default, as in the mapper);
// --measure-samples sets the mapper's SetGeomorphMeasureSamples (default the mapper's; 0:
// no limit). A measurement, not a test.
#include "Engine.h"
#include "Frame.h"
#include "Morph.h"
#include "SyntheticTerrain.h"
#include "../Core/CoreTestUtil.h"
#include "../Core/HgtTile.h"
#include "../Core/MorphTestUtil.h"
#include "ToolArguments.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
using gmmbench::argOr;
using gmmbench::flag;

enum Cause
{
  Merge,
  SwitchCorner,
  SwitchRing,
  SwitchInner,
  Neighbour,
  Factor,
  CauseCount
};

const char* const kCauseNames[CauseCount] = { "merge or split of a merged node",
  "switch: SE / NW ring corner cell", "switch: other ring cell (strips)", "switch: inner grid cell",
  "a neighbour's switch (its strip)", "factors alone (camera motion)" };

struct CauseTally
{
  long samples = 0; // samples over the threshold, summed over frames
  int frames = 0;   // frames with at least one
  double worst = 0.0;
  long nodataSamples = 0; // of them, in a block with nodata or beside one
  double nodataWorst = 0.0;
};


// The block whose cell holds sample (i, j) (bandOfSample: the cell to its north-east, the
// last band for the last sample), and the sample's position in it.
int blockOfSample(const gmm::Quadtree& qt, int i, int j, int& bi, int& bj)
{
  const int c = gmm::bandOfSample(qt.colStart, i), r = gmm::bandOfSample(qt.rowStart, j);
  bi = i - qt.colStart[c];
  bj = j - qt.rowStart[r];
  return qt.blockIndex(c, r);
}

// The kind of cell of `level` that block-relative sample (bi, bj) lies in.
Cause switchCell(const gmm::Quadtree& qt, int block, int level, int bi, int bj)
{
  const int step = 1 << level;
  const int cols = std::max((qt.blockWidth(block) + step - 1) / step, 1);
  const int rows = std::max((qt.blockHeight(block) + step - 1) / step, 1);
  const int ci = std::min(bi / step, cols - 1), cj = std::min(bj / step, rows - 1);
  const bool southEast = ci == cols - 1 && cj == 0, northWest = ci == 0 && cj == rows - 1;
  if (southEast || northWest)
  {
    return SwitchCorner;
  }
  return ci == 0 || cj == 0 || ci == cols - 1 || cj == rows - 1 ? SwitchRing : SwitchInner;
}

} // namespace

int main(int argc, char** argv)
{
  const double tau = argOr(argc, argv, "--tau", 2.0);
  const double range = argOr(argc, argv, "--range", gmm::kDefaultMorphRange);
  const int block = static_cast<int>(argOr(argc, argv, "--block", 32));
  const int n = static_cast<int>(argOr(argc, argv, "--n", 1025));
  const double stepBlocks = argOr(argc, argv, "--step", 0.04);
  const int frames = static_cast<int>(argOr(argc, argv, "--frames", 120));
  const int seed = static_cast<int>(argOr(argc, argv, "--seed", 1));
  const double amplitude = argOr(argc, argv, "--amplitude", 1500.0);
  const double threshold = argOr(argc, argv, "--threshold", 0.3);
  const bool merges = gmm::FrameSettings().geomorphMerges && !flag(argc, argv, "--no-merges");
  const bool list = flag(argc, argv, "--list");
  const double measureSamples =
    argOr(argc, argv, "--measure-samples", static_cast<double>(gmm::FrameSettings().geomorphMeasureSamples));
  if (!(tau >= 0.0) || block < 4 || n < 3 || frames < 2 || !(threshold > 0.0) || !(measureSamples >= 0.0) ||
    !(measureSamples < 1e15))
  {
    std::fprintf(stderr, "measure_pop_causes: bad arguments (see the file's header)\n");
    return 2;
  }
  const bool morphing = range > 0.0;
  const char* hgt = gmmbench::stringArg(argc, argv, "--hgt");
  gmm::Heightfield input;
  std::string err = hgt ? gmmtest::readHgtTile(hgt, input) : "";
  if (!hgt)
  {
    input = gmm::makeSyntheticTerrain(n, n, 30.0, seed, amplitude);
  }
  gmm::Engine e;
  if (err.empty())
  {
    err = e.setHeightfield(std::move(input), block, 0);
  }
  if (!err.empty())
  {
    std::fprintf(stderr, "measure_pop_causes: %s\n", err.c_str());
    return 2;
  }
  e.setMorphRange(morphing ? range : 0.0);
  e.setMergeOnPath(merges);
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  const double top = gmmtest::highestSample(hf);

  gmm::MorphCache cache;
  cache.measureLimit = static_cast<std::size_t>(measureSamples);
  std::vector<double> previousZ;
  std::vector<int8_t> previousLevels;
  std::vector<float> factors, previousFactors; // per block: the morph factor drawn (0 without)
  CauseTally tally[CauseCount];
  double worstPop = 0.0, meanOfFrameWorst = 0.0;
  double triangles = 0.0;
  for (int f = 0; f < frames; ++f)
  {
    const gmm::View v = gmmtest::poppingFlightView(hf, top, block, stepBlocks, f);
    e.update(v, tau);
    if (!e.lastError().empty())
    {
      std::fprintf(stderr, "measure_pop_causes: frame %d: %s\n", f, e.lastError().c_str());
      return 1;
    }
    triangles += static_cast<double>(e.stats().triangles) / frames;
    std::vector<double> z;
    if (morphing)
    {
      gmm::MorphFrame mf;
      gmm::computeMorph(hf, qt, e.levels(), e.pixelFactors(), gmm::morphErrorBudget(e.stats(), tau), cache,
        mf, e.morphRamp(), &e.drawnBlocks(), &e.drawnConfigs(), &e.errorTable());
      z = gmmtest::morphedHeights(e, mf);
      factors.assign(mf.blockT.begin(), mf.blockT.end());
    }
    else
    {
      z.assign(hf.z.begin(), hf.z.end());
      factors.assign(static_cast<std::size_t>(qt.blockCount()), 0.0f);
    }
    const gmmtest::SurfaceSample surface = gmmtest::sampleSurface(hf, e.indices(), z.data());
    const std::vector<int8_t>& levels = e.levels();
    if (!previousZ.empty())
    {
      const gmmtest::MyCamera cam = gmmtest::makeCamera(v);
      double frameWorst = 0.0;
      int worstI = 0, worstJ = 0;
      Cause worstCause = Factor;
      bool seen[CauseCount] = {};
      for (int j = 0; j < hf.ny; ++j)
      {
        for (int i = 0; i < hf.nx; ++i)
        {
          const std::size_t k = hf.index(i, j);
          const double x = hf.worldX(i), y = hf.worldY(j);
          double px, py, qx, qy;
          if (std::isnan(surface.z[k]) || std::isnan(previousZ[k]) || !gmmtest::insideFrustum(cam, x, y, hf.z[k]) ||
            gmmtest::project(cam, x, y, surface.z[k], px, py) < cam.nearD ||
            gmmtest::project(cam, x, y, previousZ[k], qx, qy) < cam.nearD)
          {
            continue;
          }
          const double pop = std::hypot(px - qx, py - qy);
          const bool worst = pop > frameWorst;
          if (worst)
          {
            frameWorst = pop;
            worstI = i;
            worstJ = j;
          }
          if (pop <= threshold)
          {
            continue;
          }
          int bi = 0, bj = 0;
          const int b = blockOfSample(qt, i, j, bi, bj);
          const int before = previousLevels[b], now = levels[b];
          Cause cause = Factor;
          if (before < 0 || now < 0)
          {
            cause = Merge;
          }
          else if (before != now)
          {
            cause = switchCell(qt, b, std::max(before, now), bi, bj);
          }
          else
          {
            for (int nb : qt.blockNeighbours(b))
            {
              if (nb >= 0 && previousLevels[nb] != levels[nb])
              {
                cause = Neighbour;
              }
            }
          }
          if (worst)
          {
            worstCause = cause;
          }
          ++tally[cause].samples;
          tally[cause].worst = std::max(tally[cause].worst, pop);
          if (qt.anySideAtFullResolution(b))
          {
            ++tally[cause].nodataSamples;
            tally[cause].nodataWorst = std::max(tally[cause].nodataWorst, pop);
          }
          seen[cause] = true;
        }
      }
      for (int c = 0; c < CauseCount; ++c)
      {
        tally[c].frames += seen[c] ? 1 : 0;
      }
      if (list && frameWorst > threshold)
      {
        int bi = 0, bj = 0;
        const int b = blockOfSample(qt, worstI, worstJ, bi, bj);
        std::printf("frame %d: %.3f px at sample (%d, %d), block %d (%d, %d in it)%s: %s; level %d -> %d, "
                    "factor %.3f -> %.3f\n",
          f, frameWorst, worstI, worstJ, b, bi, bj, qt.anySideAtFullResolution(b) ? ", at nodata" : "",
          kCauseNames[worstCause], previousLevels[b], levels[b], previousFactors[b], factors[b]);
      }
      worstPop = std::max(worstPop, frameWorst);
      meanOfFrameWorst += frameWorst / (frames - 1);
    }
    previousZ = surface.z;
    previousLevels = levels;
    previousFactors = factors;
  }
  char mode[64] = "no geomorphing";
  if (morphing)
  {
    std::snprintf(mode, sizeof mode, "geomorphing range %g, merges %s the path", range, merges ? "on" : "off");
  }
  const std::string what = hgt ? std::string(hgt) : "fractal " + std::to_string(n) + "^2";
  std::printf("%s, block %d, tau %g, %s, %d frames of %g blocks: worst pop %.3f px, mean of "
              "frames' worst %.3f px, %.0f triangles a frame\n",
    what.c_str(), block, tau, mode, frames, stepBlocks, worstPop, meanOfFrameWorst, triangles);
  std::printf("samples moving more than %g px between frames, by cause:\n", threshold);
  std::printf("| cause | samples | frames | worst px | samples at nodata | worst px at nodata |\n"
              "|---|---|---|---|---|---|\n");
  for (int c = 0; c < CauseCount; ++c)
  {
    std::printf("| %s | %ld | %d | %.3f | %ld | %.3f |\n", kCauseNames[c], tally[c].samples, tally[c].frames,
      tally[c].worst, tally[c].nodataSamples, tally[c].nodataWorst);
  }
  return 0;
}
