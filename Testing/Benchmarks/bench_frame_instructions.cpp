// The mapper default's per-frame CPU work along bench_core's flight, for counting under
// callgrind, and a hash of every frame's result, for comparing two builds.
//
// Why: on this shared VM the speed of one benchmark run moves by 2x or more within minutes,
// which hides changes of 10 - 20 %. Instructions counted by callgrind do not move: the same
// build gives the same count. They are not time (a logarithm and a division differ in
// latency, a cache miss costs no instruction), so a change measured this way is also timed
// when the machine allows (Documentation/benchmarks-core.md, session 18).
//
//   valgrind --tool=callgrind --instr-atstart=no build/Testing/Benchmarks/bench_frame_instructions 4097
//   callgrind_annotate callgrind.out.<pid> | head -40
//
// Arguments: SIZE (4097) FRAMES (100) METRES_PER_FRAME (20) MAPPER (1: the mapper's default
// frame, gmm::FrameDriver with geomorphing's level path and factors; 0: without geomorphing,
// the engine's update alone). Scene as bench_core's (synthetic terrain, seed 42, 30 m spacing, its flight from
// BenchFlight.h, tau 1, the default block size), terrain and tables on one thread. Only the frames are counted
// (callgrind's instrumentation starts after the first frame, which allocates the caches).
// Printed: the triangles summed over the frames and a hash of every frame's levels, merged
// nodes, morph factors and certified bounds: a change that claims the same selections must
// leave it as it was.
#include "BenchFlight.h"
#include "Frame.h"
#include "SyntheticTerrain.h"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#endif
#endif
#ifndef CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace
{
uint64_t mix(uint64_t h, uint64_t v)
{
  return h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
}

uint64_t bitsOf(double d)
{
  uint64_t u = 0;
  std::memcpy(&u, &d, sizeof u);
  return u;
}
} // namespace

int main(int argc, char** argv)
{
  const int size = argc > 1 ? std::atoi(argv[1]) : 4097;
  const int frames = argc > 2 ? std::atoi(argv[2]) : 100;
  const double step = argc > 3 ? std::atof(argv[3]) : 20.0;
  const bool mapper = argc > 4 ? std::atoi(argv[4]) != 0 : true;
  if (size < 2 || frames < 1 || !(step >= 0.0))
  {
    std::fprintf(stderr, "usage: %s [SIZE >= 2] [FRAMES >= 1] [METRES_PER_FRAME >= 0] [MAPPER 0|1]\n", argv[0]);
    return 2;
  }
  gmm::Heightfield hf = gmm::makeSyntheticTerrain(size, size, 30.0, 42, 1500.0, 1);
  // frames + 1 views: the first is the warm-up.
  const std::vector<gmm::View> path = gmmbench::makeFlight(hf, frames + 1, step);
  std::shared_ptr<const gmm::Terrain> terrain;
  const std::string err = gmm::buildTerrain(std::move(hf), gmm::kDefaultBlockQuads, 1, terrain);
  if (!err.empty())
  {
    std::fprintf(stderr, "buildTerrain failed: %s\n", err.c_str());
    return 1;
  }
  gmm::FrameDriver driver;
  driver.setTerrain(terrain);
  gmm::FrameSettings settings;
  settings.geomorphing = mapper;
  const gmm::Engine& engine = driver.engine();
  const gmm::MorphFrame& morph = driver.morph();
  uint64_t hash = 0;
  long long triangles = 0;
  for (int f = 0; f <= frames; ++f)
  {
    if (f == 1)
    {
      CALLGRIND_START_INSTRUMENTATION;
    }
    const gmm::Frame& frame = driver.update(path[f], settings);
    const gmm::FrameStats& st = frame.stats;
    if (f == 0)
    {
      continue;
    }
    triangles += static_cast<long long>(st.triangles);
    for (int b : engine.drawnBlocks())
    {
      hash = mix(hash, static_cast<uint64_t>(b) * 64 + static_cast<uint64_t>(engine.levels()[b] + 2));
      hash = mix(hash, mapper ? bitsOf(morph.blockT[b]) : 0);
    }
    for (int n : engine.mergedNodeList())
    {
      hash = mix(hash, static_cast<uint64_t>(n));
    }
    hash = mix(hash, bitsOf(frame.selectionScreenError));
    hash = mix(hash, mapper ? bitsOf(morph.maxBoundPixels) : 0);
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  std::printf("%d^2, %d frames, %g m a frame, %s: %lld triangles, hash %016llx\n", size, frames, step,
    mapper ? "mapper default" : "engine update", triangles, static_cast<unsigned long long>(hash));
  return 0;
}
