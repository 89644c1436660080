// The error table cache: a hit gives the very table a build gives; a corrupt, truncated,
// stale or foreign file is refused, rebuilt and replaced; an unwritable location only
// costs the saving; trimming removes the oldest tables and nothing else.
#include "CoreTestUtil.h"
#include "Terrain.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

#include <chrono>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>

using namespace gmmtest;
namespace fs = std::filesystem;

namespace
{

// A fresh directory under the test's working directory, removed at the end.
struct TempDir
{
  fs::path path;
  explicit TempDir(const std::string& name)
    : path(fs::current_path() / ("TableCache_" + name))
  {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

gmm::Heightfield terrain(int nx, int ny, uint64_t seed)
{
  Rng rng(seed);
  gmm::Heightfield hf = roughTerrain(nx, ny, rng);
  hf.z[hf.index(nx / 3, ny / 2)] = std::numeric_limits<float>::quiet_NaN(); // nodata too
  return hf;
}

gmm::TableCacheOptions cacheIn(const fs::path& dir)
{
  gmm::TableCacheOptions o;
  o.directory = dir.string();
  o.minSamples = 0; // the tests use small DEMs
  return o;
}

std::shared_ptr<const gmm::Terrain> build(const gmm::Heightfield& hf, int blockQuads,
  const gmm::TableCacheOptions& cache, gmm::TableCacheReport& report)
{
  std::shared_ptr<const gmm::Terrain> t;
  const std::string err = gmm::buildTerrain(hf, blockQuads, 2, t, nullptr, cache, &report);
  EXPECT_EQ(err, "");
  return t;
}

void expectSameTable(const gmm::ErrorTable& a, const gmm::ErrorTable& b)
{
  EXPECT_EQ(a.levels, b.levels);
  EXPECT_EQ(a.pairs, b.pairs);
  EXPECT_TRUE(a.ownError == b.ownError);
  EXPECT_TRUE(a.ownErrorExact == b.ownErrorExact);
  EXPECT_TRUE(a.stripError == b.stripError);
  EXPECT_TRUE(a.mergedError == b.mergedError);
  EXPECT_TRUE(a.cellTriangles == b.cellTriangles); // derived again on a hit
}

// Overwrites `bytes` at `offset` of a file.
void patch(const std::string& path, std::streamoff offset, const std::string& bytes)
{
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(offset);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Flips the lowest bit of the byte at `offset`: a change whatever the byte was.
void flipBit(const std::string& path, std::streamoff offset)
{
  char byte = 0;
  {
    std::ifstream f(path, std::ios::binary);
    f.seekg(offset);
    f.read(&byte, 1);
  }
  patch(path, offset, std::string(1, static_cast<char>(byte ^ 1)));
}

// The 4 bytes of `v`, least significant first (the cache files' byte order on this machine).
std::string littleEndian(uint32_t v)
{
  std::string b(4, '\0');
  for (int k = 0; k < 4; ++k)
    b[k] = static_cast<char>((v >> (8 * k)) & 0xffu);
  return b;
}

} // namespace

TEST(TableCache, HitGivesTheBuiltTable)
{
  TempDir dir("hit");
  gmm::Heightfield hf = terrain(301, 217, 1);
  for (int k = 0; k < 40; ++k) // voids: blocks drawn as cells, whose counts the table holds
    hf.z[hf.index((k * 97) % 301, (k * 61) % 217)] = std::numeric_limits<float>::quiet_NaN();
  gmm::TableCacheReport first, second;
  auto built = build(hf, 32, cacheIn(dir.path), first);
  EXPECT_TRUE(first.used);
  EXPECT_FALSE(first.hit);
  EXPECT_TRUE(first.written) << first.problem;
  EXPECT_TRUE(fs::exists(first.path));
  auto read = build(hf, 32, cacheIn(dir.path), second);
  EXPECT_TRUE(second.hit) << second.problem;
  EXPECT_EQ(second.path, first.path);
  EXPECT_EQ(second.problem, "");
  expectSameTable(read->table, built->table);
  EXPECT_FALSE(read->table.cellTriangles.empty());
  // And the very table a build without any cache gives.
  gmm::TableCacheReport none;
  auto plain = build(hf, 32, gmm::TableCacheOptions(), none);
  EXPECT_FALSE(none.used);
  expectSameTable(read->table, plain->table);
}

TEST(TableCache, OtherHeightsOrBlockSizeMiss)
{
  TempDir dir("miss");
  gmm::Heightfield hf = terrain(150, 160, 2);
  gmm::TableCacheReport r;
  build(hf, 32, cacheIn(dir.path), r);
  ASSERT_TRUE(r.written);
  // Another block size: another file.
  gmm::TableCacheReport b16;
  auto t16 = build(hf, 16, cacheIn(dir.path), b16);
  EXPECT_FALSE(b16.hit);
  EXPECT_NE(b16.path, r.path);
  // One height changed by one float step: another hash, so the old table is not used.
  hf.z[hf.index(77, 88)] = std::nextafter(hf.z[hf.index(77, 88)], 1e9f);
  gmm::TableCacheReport changed;
  auto t = build(hf, 32, cacheIn(dir.path), changed);
  EXPECT_FALSE(changed.hit);
  EXPECT_NE(changed.path, r.path);
  gmm::TableCacheReport none;
  expectSameTable(t->table, build(hf, 32, gmm::TableCacheOptions(), none)->table);
}

TEST(TableCache, StaleFileUnderTheRightNameIsRebuilt)
{
  TempDir dir("stale");
  const gmm::Heightfield a = terrain(120, 90, 3), b = terrain(120, 90, 4);
  gmm::TableCacheReport ra, rb;
  build(a, 16, cacheIn(dir.path), ra);
  // Put a's table where b's belongs (same size and block size: only the hash differs).
  const std::string bPath = gmm::tableCachePath(dir.path.string(),
    gmm::TableCacheKey{ gmm::hashHeights(b, 1), b.nx, b.ny, 16 });
  fs::copy_file(ra.path, bPath);
  auto t = build(b, 16, cacheIn(dir.path), rb);
  EXPECT_FALSE(rb.hit);
  EXPECT_NE(rb.problem.find("stale"), std::string::npos) << rb.problem;
  EXPECT_TRUE(rb.written);
  gmm::TableCacheReport none, again;
  expectSameTable(t->table, build(b, 16, gmm::TableCacheOptions(), none)->table);
  build(b, 16, cacheIn(dir.path), again);
  EXPECT_TRUE(again.hit) << again.problem; // the rebuilt table replaced the stale file
}

TEST(TableCache, CorruptFilesAreRefusedAndReplaced)
{
  TempDir dir("corrupt");
  const gmm::Heightfield hf = terrain(200, 130, 5);
  gmm::TableCacheReport r0;
  auto reference = build(hf, 16, cacheIn(dir.path), r0);
  ASSERT_TRUE(r0.written);
  const uintmax_t size = fs::file_size(r0.path);
  struct Damage
  {
    const char* name;
    std::function<void(const std::string&)> apply;
    const char* expect;
  };
  const std::vector<Damage> damages = {
    { "bit in the data", [&](const std::string& p) { flipBit(p, static_cast<std::streamoff>(size / 2)); },
      "checksum" },
    { "last byte", [&](const std::string& p) { flipBit(p, static_cast<std::streamoff>(size - 1)); }, "checksum" },
    { "truncated", [&](const std::string& p) { fs::resize_file(p, size - 4); }, "size" },
    { "padded", [&](const std::string& p) { fs::resize_file(p, size + 8); }, "size" },
    { "header only", [&](const std::string& p) { fs::resize_file(p, 20); }, "truncated" },
    { "empty", [&](const std::string& p) { fs::resize_file(p, 0); }, "truncated" },
    { "magic", [&](const std::string& p) { patch(p, 0, "XMMTABLE"); }, "not an error table" },
    { "version", [&](const std::string& p) { patch(p, 8, littleEndian(gmm::tableCacheFormatVersion() + 1)); },
      "version" },
    { "byte order", [&](const std::string& p) { patch(p, 12, std::string("\x01\x02\x03\x04", 4)); },
      "byte order" },
    { "block count", [&](const std::string& p) { patch(p, 44, std::string("\x01\0\0\0", 4)); },
      "quadtree" },
  };
  for (const Damage& d : damages)
  {
    d.apply(r0.path);
    gmm::TableCacheReport r;
    auto t = build(hf, 16, cacheIn(dir.path), r);
    EXPECT_FALSE(r.hit) << d.name;
    EXPECT_NE(r.problem.find(d.expect), std::string::npos) << d.name << ": " << r.problem;
    EXPECT_TRUE(r.written) << d.name;
    expectSameTable(t->table, reference->table);
    EXPECT_EQ(fs::file_size(r0.path), size) << d.name << ": not replaced";
  }
}

TEST(TableCache, ForgedValuesWithAValidChecksumAreRefused)
{
  // A file whose checksum was recomputed after writing a NaN: the value check still
  // refuses it (NaN would disable every comparison in the selection).
  TempDir dir("nan");
  const gmm::Heightfield hf = terrain(90, 90, 6);
  gmm::TableCacheReport r0;
  auto built = build(hf, 16, cacheIn(dir.path), r0);
  gmm::ErrorTable bad = built->table;
  bad.ownError[3] = std::numeric_limits<float>::quiet_NaN();
  const gmm::TableCacheKey key{ gmm::hashHeights(hf, 1), hf.nx, hf.ny, 16 };
  ASSERT_EQ(gmm::writeTableCache(r0.path, key, built->qt, bad), "");
  gmm::ErrorTable out;
  EXPECT_NE(gmm::readTableCache(r0.path, key, built->qt, out).find("values"), std::string::npos);
  EXPECT_TRUE(out.ownError.empty());
}

TEST(TableCache, ATableForOtherBandsIsRefused)
{
  // Same heights, block size and sizes, but one band boundary moved by a quad (as a
  // nodata collar one quad wider would): the errors are those of other blocks.
  TempDir dir("bands");
  const gmm::Heightfield hf = terrain(90, 90, 8);
  gmm::TableCacheReport r0;
  auto built = build(hf, 16, cacheIn(dir.path), r0);
  gmm::Quadtree moved = built->qt;
  ASSERT_GE(moved.colStart.size(), 3u);
  moved.colStart[1] += 1;
  const gmm::TableCacheKey key{ gmm::hashHeights(hf, 1), hf.nx, hf.ny, 16 };
  ASSERT_EQ(gmm::writeTableCache(r0.path, key, moved, built->table), "");
  gmm::ErrorTable out;
  EXPECT_NE(gmm::readTableCache(r0.path, key, built->qt, out).find("band layout"), std::string::npos);
  EXPECT_TRUE(out.ownError.empty());
  ASSERT_EQ(gmm::writeTableCache(r0.path, key, built->qt, built->table), "");
  EXPECT_EQ(gmm::readTableCache(r0.path, key, built->qt, out), "");
}

TEST(TableCache, UnwritableLocationStillBuilds)
{
  TempDir dir("readonly");
  // A directory below a regular file can never be created, whoever runs the test.
  const fs::path blocker = dir.path / "a-file";
  std::ofstream(blocker) << "not a directory";
  const gmm::Heightfield hf = terrain(100, 100, 7);
  gmm::TableCacheReport r;
  auto t = build(hf, 16, cacheIn(blocker / "cache"), r);
  ASSERT_TRUE(t);
  EXPECT_TRUE(r.used);
  EXPECT_FALSE(r.written);
  EXPECT_NE(r.problem.find("cannot create"), std::string::npos) << r.problem;
  gmm::TableCacheReport none;
  expectSameTable(t->table, build(hf, 16, gmm::TableCacheOptions(), none)->table);
}

TEST(TableCache, SmallDemsAreNotCached)
{
  TempDir dir("small");
  const gmm::Heightfield hf = terrain(64, 64, 8);
  gmm::TableCacheOptions o = cacheIn(dir.path);
  o.minSamples = 64 * 64 + 1;
  gmm::TableCacheReport r;
  build(hf, 16, o, r);
  EXPECT_FALSE(r.used);
  EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(TableCache, HashSeesEveryBitAndNotTheThreadCount)
{
  gmm::Heightfield hf = terrain(1500, 1400, 9); // two 2^20-sample chunks and a tail
  const uint64_t h1 = gmm::hashHeights(hf, 1);
  EXPECT_EQ(gmm::hashHeights(hf, 2), h1);
  EXPECT_EQ(gmm::hashHeights(hf, 5), h1);
  for (std::size_t at : { std::size_t(0), std::size_t(1) << 20, hf.z.size() - 1 })
  {
    gmm::Heightfield g = hf;
    uint32_t bits;
    std::memcpy(&bits, &g.z[at], 4);
    bits ^= 1u; // the lowest mantissa bit
    std::memcpy(&g.z[at], &bits, 4);
    EXPECT_NE(gmm::hashHeights(g, 2), h1) << "sample " << at;
  }
  // The same heights seen as another grid size.
  gmm::Heightfield t = hf;
  t.nx = hf.ny;
  t.ny = hf.nx;
  EXPECT_NE(gmm::hashHeights(t, 2), h1);
}

TEST(TableCache, TrimRemovesTheOldestTablesOnly)
{
  TempDir dir("trim");
  const gmm::Heightfield a = terrain(100, 100, 10), b = terrain(100, 100, 11), c = terrain(100, 100, 12);
  gmm::TableCacheReport ra, rb, rc;
  gmm::TableCacheOptions o = cacheIn(dir.path);
  build(a, 16, o, ra);
  build(b, 16, o, rb);
  const fs::path other = dir.path / "notes.txt";
  std::ofstream(other) << "user file";
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(ra.path, now - std::chrono::hours(3));
  fs::last_write_time(rb.path, now - std::chrono::hours(2));
  fs::last_write_time(other, now - std::chrono::hours(9));
  // Room for two tables: writing c removes a, the oldest.
  o.maxBytes = 2 * fs::file_size(ra.path) + 10;
  build(c, 16, o, rc);
  EXPECT_FALSE(fs::exists(ra.path));
  EXPECT_TRUE(fs::exists(rb.path));
  EXPECT_TRUE(fs::exists(rc.path));
  EXPECT_TRUE(fs::exists(other));
  // A hit refreshes the time, so b is now the most recently used and c goes next.
  gmm::TableCacheReport hitB, rd;
  build(b, 16, o, hitB);
  EXPECT_TRUE(hitB.hit);
  fs::last_write_time(rc.path, now - std::chrono::hours(1));
  build(a, 16, o, rd);
  EXPECT_TRUE(fs::exists(rb.path));
  EXPECT_FALSE(fs::exists(rc.path));
  EXPECT_TRUE(fs::exists(rd.path));
}

// A cache file is trusted when its format version matches, so a change to what the tables
// hold (what Tessellate draws, how ErrorTable measures it, the bands) without a new version
// makes every build read stale tables and report bounds that do not hold: it happened twice
// (session 10: TestFlyRealDEM certified 1.89 px at tau 1 from another tree's cache; session
// 11: fans from a corner measured 1.09 px at tau 1 in TestFillVoidsRender). This test holds
// the version and a hash of the table of one reference DEM (integer-built heights, voids
// inside, on block borders and in a border wedge; block 16, merged nodes): when the tables
// change, it fails until kFormatVersion is raised and the new pair recorded here.
TEST(TableCache, FormatVersionFollowsTheTables)
{
  gmm::Heightfield hf;
  hf.nx = 97;
  hf.ny = 81;
  hf.z.resize(static_cast<std::size_t>(hf.nx) * hf.ny);
  for (int j = 0; j < hf.ny; ++j)
    for (int i = 0; i < hf.nx; ++i)
    {
      const uint32_t h = (static_cast<uint32_t>(i) * 73856093u) ^ (static_cast<uint32_t>(j) * 19349663u);
      float z = static_cast<float>(h % 997u) * 0.25f + 0.5f * static_cast<float>(i) + 0.25f * static_cast<float>(j);
      const bool wedge = i < (j % 5);
      const bool crossing = (i - 32) * (i - 32) + (j - 40) * (j - 40) <= 9; // on a block border
      const bool inside = (i == 50 && j == 20) || (i >= 70 && i <= 73 && j >= 58 && j <= 60);
      if (wedge || crossing || inside)
        z = std::numeric_limits<float>::quiet_NaN();
      hf.z[hf.index(i, j)] = z;
    }
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  const gmm::ErrorTable t = gmm::buildErrorTable(hf, qt, 1);
  uint64_t hash = 1469598103934665603ull; // FNV-1a over the table's arrays
  auto add = [&hash](const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k)
      hash = (hash ^ p[k]) * 1099511628211ull;
  };
  add(t.ownError.data(), t.ownError.size() * sizeof(float));
  add(t.ownErrorExact.data(), t.ownErrorExact.size() * sizeof(float));
  add(t.stripError.data(), t.stripError.size() * sizeof(float));
  add(t.mergedError.data(), t.mergedError.size() * sizeof(float));
  for (const std::vector<float>* v : { &t.fanResidual, &t.fanMovedError, &t.fanChildrenError })
    add(v->data(), v->size() * sizeof(float));
  add(t.cellTriangles.data(), t.cellTriangles.size() * sizeof(uint32_t));
  for (const std::vector<float>* v : { &t.perimeterError, &t.perimeterPop })
    add(v->data(), v->size() * sizeof(float));
  const uint32_t recordedVersion = 18;
  const uint64_t recordedHash = 0x902a827d44132a21ull;
  char hex[32];
  std::snprintf(hex, sizeof hex, "0x%016llx", static_cast<unsigned long long>(hash));
  EXPECT_TRUE(gmm::tableCacheFormatVersion() == recordedVersion && hash == recordedHash)
    << "format version " << gmm::tableCacheFormatVersion() << ", table hash " << hex
    << "; recorded: version " << recordedVersion << ". If the tables changed, raise kFormatVersion "
    << "(TableCache.cpp) and record the new version and hash here.";
}
