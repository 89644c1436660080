// The real-DEM folder of the tests, in one place for the C++ tests (VTK or not); the Python
// tests' twin is Testing/Python/gmmdata.py. Needs GEOMIPMAP_SOURCE_DIR defined (CMake).
#ifndef GeoMipMapTestData_h
#define GeoMipMapTestData_h

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace gmmtest
{
constexpr int SkipReturnCode = 125; // VTK_SKIP_RETURN_CODE

// The real-DEM folder: $GEOMIPMAP_DATA_DIR when set (non-empty), else ../shared/data beside
// the source tree. The same rule as Testing/Python/gmmdata.py.
inline std::string DataDir()
{
  const char* env = std::getenv("GEOMIPMAP_DATA_DIR");
  return env && *env ? env : std::string(GEOMIPMAP_SOURCE_DIR) + "/../shared/data";
}

// True when missing data must fail a test (GEOMIPMAP_REQUIRE_DATA set and not "0", as CI does).
inline bool DataRequired()
{
  const char* env = std::getenv("GEOMIPMAP_REQUIRE_DATA");
  return env && *env && std::string(env) != "0";
}

// Path of a data file in DataDir(). When it is missing, prints why and returns false with
// `exitCode` set to what the test must return: SkipReturnCode, or EXIT_FAILURE when data is
// required.
inline bool DataFile(const std::string& name, std::string& path, int& exitCode)
{
  path = DataDir() + "/" + name;
  if (FILE* f = std::fopen(path.c_str(), "rb"))
  {
    std::fclose(f);
    return true;
  }
  if (DataRequired())
  {
    std::cout << "FAIL: " << path << " not found; GEOMIPMAP_REQUIRE_DATA is set, so missing "
              << "data fails the test\n";
    exitCode = EXIT_FAILURE;
  }
  else
  {
    std::cout << "SKIP: " << path << " not found (set GEOMIPMAP_DATA_DIR to the shared data "
              << "folder)\n";
    exitCode = SkipReturnCode;
  }
  return false;
}

} // namespace gmmtest

#endif
