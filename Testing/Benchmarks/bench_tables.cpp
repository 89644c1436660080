// Error table build and cached open (issue #11): what a terrain costs before its first
// frame, built with one thread and with all, and read back from the table cache.
//
//   build/Testing/Benchmarks/bench_tables                          # 4097^2
//   GEOMIPMAP_BENCH_MAX=16385 build/Testing/Benchmarks/bench_tables # adds 8193^2, 16385^2 (~3 GB)
//   GEOMIPMAP_BENCH_SINGLE=0 ...                                    # skip the one-thread builds
//
// DEM: synthetic terrain (gmm::makeSyntheticTerrain, 30 m, seed 42), the default block size
// (gmm::kDefaultBlockQuads; GEOMIPMAP_BENCH_BLOCK=N for another). Each
// figure is one run (seconds, wall clock) and the ratios are taken within the run, so the
// machine's load at that moment affects both sides alike. An open is buildTerrain over
// heights held elsewhere (as the VTK classes pass the image's array) with the table cache
// in a fresh directory: the first validates, builds the quadtree, hashes the heights,
// builds the table and saves it; the second reads it instead of building it.
#include "ErrorTable.h"
#include "SyntheticTerrain.h"
#include "Terrain.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <thread>

namespace
{
double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int envInt(const char* name, int fallback)
{
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

// A view of `hf`'s heights, as the VTK classes hand the image's array to the engine.
gmm::Heightfield sharedView(const gmm::Heightfield& hf)
{
  gmm::Heightfield v;
  v.nx = hf.nx;
  v.ny = hf.ny;
  v.dx = hf.dx;
  v.dy = hf.dy;
  v.external = hf.z.data();
  return v;
}
} // namespace

int main()
{
  const int maxSize = envInt("GEOMIPMAP_BENCH_MAX", 4097);
  const bool single = envInt("GEOMIPMAP_BENCH_SINGLE", 1) != 0;
  const int block = envInt("GEOMIPMAP_BENCH_BLOCK", gmm::kDefaultBlockQuads);
  const unsigned cores = std::thread::hardware_concurrency();
  const std::filesystem::path dir = std::filesystem::current_path() / "bench_tables_cache";
  std::printf("Block size %d quads.\n\n", block);
  std::printf("| DEM | table, 1 thread | table, %u threads | speed-up | first open (tables built "
              "and saved) | second open (of which hash) | first / second |\n"
              "|---|---|---|---|---|---|---|\n",
    cores);
  for (int n : { 4097, 8193, 16385 })
  {
    if (n > maxSize)
    {
      continue;
    }
    std::filesystem::remove_all(dir);
    const gmm::Heightfield hf = gmm::makeSyntheticTerrain(n, n, 30.0, 42);
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, block);
    double one = 0.0;
    if (single)
    {
      auto t0 = std::chrono::steady_clock::now();
      const gmm::ErrorTable t1 = gmm::buildErrorTable(hf, qt, 1);
      one = seconds(t0);
    }
    // The full first open with the cache: build with all threads, then save.
    gmm::TableCacheOptions cache;
    cache.directory = dir.string();
    std::shared_ptr<const gmm::Terrain> built, read;
    gmm::TableCacheReport first, second;
    auto t0 = std::chrono::steady_clock::now();
    const gmm::ErrorTable all = gmm::buildErrorTable(hf, qt, 0);
    const double allSeconds = seconds(t0);
    t0 = std::chrono::steady_clock::now();
    gmm::buildTerrain(sharedView(hf), block, 0, built, nullptr, cache, &first);
    const double firstOpen = seconds(t0);
    t0 = std::chrono::steady_clock::now();
    const std::string err = gmm::buildTerrain(sharedView(hf), block, 0, read, nullptr, cache, &second);
    const double cachedOpen = seconds(t0);
    if (!err.empty() || !first.written || !second.hit || read->table.ownError != all.ownError)
    {
      std::fprintf(stderr, "%d^2: cache did not give the built table (%s%s)\n", n, err.c_str(),
        second.problem.c_str());
      return 1;
    }
    char oneText[32] = "-", ratioText[32] = "-";
    if (single)
    {
      std::snprintf(oneText, sizeof oneText, "%.2f s", one);
      std::snprintf(ratioText, sizeof ratioText, "%.2fx", one / allSeconds);
    }
    std::printf("| %d² | %s | %.2f s | %s | %.2f s | %.3f s (%.3f s) | %.0fx |\n", n, oneText,
      allSeconds, ratioText, firstOpen, cachedOpen, second.hashSeconds, firstOpen / cachedOpen);
    std::fflush(stdout);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
