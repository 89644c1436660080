// How far the drawn surface jumps when a block switches level, measured on the frames of
// measure_pop_causes' flight: the yardstick for levels that nest (benchmarks-core.md,
// session 27).
//
// For every drawn block at level c >= 1 of every `--every`-th frame, with a the level below
// c on its chain (MorphRamp.h) and the neighbours as selected, three mismatches between
// level a fully morphed (factor 1) and level c unmorphed, each the largest vertical
// distance over the block's samples, in pixels at a switch where the block's error just
// fits tau (tau * M / E, E the block's certified error at c with its edges, as selection
// bounds it):
//   rule      the block's interior vertices at Morph.h's targets (level c with its own
//             edges, ignoring a coarser neighbour's edge), its edges it sets at level c's
//             polyline: what geomorphing draws;
//   nested    every vertex of level a moved onto level c's drawn surface, edges included:
//             what remains if the targets followed the neighbours' edges (the triangles of
//             the two levels still differ: the strips' fans and the corner cells);
//   neighbour the strip of each finer neighbour whose edge follows the block's level, its
//             edge vertices on level c's polyline (the same for both rules), against that
//             neighbour's own error.
//
//   measure_switch_mismatch [--tau 2] [--block 32] [--n 1025] [--step 0.04] [--frames 120]
//                           [--every 10]
// A measurement, not a test.
#include "Engine.h"
#include "EdgeHeights.h"
#include "Morph.h"
#include "SelectLevels.h"
#include "SyntheticTerrain.h"
#include "../Core/MorphTestUtil.h"
#include "ToolArguments.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
using gmmbench::argOr;

// The drawn surface of `block` with `config` at every sample of its rectangle (row by row
// from its first sample; NaN where no triangle covers one), each vertex at vertexHeight(i, j).
std::vector<double> blockSurface(const gmm::Quadtree& qt, int block, const gmm::BlockConfig& config,
  const std::function<double(int, int)>& vertexHeight)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], j0 = qt.rowStart[r];
  const int w = qt.blockWidth(block) + 1, h = qt.blockHeight(block) + 1;
  std::vector<double> out(static_cast<std::size_t>(w) * h, std::numeric_limits<double>::quiet_NaN());
  std::vector<gmm::GridTriangle> tris;
  gmm::EmitScratch scratch;
  gmm::emitBlockGrid(qt, block, config, gmm::BlockPart::Whole, tris, scratch);
  for (const gmm::GridTriangle& t : tris)
  {
    const long long I[3] = { t.v[0].i, t.v[1].i, t.v[2].i }, J[3] = { t.v[0].j, t.v[1].j, t.v[2].j };
    const long long area = (I[1] - I[0]) * (J[2] - J[0]) - (I[2] - I[0]) * (J[1] - J[0]);
    if (area == 0)
    {
      continue;
    }
    const double H[3] = { vertexHeight(t.v[0].i, t.v[0].j), vertexHeight(t.v[1].i, t.v[1].j),
      vertexHeight(t.v[2].i, t.v[2].j) };
    for (long long j = std::min({ J[0], J[1], J[2] }); j <= std::max({ J[0], J[1], J[2] }); ++j)
    {
      for (long long i = std::min({ I[0], I[1], I[2] }); i <= std::max({ I[0], I[1], I[2] }); ++i)
      {
        long long wk[3]; // edge function opposite vertex k: the weight of vertex k times area
        for (int k = 0; k < 3; ++k)
        {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          wk[k] = (I[b] - I[a]) * (j - J[a]) - (J[b] - J[a]) * (i - I[a]);
        }
        if (area > 0 ? (wk[0] < 0 || wk[1] < 0 || wk[2] < 0) : (wk[0] > 0 || wk[1] > 0 || wk[2] > 0))
        {
          continue;
        }
        out[static_cast<std::size_t>(j - j0) * w + (i - i0)] =
          (wk[0] * H[0] + wk[1] * H[1] + wk[2] * H[2]) / static_cast<double>(area);
      }
    }
  }
  return out;
}

double largestGap(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    worst = std::max(worst, std::fabs(a[k] - b[k])); // NaN (uncovered) is skipped by max
  }
  return worst;
}

void report(const char* name, std::vector<double> px)
{
  if (px.empty())
  {
    std::printf("| %s | 0 | | | | |\n", name);
    return;
  }
  std::sort(px.begin(), px.end());
  auto at = [&](double q) { return px[static_cast<std::size_t>(q * (px.size() - 1))]; };
  const long over = std::count_if(px.begin(), px.end(), [](double p) { return p > 0.5; });
  std::printf("| %s | %zu | %.3f | %.3f | %.3f | %.1f %% |\n", name, px.size(), at(0.5), at(0.9), px.back(),
    100.0 * over / px.size());
}

} // namespace

int main(int argc, char** argv)
{
  const double tau = argOr(argc, argv, "--tau", 2.0);
  const int block = static_cast<int>(argOr(argc, argv, "--block", 32));
  const int n = static_cast<int>(argOr(argc, argv, "--n", 1025));
  const double stepBlocks = argOr(argc, argv, "--step", 0.04);
  const int frames = static_cast<int>(argOr(argc, argv, "--frames", 120));
  const int every = static_cast<int>(argOr(argc, argv, "--every", 10));
  if (!(tau > 0.0) || block < 4 || n < 3 || frames < 1 || every < 1)
  {
    std::fprintf(stderr, "measure_switch_mismatch: bad arguments (see the file's header)\n");
    return 2;
  }
  gmm::Engine e;
  const std::string err = e.setHeightfield(gmm::makeSyntheticTerrain(n, n, 30.0, 1), block, 0);
  if (!err.empty())
  {
    std::fprintf(stderr, "measure_switch_mismatch: %s\n", err.c_str());
    return 2;
  }
  e.setMorphRange(gmm::kDefaultMorphRange);
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  const gmm::ErrorTable& table = e.errorTable();
  const double top = gmmtest::highestSample(hf);
  std::vector<double> rulePx, nestedPx, neighbourPx;
  // A block's samples as it draws them at `cfg` (glided edges' on their polylines).
  auto baseHeights = [&](int block, const gmm::BlockConfig& cfg) {
    const int c0 = block % qt.blockCols, r0 = block / qt.blockCols;
    const int bi0 = qt.colStart[c0], bi1 = qt.colStart[c0 + 1], bj0 = qt.rowStart[r0], bj1 = qt.rowStart[r0 + 1];
    return [&hf, bi0, bi1, bj0, bj1, cfg](int i, int jj) {
      return gmm::sideBaseHeight(hf, bi0, bi1, bj0, bj1, cfg.edgeLevel, i, jj);
    };
  };
  for (int f = 0; f < frames; f += every)
  {
    e.update(gmmtest::poppingFlightView(hf, top, block, stepBlocks, f), tau);
    std::vector<int8_t> levels = e.levels();
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      const int c = levels[b];
      if (c < 1 || qt.blockHasNodata[b])
      {
        continue;
      }
      gmm::MorphChain chain;
      const int links = gmm::morphChain(qt, b, chain);
      const int j = gmm::chainIndex(qt, b, c);
      if (j < 1 || j >= links || chain[j] != c || !qt.blockIsRingAt(b, chain[j - 1]))
      {
        continue;
      }
      const int a = chain[j - 1];
      const gmm::BlockConfig now = gmm::blockConfigOf(qt, levels, b);
      const double errorNow = gmm::blockCertifiedError(qt, table, b, now);
      if (!(errorNow > 0.0) || !std::isfinite(errorNow))
      {
        continue;
      }
      levels[b] = static_cast<int8_t>(a);
      const gmm::BlockConfig was = gmm::blockConfigOf(qt, levels, b);
      const std::vector<double> after = blockSurface(qt, b, now, baseHeights(b, now));
      std::array<int, 4> edgeTarget{ -1, -1, -1, -1 };
      for (int s = 0; s < 4; ++s)
      {
        if (was.edgeLevel[s] == a && !qt.sideAtFullResolution(b, s))
        {
          edgeTarget[s] = c;
        }
      }
      const std::vector<double> rule = blockSurface(
        qt, b, was,
        [&](int i, int jj) { return gmm::blockVertexTarget(hf, qt, b, c, edgeTarget, was.edgeLevel, i, jj); });
      const int i0 = qt.colStart[b % qt.blockCols], j0 = qt.rowStart[b / qt.blockCols], w = qt.blockWidth(b) + 1;
      const std::vector<double> nested =
        blockSurface(qt, b, was, [&](int i, int jj) { return after[static_cast<std::size_t>(jj - j0) * w + (i - i0)]; });
      rulePx.push_back(tau * largestGap(rule, after) / errorNow);
      nestedPx.push_back(tau * largestGap(nested, after) / errorNow);
      const std::array<int, 4> neighbour = qt.blockNeighbours(b);
      for (int s = 0; s < 4; ++s)
      {
        const int nb = neighbour[s];
        if (nb < 0 || was.edgeLevel[s] == now.edgeLevel[s] || levels[nb] < 0 || !qt.blockIsRingAt(nb, levels[nb]) ||
          qt.blockHasNodata[nb])
        {
          continue;
        }
        const gmm::BlockConfig nbWas = gmm::blockConfigOf(qt, levels, nb);
        levels[b] = static_cast<int8_t>(c);
        const gmm::BlockConfig nbNow = gmm::blockConfigOf(qt, levels, nb);
        levels[b] = static_cast<int8_t>(a);
        const double nbError = gmm::blockCertifiedError(qt, table, nb, nbNow);
        if (!(nbError > 0.0) || !std::isfinite(nbError))
        {
          continue;
        }
        std::array<int, 4> nbTarget{ -1, -1, -1, -1 };
        const int side = (s + 2) % 4;
        if (nbWas.edgeLevel[side] == a)
        {
          nbTarget[side] = c;
        }
        const std::vector<double> nbBefore = blockSurface(
          qt, nb, nbWas,
          [&](int i, int jj) { return gmm::blockVertexTarget(hf, qt, nb, -1, nbTarget, nbWas.edgeLevel, i, jj); });
        const std::vector<double> nbAfter = blockSurface(qt, nb, nbNow, baseHeights(nb, nbNow));
        neighbourPx.push_back(tau * largestGap(nbBefore, nbAfter) / nbError);
      }
      levels[b] = static_cast<int8_t>(c);
    }
  }
  std::printf("fractal %d^2, block %d, tau %g, every %d-th of %d frames: a switch's jump in px where the "
              "error just fits tau (tau M / E)\n",
    n, block, tau, every, frames);
  std::printf("| mismatch | switches | median px | 90th percentile | worst | over 0.5 px |\n|---|---|---|---|---|---|\n");
  report("rule (Morph.h's targets)", rulePx);
  report("nested (targets on the drawn level)", nestedPx);
  report("neighbour's strip", neighbourPx);
  return 0;
}
