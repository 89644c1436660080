// Command-line options of the measurement tools (measure_pop_causes, measure_switch_mismatch):
// "--name value" pairs and bare "--flag"s, anywhere on the line.
#pragma once

#include <cstdlib>
#include <cstring>

namespace gmmbench
{

// The number after `name`, or `fallback` when `name` is not given.
inline double argOr(int argc, char** argv, const char* name, double fallback)
{
  for (int k = 1; k + 1 < argc; ++k)
  {
    if (std::strcmp(argv[k], name) == 0)
    {
      return std::atof(argv[k + 1]);
    }
  }
  return fallback;
}

// The word after `name`, or null when `name` is not given.
inline const char* stringArg(int argc, char** argv, const char* name)
{
  for (int k = 1; k + 1 < argc; ++k)
  {
    if (std::strcmp(argv[k], name) == 0)
    {
      return argv[k + 1];
    }
  }
  return nullptr;
}

// Whether `name` is given.
inline bool flag(int argc, char** argv, const char* name)
{
  for (int k = 1; k < argc; ++k)
  {
    if (std::strcmp(argv[k], name) == 0)
    {
      return true;
    }
  }
  return false;
}

} // namespace gmmbench
