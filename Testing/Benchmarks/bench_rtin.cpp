// Triangle counts of GeoMipMapping against an RTIN reference (issue #11's yardstick).
//
//   build/Testing/Benchmarks/bench_rtin              # tables below (about 2 minutes)
//   build/Testing/Benchmarks/bench_rtin --validate   # RTIN counts == martini's on Fuji (a test)
//   build/Testing/Benchmarks/bench_rtin --view-independent  # table 1 only (seconds)
//   GEOMIPMAP_BENCH_SYNTH=0 ...                      # without the 4097^2 synthetic DEM
//   GEOMIPMAP_BENCH_MERGED=0 ...                     # ours block by block (no merged nodes)
//
// 1. View-independent, Fuji tile (../shared/data/fuji_terrain_rgb.png, martini's fixture):
//    triangles and time of the RTIN (martini's algorithm, RtinReference.h, on the 513 grid
//    martini builds: the tile plus a backfilled edge) and of our engine's
//    Engine::updateForError on the 512 x 512 tile, for several block sizes. Times are the
//    best of 5: the RTIN's count only (martini's getMesh also writes the mesh, so this
//    flatters it), ours the whole selection and index list from a fresh frame state.
// 2. View-dependent, along flights: for each DEM and flight, frames at 1280 x 720 with a 60
//    degree field of view, the RTIN's count (Lindstrom-Pascucci nested spheres) against
//    ours (Engine::update, certified metric) at tau = 1 and 2 px; printed: the mean, min and
//    max over the frames of ours / RTIN.
// Columns are block sizes as set (SetBlockSize); the leaves are a power of two within each
// (Quadtree.h, bandWidth), printed beside it: on the 512^2 Fuji tile, half the block size.
// DEMs: the Fuji tile (62 m spacing), Puget Sound 1025^2 (ps_height_1k.png, 160 m) and a
// 4097^2 synthetic (gmm::makeSyntheticTerrain, 30 m, seed 42). RTIN grids must be
// (2^k + 1)^2, which all three are (Fuji after martini's backfill).
#include "Engine.h"
#include "RtinReference.h"
#include "SyntheticTerrain.h"
#include "../Cxx/GeoMipMapTestData.h"

#ifdef GEOMIPMAP_BENCH_HAVE_OIIO
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace
{

double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Keeps a result alive so that the timed work is not optimised away.
void benchmark_keep(const void* p)
{
  static const void* volatile sink;
  sink = p;
}

// The published counts of martini on its Fuji fixture (the table, measured with
// martini itself): maxError (m) -> triangles.
struct MartiniCount
{
  double maxError;
  std::size_t triangles;
};
constexpr MartiniCount kMartiniFuji[] = { { 30.0, 19086 }, { 10.0, 89513 }, { 5.0, 187985 } };

// Reads an image's first channels as float, row 0 = the file's top row. "" or the reason.
std::string readImage(const std::string& path, int& w, int& h, int& channels, std::vector<float>& px)
{
#ifdef GEOMIPMAP_BENCH_HAVE_OIIO
  auto in = OIIO::ImageInput::open(path);
  if (!in)
  {
    return "cannot open " + path + ": " + OIIO::geterror();
  }
  const OIIO::ImageSpec& spec = in->spec();
  w = spec.width;
  h = spec.height;
  channels = spec.nchannels;
  px.resize(static_cast<std::size_t>(w) * h * channels);
  // UINT8 / UINT16 read as float keep their integer values only through an explicit
  // unsigned type, so read in the file's type and convert here.
  if (spec.format == OIIO::TypeDesc::UINT16)
  {
    std::vector<uint16_t> raw(px.size());
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT16, raw.data()))
      return "cannot read " + path + ": " + in->geterror();
    std::copy(raw.begin(), raw.end(), px.begin());
  }
  else
  {
    std::vector<uint8_t> raw(px.size());
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data()))
      return "cannot read " + path + ": " + in->geterror();
    std::copy(raw.begin(), raw.end(), px.begin());
  }
  return "";
#else
  (void)path, (void)w, (void)h, (void)channels, (void)px;
  return "built without OpenImageIO";
#endif
}

// Fuji terrain-RGB tile as martini's example decodes it: the 512 x 512 tile (`tile`) and
// the 513 grid with the last row and column repeated (`grid`).
std::string loadFuji(const std::string& path, rtin::Grid& grid, gmm::Heightfield& tile)
{
  int w = 0, h = 0, ch = 0;
  std::vector<float> px;
  std::string err = readImage(path, w, h, ch, px);
  if (!err.empty())
    return err;
  if (w != 512 || h != 512 || ch < 3)
    return path + ": expected a 512 x 512 RGB(A) tile";
  const double spacing = 62.3; // m: 0.3516 degrees of longitude over 512 pixels at 35.3 N
  grid.size = w + 1;
  grid.dx = grid.dy = spacing;
  grid.h.assign(static_cast<std::size_t>(grid.size) * grid.size, 0.0f);
  tile.nx = w;
  tile.ny = h;
  tile.dx = tile.dy = spacing;
  tile.z.resize(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      const float* p = &px[(static_cast<std::size_t>(y) * w + x) * ch];
      const float z = static_cast<float>((p[0] * 65536.0 + p[1] * 256.0 + p[2]) / 10.0 - 10000.0);
      grid.h[static_cast<std::size_t>(y) * grid.size + x] = z;
      tile.z[static_cast<std::size_t>(y) * w + x] = z;
    }
  const int s = grid.size;
  for (int x = 0; x < s - 1; ++x)
    grid.h[static_cast<std::size_t>(s - 1) * s + x] = grid.h[static_cast<std::size_t>(s - 2) * s + x];
  for (int y = 0; y < s; ++y)
    grid.h[static_cast<std::size_t>(y) * s + s - 1] = grid.h[static_cast<std::size_t>(y) * s + s - 2];
  return "";
}

// Puget Sound: 16-bit grey, 0.1 m units, 160 m spacing (../shared/data/README.md).
std::string loadPugetSound(const std::string& path, rtin::Grid& grid)
{
  int w = 0, h = 0, ch = 0;
  std::vector<float> px;
  std::string err = readImage(path, w, h, ch, px);
  if (!err.empty())
    return err;
  if (w != 1025 || h != 1025)
    return path + ": expected 1025 x 1025 samples";
  grid.size = w;
  grid.dx = grid.dy = 160.0;
  grid.h.resize(static_cast<std::size_t>(w) * h);
  for (std::size_t k = 0; k < grid.h.size(); ++k)
    grid.h[k] = static_cast<float>(px[k * ch] * 0.1);
  return "";
}

// Our engine as the benchmark runs it: merged nodes unless GEOMIPMAP_BENCH_MERGED=0.
std::unique_ptr<gmm::Engine> makeEngine(const gmm::Heightfield& hf, int blockQuads)
{
  auto e = std::make_unique<gmm::Engine>();
  const std::string err = e->setHeightfield(hf, blockQuads, 0);
  if (!err.empty())
    std::printf("engine: %s\n", err.c_str());
  const char* merged = std::getenv("GEOMIPMAP_BENCH_MERGED");
  e->setMergedNodes(!(merged && std::strcmp(merged, "0") == 0));
  return e;
}

gmm::Heightfield heightfieldOf(const rtin::Grid& g)
{
  gmm::Heightfield hf;
  hf.nx = hf.ny = g.size;
  hf.dx = g.dx;
  hf.dy = g.dy;
  hf.z = g.h;
  return hf;
}

// Three low flights across the DEM (diagonal, west-east, south-north), `frames` views each:
// 10 samples' spacing above the highest ground within a few samples ahead, looking along
// the track and 15 degrees down.
std::vector<std::vector<gmm::View>> makeFlights(const rtin::Grid& g, int frames)
{
  const double ext = (g.size - 1) * g.dx;
  const double dirs[3][2] = { { std::sqrt(0.5), std::sqrt(0.5) }, { 1.0, 0.0 }, { 0.0, 1.0 } };
  const double starts[3][2] = { { 0.2, 0.2 }, { 0.15, 0.55 }, { 0.45, 0.15 } };
  const double pitch = -15.0 * M_PI / 180.0;
  auto ground = [&](double x, double y) {
    const int i = std::clamp(static_cast<int>(std::lround(x / g.dx)), 0, g.size - 1);
    const int j = std::clamp(static_cast<int>(std::lround(y / g.dy)), 0, g.size - 1);
    return static_cast<double>(g.h[static_cast<std::size_t>(j) * g.size + i]);
  };
  std::vector<std::vector<gmm::View>> flights(3);
  for (int f = 0; f < 3; ++f)
  {
    for (int k = 0; k < frames; ++k)
    {
      const double along = 0.5 * ext * k / std::max(1, frames - 1);
      const double x = starts[f][0] * ext + dirs[f][0] * along;
      const double y = starts[f][1] * ext + dirs[f][1] * along;
      double z = -1e30;
      for (double a = -3 * g.dx; a <= 20 * g.dx; a += g.dx)
        z = std::max(z, ground(x + dirs[f][0] * a, y + dirs[f][1] * a));
      gmm::View v;
      v.eye = { x, y, z + 10 * g.dx };
      v.forward = { dirs[f][0] * std::cos(pitch), dirs[f][1] * std::cos(pitch), std::sin(pitch) };
      v.up = { 0, 0, 1 };
      v.fovYDegrees = 60;
      v.viewportWidth = 1280;
      v.viewportHeight = 720;
      v.nearDistance = 1.0;
      v.farDistance = 4 * ext;
      flights[f].push_back(v);
    }
  }
  return flights;
}

rtin::Camera cameraOf(const gmm::View& v)
{
  rtin::Camera c;
  c.eye = v.eye;
  c.planes = gmm::frustumOf(v);
  c.pixelsPerUnit = gmm::pixelsPerUnit(v);
  return c;
}

int validate()
{
  std::string path;
  int code = 0;
  if (!gmmtest::DataFile("fuji_terrain_rgb.png", path, code))
    return code == gmmtest::SkipReturnCode ? 77 : code;
  rtin::Grid grid;
  gmm::Heightfield tile;
  const std::string err = loadFuji(path, grid, tile);
  if (!err.empty())
  {
    std::printf("FAIL: %s\n", err.c_str());
    return 1;
  }
  rtin::Mesher mesher(grid);
  bool ok = true;
  for (const MartiniCount& m : kMartiniFuji)
  {
    const std::size_t n = mesher.countForError(m.maxError);
    std::printf("max error %5.1f m: RTIN %zu triangles, martini %zu  %s\n", m.maxError, n,
      m.triangles, n == m.triangles ? "ok" : "MISMATCH");
    ok = ok && n == m.triangles;
  }
  // The view-dependent criterion with every vertex in view and at one distance D reduces
  // to error > tau * D / f: the view-independent mesh. An eye 1e15 m above the tile puts
  // every vertex's |eye - p| - r within 1e-10 of D, and tau puts the threshold halfway to
  // the next float above maxError, so no stored error falls between the two criteria.
  rtin::Camera far;
  for (auto& p : far.planes)
    p = glm::dvec4(0, 0, 0, 1); // always inside
  const double D = 1e15;
  far.eye = glm::dvec3(0.5 * 512 * grid.dx, 0.5 * 512 * grid.dy, D);
  far.pixelsPerUnit = 1.0;
  for (const MartiniCount& m : kMartiniFuji)
  {
    const float e = static_cast<float>(m.maxError);
    const double threshold = 0.5 * (double(e) + double(std::nextafter(e, HUGE_VALF)));
    const std::size_t n = mesher.countForView(far, threshold / D);
    std::printf("view-dependent, every vertex at one distance, %5.1f m: %zu  %s\n", m.maxError,
      n, n == m.triangles ? "ok" : "MISMATCH");
    ok = ok && n == m.triangles;
  }
  return ok ? 0 : 1;
}

void viewIndependentTable(const rtin::Grid& grid, const gmm::Heightfield& tile)
{
  std::printf("\n## View-independent, Fuji tile\n\n");
  auto t0 = std::chrono::steady_clock::now();
  rtin::Mesher mesher(grid);
  const double build = seconds(t0);
  std::printf("RTIN error build (513^2): %.1f ms\n\n", build * 1e3);
  const int blocks[] = { 64, 32, 16, 8, 4 };
  // Block sizes as set; the leaves are bandWidth's power of two (511 quads: half of it).
  std::printf("| max error | RTIN (martini) |");
  for (int b : blocks)
    std::printf(" ours b%d (leaves %d) |", b, gmm::bandWidth(tile.nx - 1, b));
  std::printf("\n|---|---|---|---|---|---|---|\n");
  std::vector<std::unique_ptr<gmm::Engine>> engines;
  for (int b : blocks)
    engines.push_back(makeEngine(tile, b));
  for (const MartiniCount& m : kMartiniFuji)
  {
    std::size_t n = 0;
    double tr = 1e300;
    for (int rep = 0; rep < 5; ++rep)
    {
      t0 = std::chrono::steady_clock::now();
      n = mesher.countForError(m.maxError);
      tr = std::min(tr, seconds(t0));
    }
    std::printf("| %.0f m | %zu (%.2f ms count) |", m.maxError, n, tr * 1e3);
    for (auto& e : engines)
    {
      // From scratch (a fresh frame state on the same tables, as martini's getMesh starts
      // from its tile), the index list included; the best of 5 on this shared machine.
      const std::shared_ptr<const gmm::Terrain> terrain = e->terrain();
      std::size_t ours = 0;
      double best = 1e300;
      for (int rep = 0; rep < 5; ++rep)
      {
        e->setTerrain(terrain);
        t0 = std::chrono::steady_clock::now();
        ours = e->updateForError(m.maxError).triangles;
        benchmark_keep(e->indices().data());
        best = std::min(best, seconds(t0));
      }
      std::printf(" %zu (%.1fx, %.2f ms) |", ours, double(ours) / n, best * 1e3);
    }
    std::printf("\n");
  }
}

void flightTable(const char* name, const rtin::Grid& grid, int frames)
{
  const gmm::Heightfield hf = heightfieldOf(grid);
  auto t0 = std::chrono::steady_clock::now();
  rtin::Mesher mesher(grid);
  std::printf("\n## %s (%d^2), %d frames per flight; RTIN build %.2f s\n\n", name, grid.size,
    frames, seconds(t0));
  const int blocks[] = { 64, 32, 16, 8 };
  std::vector<std::unique_ptr<gmm::Engine>> engines;
  for (int b : blocks)
    engines.push_back(makeEngine(hf, b));
  const auto flights = makeFlights(grid, frames);
  std::printf("| flight | tau | RTIN tris (mean) |");
  for (int b : blocks)
    std::printf(" ours/RTIN b%d (leaves %d) |", b, gmm::bandWidth(hf.nx - 1, b));
  std::printf("\n|---|---|---|---|---|---|---|\n");
  const char* names[] = { "diagonal", "west-east", "south-north" };
  for (int f = 0; f < 3; ++f)
    for (double tau : { 1.0, 2.0 })
    {
      double rtinSum = 0;
      std::vector<double> lo(engines.size(), 1e300), hi(engines.size(), 0), sum(engines.size(), 0);
      for (const gmm::View& v : flights[f])
      {
        const double r = static_cast<double>(mesher.countForView(cameraOf(v), tau));
        rtinSum += r;
        for (std::size_t e = 0; e < engines.size(); ++e)
        {
          const double ratio = engines[e]->update(v, tau).triangles / std::max(1.0, r);
          lo[e] = std::min(lo[e], ratio);
          hi[e] = std::max(hi[e], ratio);
          sum[e] += ratio;
        }
      }
      std::printf("| %s | %.0f | %.0f |", names[f], tau, rtinSum / frames);
      for (std::size_t e = 0; e < engines.size(); ++e)
        std::printf(" %.1f (%.1f - %.1f) |", sum[e] / frames, lo[e], hi[e]);
      std::printf("\n");
    }
}

} // namespace

int main(int argc, char** argv)
{
  if (argc > 1 && std::strcmp(argv[1], "--validate") == 0)
    return validate();
  const bool viewIndependentOnly = argc > 1 && std::strcmp(argv[1], "--view-independent") == 0;
  std::string path;
  int code = 0;
  if (gmmtest::DataFile("fuji_terrain_rgb.png", path, code))
  {
    rtin::Grid grid;
    gmm::Heightfield tile;
    const std::string err = loadFuji(path, grid, tile);
    if (err.empty())
    {
      viewIndependentTable(grid, tile);
      if (viewIndependentOnly)
        return 0;
      flightTable("Fuji tile", grid, 12);
    }
    else
      std::printf("%s\n", err.c_str());
  }
  if (gmmtest::DataFile("ps_height_1k.png", path, code))
  {
    rtin::Grid grid;
    const std::string err = loadPugetSound(path, grid);
    if (err.empty())
      flightTable("Puget Sound", grid, 12);
    else
      std::printf("%s\n", err.c_str());
  }
  const char* synth = std::getenv("GEOMIPMAP_BENCH_SYNTH");
  if (!synth || std::strcmp(synth, "0") != 0)
  {
    rtin::Grid grid;
    grid.size = 4097;
    grid.dx = grid.dy = 30.0;
    grid.h = gmm::makeSyntheticTerrain(4097, 4097, 30.0, 42, 1500.0).z;
    flightTable("Synthetic", grid, 8);
  }
  return 0;
}
