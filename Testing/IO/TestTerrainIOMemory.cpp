// gmm::readTerrain from memory (TerrainBytes) against the same file read from disk: every
// real DEM of ../shared/data and files of each one-file format written here must give the
// same header, georeference, metadata and heights (bit for bit, NaN where NaN); formats
// that need a second file fail in memory with the file path's message; bad buffers get
// the file path's messages (and a null pointer its own); no /vsimem/ file is left behind.
#include "TerrainIO.h"

#include "GdalTestRaster.h"    // writeGdalRaster
#include "GeoMipMapTestData.h" // DataDir, DataRequired

#include <OpenImageIO/imageio.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{

std::vector<char> fileBytes(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::string baseName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Same result, field by field; heights bit for bit (all NaNs alike).
void expectSame(const gmm::TerrainRaster& a, const gmm::TerrainRaster& b, const std::string& what)
{
  EXPECT_EQ(a.nx, b.nx) << what;
  EXPECT_EQ(a.ny, b.ny) << what;
  EXPECT_EQ(a.x0, b.x0) << what;
  EXPECT_EQ(a.y0, b.y0) << what;
  EXPECT_EQ(a.dx, b.dx) << what;
  EXPECT_EQ(a.dy, b.dy) << what;
  EXPECT_EQ(a.crs, b.crs) << what;
  EXPECT_EQ(a.format, b.format) << what;
  EXPECT_EQ(a.heightUnit, b.heightUnit) << what;
  EXPECT_EQ(a.geographic, b.geographic) << what;
  EXPECT_EQ(a.georeferenced, b.georeferenced) << what;
  EXPECT_EQ(a.lon0, b.lon0) << what;
  EXPECT_EQ(a.lat0, b.lat0) << what;
  ASSERT_EQ(a.z.size(), b.z.size()) << what;
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.z.size(); ++k)
  {
    const bool same = std::isnan(a.z[k]) ? std::isnan(b.z[k])
                                         : std::memcmp(&a.z[k], &b.z[k], sizeof(float)) == 0;
    differ += same ? 0 : 1;
  }
  EXPECT_EQ(differ, 0u) << what << ": heights differ";
}

// Reads path from disk and from memory (under its own name), header and full; returns
// the full read's error (the same from both).
std::string readBothWays(const std::string& path, const gmm::TerrainReadOptions& opt)
{
  const std::vector<char> bytes = fileBytes(path);
  gmm::TerrainBytes mem;
  mem.data = bytes.data();
  mem.size = bytes.size();
  mem.name = baseName(path);
  gmm::TerrainRaster fileHeader, memHeader, fileFull, memFull;
  const std::string fileHeaderErr = gmm::readTerrainHeader(path, opt, fileHeader);
  const std::string memHeaderErr = gmm::readTerrainHeader(mem, opt, memHeader);
  EXPECT_EQ(fileHeaderErr, memHeaderErr) << path;
  expectSame(fileHeader, memHeader, path + " (header)");
  const auto ignore = [](double) {};
  const std::string fileErr = gmm::readTerrain(path, opt, fileFull, ignore);
  const std::string memErr = gmm::readTerrain(mem, opt, memFull, ignore);
  EXPECT_EQ(fileErr, memErr) << path;
  expectSame(fileFull, memFull, path);
  return fileErr;
}

// No /vsimem/ file of ours may outlive a read.
void expectNoMemFilesLeft()
{
  char** names = VSIReadDir("/vsimem/");
  for (int k = 0; names && names[k]; ++k)
  {
    EXPECT_NE(std::string(names[k]).rfind("geomipmap-", 0), 0u) << "left behind: " << names[k];
  }
  CSLDestroy(names);
}

class TerrainIOMemory : public ::testing::Test
{
protected:
  void SetUp() override
  {
    char tmpl[] = "/tmp/geomipmap-io-test-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    GDALAllRegister();
  }
  void TearDown() override
  {
    // Every file written here, sidecars (.prj, .hdr, .aux.xml) included.
    char** names = VSIReadDir(dir_.c_str());
    for (int k = 0; names && names[k]; ++k)
    {
      std::remove((dir_ + "/" + names[k]).c_str());
    }
    CSLDestroy(names);
    rmdir(dir_.c_str());
  }

  // A 41 x 29 DEM with a nodata sample, written with GDAL's driver (via a MEM copy).
  std::string gdalFile(const char* driver, const std::string& name, GDALDataType type,
    bool geographic, const char* nodata)
  {
    gmmtest::GdalRaster r;
    r.driver = driver;
    r.type = type;
    r.nx = 41;
    r.ny = 29;
    r.values.resize(static_cast<std::size_t>(r.nx) * r.ny);
    for (int j = 0; j < r.ny; ++j)
      for (int i = 0; i < r.nx; ++i)
        r.values[static_cast<std::size_t>(j) * r.nx + i] =
          500 + 100 * std::sin(0.2 * i) * std::cos(0.15 * j);
    if (nodata)
    {
      r.values[3] = r.nodata = std::atof(nodata);
      r.hasNodata = true;
    }
    r.geographic = geographic;
    if (geographic)
    {
      r.west = 1.0;
      r.north = 43.0;
      r.step = 1.0 / 1200;
    }
    return gmmtest::writeGdalRaster(dir_ + "/" + name, r);
  }

  // An image written with OpenImageIO: nch channels of type t, 37 x 23.
  std::string oiioFile(const std::string& name, int nch, OIIO::TypeDesc t)
  {
    const int nx = 37, ny = 23;
    std::vector<float> px(static_cast<std::size_t>(nx) * ny * nch);
    for (std::size_t k = 0; k < px.size(); ++k)
    {
      px[k] = t.is_floating_point() ? 100.0f * std::sin(0.01f * k) : float(k % 251) / 255.0f;
    }
    const std::string path = dir_ + "/" + name;
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out) << name;
    if (out)
    {
      EXPECT_TRUE(out->open(path, OIIO::ImageSpec(nx, ny, nch, t))) << out->geterror();
      EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
      out->close();
    }
    return path;
  }

  std::string dir_;
};

TEST_F(TerrainIOMemory, RealDemsReadTheSameFromMemory)
{
  const std::string data = gmmtest::DataDir();
  const char* const dems[] = { "N42E001.hgt", "N48W125.hgt", "SainteHelens.dem",
    "boulder_srtmgl3.asc", "mt_rainier_90m.tif", "ps_height_1k.png", "fuji_terrain_rgb.png" };
  int found = 0;
  for (const char* dem : dems)
  {
    const std::string path = data + "/" + dem;
    if (access(path.c_str(), R_OK) != 0)
    {
      // every one of them is in the shared folder: with data required, a missing one fails
      EXPECT_FALSE(gmmtest::DataRequired()) << path << " is missing and GEOMIPMAP_REQUIRE_DATA is set";
      continue;
    }
    ++found;
    gmm::TerrainReadOptions opt;
    opt.terrainRGB = std::strstr(dem, "terrain_rgb") != nullptr;
    EXPECT_EQ(readBothWays(path, opt), "") << path;
    opt.heightScale = 0.1;
    opt.heightOffset = 5.0;
    opt.spacing = 30.0;
    EXPECT_EQ(readBothWays(path, opt), "") << path << " (scale, offset, spacing)";
  }
  expectNoMemFilesLeft();
  if (found == 0)
  {
    GTEST_SKIP() << "no real DEMs in " << data << " (set GEOMIPMAP_DATA_DIR to the shared data folder)";
  }
}

TEST_F(TerrainIOMemory, OneFileFormatsReadTheSameFromMemory)
{
  gmm::TerrainReadOptions opt;
  for (const std::string& path :
    { gdalFile("GTiff", "int16.tif", GDT_Int16, false, "-32768"),
      gdalFile("GTiff", "float64.tif", GDT_Float64, true, nullptr),
      gdalFile("AAIGrid", "grid.asc", GDT_Float32, false, "-9999"),
      gdalFile("XYZ", "points.xyz", GDT_Float32, false, nullptr),
      gdalFile("USGSDEM", "usgs.dem", GDT_Int16, true, nullptr),
      oiioFile("grey16.png", 1, OIIO::TypeDesc::UINT16),
      oiioFile("greyalpha8.png", 2, OIIO::TypeDesc::UINT8),
      oiioFile("half.exr", 1, OIIO::TypeDesc::HALF),
      oiioFile("float.exr", 1, OIIO::TypeDesc::FLOAT),
      oiioFile("grey.pgm", 1, OIIO::TypeDesc::UINT8) })
  {
    // The .asc has a .prj beside it, which only the file read sees: its CRS differs.
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".asc") == 0)
    {
      std::remove((path.substr(0, path.size() - 4) + ".prj").c_str());
    }
    EXPECT_EQ(readBothWays(path, opt), "") << path;
  }
  opt.terrainRGB = true;
  EXPECT_EQ(readBothWays(oiioFile("terrain.png", 3, OIIO::TypeDesc::UINT8), opt), "");
  expectNoMemFilesLeft();
}

TEST_F(TerrainIOMemory, FormatsWithASecondFileFailInMemory)
{
  const std::string envi = gdalFile("ENVI", "envi.bin", GDT_Int16, false, nullptr);
  gmm::TerrainRaster r;
  ASSERT_EQ(gmm::readTerrainHeader(envi, gmm::TerrainReadOptions(), r), "");
  const std::vector<char> bytes = fileBytes(envi);
  gmm::TerrainBytes mem{ bytes.data(), bytes.size(), "envi.bin" };
  const std::string err = gmm::readTerrainHeader(mem, gmm::TerrainReadOptions(), r);
  EXPECT_EQ(err.rfind("is not a raster GDAL can read", 0), 0u) << err;
  expectNoMemFilesLeft();
}

TEST_F(TerrainIOMemory, BadBuffersGetClearMessages)
{
  gmm::TerrainRaster r;
  const gmm::TerrainReadOptions opt;
  const char junk[] = "this is not a raster";
  EXPECT_EQ(gmm::readTerrainHeader(gmm::TerrainBytes{ junk, 0, "dem.tif" }, opt, r), "is empty");
  EXPECT_EQ(gmm::readTerrainHeader(gmm::TerrainBytes{ junk, sizeof junk, "" }, opt, r),
    "no file name was given");
  EXPECT_EQ(gmm::readTerrainHeader(gmm::TerrainBytes{ nullptr, 100, "dem.tif" }, opt, r),
    "was given as a null pointer with 100 bytes");
  const std::string hgt =
    gmm::readTerrainHeader(gmm::TerrainBytes{ junk, sizeof junk, "N42E001.hgt" }, opt, r);
  EXPECT_NE(hgt.find("SRTM .hgt tiles are identified by size"), std::string::npos) << hgt;
  EXPECT_NE(hgt.find("this one has 21 bytes"), std::string::npos) << hgt;
  const std::string png =
    gmm::readTerrainHeader(gmm::TerrainBytes{ junk, sizeof junk, "dem.png" }, opt, r);
  EXPECT_EQ(png.rfind("is not an image OpenImageIO can read", 0), 0u) << png;
  expectNoMemFilesLeft();
}

} // namespace
