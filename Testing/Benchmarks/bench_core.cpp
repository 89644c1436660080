// Core engine benchmark (Google Benchmark): LOD update along a deterministic low-altitude
// flight versus full-resolution index generation, and a block-size sweep.
//
//   build-c/Testing/Benchmarks/bench_core                          # 1025^2 and 4097^2
//   GEOMIPMAP_BENCH_MAX=16385 build-c/Testing/Benchmarks/bench_core # adds 16385^2 (~1 GB)
//   GEOMIPMAP_BENCH_MAX=32769 ...                                  # adds 32769^2 (~5.5 GB; the
//     largest power-of-two-plus-one size the engine takes: 65537^2 has more samples than 32-bit
//     indices reach). No full-resolution index list there: it would be 25.8 GB.
//   GEOMIPMAP_BENCH_THREADS=1 ...                                  # table build threads (0 = all)
//
// BM_LodFlightFar20km: the same flight with the far plane at 20 km.
// BM_BudgetFlight / BM_BudgetFlightVarying: the mapper's per-frame work in a budgeted frame
// (runBudgetFlight below), the first kBudgetFlightFrames frames of the flight.
// BM_BlockSizeSweep4097 / BM_BlockSizeSweepMapperDefault4097: the whole-DEM flight at 4097^2
// for leaf sizes 16 .. 256, engine default and mapper default.
// BM_LodJumpsMapperDefault: the mapper default's frame when the camera jumps (runJumps).
// BM_LodFlightMapperDefault: the whole-DEM flight with the CPU work the mapper does per frame
// by default: Engine::update on geomorphing's level path (kDefaultMorphRange) and
// computeMorph over the drawn blocks (the mapper draws the index arena: no concatenation);
// GEOMIPMAP_BENCH_MERGE_ON_PATH=0 or 1 sets the mapper's SetGeomorphMerges (Engine::setMergeOnPath;
// default the mapper's),
// GEOMIPMAP_BENCH_MORPH_RANGE=R sets its SetGeomorphRange (default kDefaultMorphRange).
// Scene: synthetic terrain (gmm::makeSyntheticTerrain, 30 m spacing, seed 42), camera flying
// a straight diagonal line from 30 % of the diagonal at 5 m per frame, 200 m above the highest
// ground under/just ahead of it, looking forward and 15 degrees down, fov 60, 1280 x 720,
// tau = 1 px, the default block size (gmm::kDefaultBlockQuads; GEOMIPMAP_BENCH_BLOCK=N for
// another) unless swept. Each benchmark iteration is one frame, single thread; the flight
// loops after kFlightFrames frames. Each frame is gmm::FrameDriver's, as the mapper runs it.
// Counters: frame_us, the whole iteration (engine default: the frame without geomorphing,
// cull + select + tessellate, then Engine::indices(), the concatenated list the filter
// outputs; mapper default: the frame with geomorphing's level path and factors); update_us,
// the FrameDriver's frame alone (without geomorphing, the mapper's: it draws the index
// arena, no list).
// Concatenating was more than half the engine default's frame at 4097^2 (session 16).
#include "BenchFlight.h"
#include "Engine.h"
#include "Frame.h"
#include "SyntheticTerrain.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace
{
constexpr double kSpacing = 30.0;
constexpr int kFlightFrames = 2000;
constexpr double kStep = 5.0;      // metres per frame
constexpr int kBudgetFlightFrames = 400; // frames of BM_BudgetFlight (from the flight's start)
// Largest DEM whose full-resolution index list is built (16385^2: 6.4 GB of indices).
constexpr int kMaxFullResolutionSize = 16385;

double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int envInt(const char* name, int fallback)
{
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

struct Scene
{
  std::unique_ptr<gmm::Engine> engine;
  std::vector<gmm::View> flight;
  double generateSeconds = 0, tableSeconds = 0;
  double fullResSeconds = 0; // one full-resolution index generation
  std::size_t fullResTriangles = 0;
};

// Full-resolution index generation: the obvious alternative to LOD.
std::size_t fullResolutionIndices(const gmm::Heightfield& hf, std::vector<uint32_t>& out)
{
  const std::size_t tris = 2 * static_cast<std::size_t>(hf.nx - 1) * (hf.ny - 1);
  out.resize(3 * tris);
  uint32_t* p = out.data();
  const uint32_t nx = static_cast<uint32_t>(hf.nx);
  const bool flip = hf.mirrored();
  for (uint32_t j = 0; j + 1 < static_cast<uint32_t>(hf.ny); ++j)
    for (uint32_t i = 0; i + 1 < nx; ++i)
    {
      const uint32_t a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      if (!flip)
      {
        *p++ = a; *p++ = b; *p++ = c;
        *p++ = a; *p++ = c; *p++ = d;
      }
      else
      {
        *p++ = a; *p++ = c; *p++ = b;
        *p++ = a; *p++ = d; *p++ = c;
      }
    }
  return tris;
}

Scene& scene(int size, int blockQuads)
{
  static std::map<std::pair<int, int>, Scene> cache;
  auto key = std::make_pair(size, blockQuads);
  auto it = cache.find(key);
  if (it != cache.end())
    return it->second;
  // keep memory bounded: one scene at a time
  cache.clear();
  Scene& s = cache[key];
  const int threads = envInt("GEOMIPMAP_BENCH_THREADS", 0);
  auto t0 = std::chrono::steady_clock::now();
  gmm::Heightfield hf = gmm::makeSyntheticTerrain(size, size, kSpacing, 42, 1500.0, threads);
  s.generateSeconds = seconds(t0);
  if (size <= kMaxFullResolutionSize)
  {
    std::vector<uint32_t> full;
    t0 = std::chrono::steady_clock::now();
    s.fullResTriangles = fullResolutionIndices(hf, full);
    benchmark::DoNotOptimize(full.data());
    s.fullResSeconds = seconds(t0);
  }
  s.flight = gmmbench::makeFlight(hf, kFlightFrames, kStep);
  s.engine = std::make_unique<gmm::Engine>();
  t0 = std::chrono::steady_clock::now();
  const std::string err = s.engine->setHeightfield(std::move(hf), blockQuads, threads);
  s.tableSeconds = seconds(t0);
  if (!err.empty())
    std::fprintf(stderr, "setHeightfield failed: %s\n", err.c_str());
  std::fprintf(stderr, "# %d^2 block %d: terrain %.2f s, quadtree + error table %.2f s, full-res indices %.3f s\n",
    size, blockQuads, s.generateSeconds, s.tableSeconds, s.fullResSeconds);
  return s;
}

// farDistance: 0 keeps the flight's 10^6 m (the whole DEM ahead is in view); else the far
// plane of a realistic viewer (terrain beyond it is left to fog or a horizon).
void runFlight(benchmark::State& state, int size, int blockQuads, double farDistance = 0.0,
  bool mapperDefault = false)
{
  Scene& s = scene(size, blockQuads);
  std::vector<gmm::View> flight = s.flight; // the scene is shared by the other registrations
  if (farDistance > 0.0)
    for (gmm::View& v : flight)
      v.farDistance = farDistance;
  // The frame as the mapper runs it (gmm::FrameDriver) on the scene's terrain: geomorphing's
  // level path and factors for the mapper default, the selection alone for the engine's.
  gmm::FrameDriver driver;
  driver.setTerrain(s.engine->terrain());
  gmm::FrameSettings settings;
  settings.pixelError = 1.0;
  settings.geomorphing = mapperDefault;
  settings.geomorphMerges =
    mapperDefault && envInt("GEOMIPMAP_BENCH_MERGE_ON_PATH", gmm::FrameSettings().geomorphMerges ? 1 : 0) != 0;
  if (const char* range = std::getenv("GEOMIPMAP_BENCH_MORPH_RANGE"); range && *range)
    settings.geomorphRange = std::atof(range);
  const gmm::Engine& e = driver.engine();
  std::size_t frame = 0, triangles = 0, reused = 0, visible = 0, regenFrames = 0;
  double maxErr = 0, totalUs = 0, regenUs = 0, updateUs = 0;
  // Warm up one frame (with its morph when measured) so that the first measured frame is
  // not a cold start: the first computeMorph allocates its cache, a one-off cost that 2000
  // frames would otherwise spread over the mean.
  driver.update(flight[0], settings);
  for (auto _ : state)
  {
    const auto t0 = std::chrono::steady_clock::now();
    const gmm::FrameStats& st = driver.update(flight[frame % flight.size()], settings).stats;
    updateUs += seconds(t0) * 1e6;
    if (mapperDefault)
    {
      benchmark::DoNotOptimize(driver.morph().blockT.data());
    }
    else
    {
      benchmark::DoNotOptimize(e.indices().data());
    }
    const double us = seconds(t0) * 1e6;
    totalUs += us;
    if (!st.reused)
    {
      regenUs += us;
      ++regenFrames;
    }
    triangles += st.triangles;
    reused += st.reused ? 1 : 0;
    visible += st.visibleBlocks;
    maxErr = std::max(maxErr, st.maxScreenError);
    ++frame;
  }
  const double n = static_cast<double>(frame);
  state.counters["frame_us"] = totalUs / n;
  state.counters["update_us"] = updateUs / n;
  state.counters["regen_frame_us"] = regenFrames ? regenUs / regenFrames : 0.0;
  state.counters["triangles"] = triangles / n;
  state.counters["tris_per_us"] = triangles / totalUs;
  state.counters["reused_frac"] = reused / n;
  state.counters["visible_blocks"] = visible / n;
  state.counters["max_px_err"] = maxErr;
  state.counters["table_build_s"] = s.tableSeconds;
  state.counters["fullres_ms"] = s.fullResSeconds * 1e3;
  state.counters["fullres_tris"] = static_cast<double>(s.fullResTriangles);
}

// BM_BudgetFlight: the mapper's CPU work per frame in a budgeted frame (issue #14): the same
// flight with tau 0 and a triangle budget, each frame's search started at the previous
// frame's tau (FrameSettings::budgetWarmStart, as the mapper does), and the morph factors
// within the frame's error (gmm::morphErrorBudget), as gmm::FrameDriver runs them with
// geomorphing on (budgeted frames follow no level path). The budget is held, or (`varying`)
// moved by +-15 % every 8 frames as a frame-rate controller moves it. Counters: selections
// a frame (the search's trials) and the certified error the selection reached.
void runBudgetFlight(benchmark::State& state, int size, int blockQuads, std::size_t budget, bool varying)
{
  Scene& s = scene(size, blockQuads);
  gmm::FrameDriver driver;
  driver.setTerrain(s.engine->terrain());
  gmm::FrameSettings settings;
  settings.pixelError = 0.0;
  settings.budgetWarmStart = true;
  std::size_t frame = 0, triangles = 0, trials = 0;
  double totalUs = 0, errorSum = 0;
  auto budgetOf = [&](std::size_t f) {
    if (!varying)
      return budget;
    const double scale[] = { 1.0, 1.15, 1.0, 0.85 };
    return static_cast<std::size_t>(budget * scale[(f / 8) % 4]);
  };
  settings.triangleBudget = budgetOf(0);
  driver.update(s.flight[0], settings); // warm-up, as runFlight
  for (auto _ : state)
  {
    const auto t0 = std::chrono::steady_clock::now();
    settings.triangleBudget = budgetOf(frame);
    const gmm::Frame& f = driver.update(s.flight[frame % s.flight.size()], settings);
    benchmark::DoNotOptimize(driver.morph().blockT.data());
    totalUs += seconds(t0) * 1e6;
    triangles += f.stats.triangles;
    trials += static_cast<std::size_t>(f.stats.budgetTrials);
    errorSum += f.selectionScreenError;
    ++frame;
  }
  const double n = static_cast<double>(frame);
  state.counters["frame_us"] = totalUs / n;
  state.counters["triangles"] = triangles / n;
  state.counters["selections"] = trials / n;
  state.counters["certified_px_mean"] = errorSum / n;
}

// BM_LodJumpsMapperDefault: the mapper default's frame when the camera jumps: twelve views
// 30 degrees apart on an orbit around the DEM (gmmbench::makeOrbitJumps, as geomipmap-bench's
// orbit at 12 frames), one view a frame, so that nearly every drawn block changes its
// configuration every frame. Each iteration draws the view with three frame drivers, each
// timed alone: the mapper default (measuring at most
// gmm::kDefaultMorphMeasureSamples a frame, Morph.h), the same measuring every part, and
// without geomorphing. Counters: jump_us (the default), measure_all_us and
// no_geomorph_us, and the ratios measure_all_x = measure_all_us / jump_us and
// geomorph_x = jump_us / no_geomorph_us, all from the same run.
void runJumps(benchmark::State& state, int size, int blockQuads)
{
  Scene& s = scene(size, blockQuads);
  const std::vector<gmm::View> views = gmmbench::makeOrbitJumps(s.engine->heightfield(), 12);
  gmm::FrameSettings byDefault, measureAll, noGeomorph;
  measureAll.geomorphMeasureSamples = 0;
  noGeomorph.geomorphing = false;
  const gmm::FrameSettings* settings[3] = { &byDefault, &measureAll, &noGeomorph };
  gmm::FrameDriver drivers[3];
  double us[3] = { 0, 0, 0 }, triangles = 0;
  for (int d = 0; d < 3; ++d)
  {
    drivers[d].setTerrain(s.engine->terrain());
    drivers[d].update(views[0], *settings[d]); // the first frame measures everything
  }
  std::size_t frame = 1;
  for (auto _ : state)
  {
    const gmm::View& v = views[frame % views.size()];
    for (int d = 0; d < 3; ++d)
    {
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(drivers[d].update(v, *settings[d]).stats.triangles);
      us[d] += seconds(t0) * 1e6;
    }
    triangles += drivers[0].frame().stats.triangles;
    ++frame;
  }
  const double n = static_cast<double>(frame - 1);
  state.counters["jump_us"] = us[0] / n;
  state.counters["measure_all_us"] = us[1] / n;
  state.counters["no_geomorph_us"] = us[2] / n;
  state.counters["measure_all_x"] = us[1] / us[0];
  state.counters["geomorph_x"] = us[0] / us[2];
  state.counters["triangles"] = triangles / n;
}

void BM_FullResolutionIndices(benchmark::State& state, int blockQuads)
{
  const int size = static_cast<int>(state.range(0));
  Scene& s = scene(size, blockQuads); // the flights' scene: the same DEM, not built again
  std::vector<uint32_t> out;
  std::size_t tris = 0;
  for (auto _ : state)
  {
    tris = fullResolutionIndices(s.engine->heightfield(), out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["triangles"] = static_cast<double>(tris);
  state.counters["ms_per_generation"] = benchmark::Counter(
    state.iterations() * 1e-3, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
} // namespace

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  const int maxSize = envInt("GEOMIPMAP_BENCH_MAX", 4097);
  const int block = envInt("GEOMIPMAP_BENCH_BLOCK", gmm::kDefaultBlockQuads);
  std::vector<int> sizes;
  for (int s : { 1025, 4097, 16385, 32769 })
    if (s <= maxSize)
      sizes.push_back(s);
  // Per size: the LOD flight, then the full-resolution alternative on the same DEM (the
  // scene cache keeps one DEM at a time, so order the registrations by size).
  for (int s : sizes)
  {
    benchmark::RegisterBenchmark(("BM_LodFlight/" + std::to_string(s)).c_str(),
      [s, block](benchmark::State& st) { runFlight(st, s, block); })
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime()
      ->MinTime(2.0);
    benchmark::RegisterBenchmark(("BM_LodFlightFar20km/" + std::to_string(s)).c_str(),
      [s, block](benchmark::State& st) { runFlight(st, s, block, 20000.0); })
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime()
      ->MinTime(2.0);
    benchmark::RegisterBenchmark(("BM_LodFlightMapperDefault/" + std::to_string(s)).c_str(),
      [s, block](benchmark::State& st) { runFlight(st, s, block, 0.0, true); })
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime()
      ->MinTime(2.0);
    benchmark::RegisterBenchmark(("BM_LodJumpsMapperDefault/" + std::to_string(s)).c_str(),
      [s, block](benchmark::State& st) { runJumps(st, s, block); })
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime()
      ->Iterations(48); // four times round the orbit
    for (bool varying : { false, true })
      benchmark::RegisterBenchmark(
        ((varying ? "BM_BudgetFlightVarying/" : "BM_BudgetFlight/") + std::to_string(s)).c_str(),
        [s, block, varying](benchmark::State& st) { runBudgetFlight(st, s, block, 100000, varying); })
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime()
        ->Iterations(kBudgetFlightFrames); // the same frames in every run: errors compare
    if (s > kMaxFullResolutionSize)
      continue;
    benchmark::RegisterBenchmark(("BM_FullResolutionIndices/" + std::to_string(s)).c_str(),
      [block](benchmark::State& st) { BM_FullResolutionIndices(st, block); })
      ->Arg(s)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(s >= 16385 ? 1 : 3);
  }
  if (envInt("GEOMIPMAP_BENCH_SWEEP", 1))
    for (int bq : { 16, 32, 64, 128, 256 })
    {
      benchmark::RegisterBenchmark(("BM_BlockSizeSweep4097/" + std::to_string(bq)).c_str(),
        [bq](benchmark::State& st) { runFlight(st, 4097, bq); })
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime()
        ->MinTime(2.0);
      benchmark::RegisterBenchmark(("BM_BlockSizeSweepMapperDefault4097/" + std::to_string(bq)).c_str(),
        [bq](benchmark::State& st) { runFlight(st, 4097, bq, 0.0, true); })
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime()
        ->MinTime(2.0);
    }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
