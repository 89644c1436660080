#include "Levels.h"

namespace gmm
{

void edgeSamples(int first, int last, int level, std::vector<int>& out)
{
  out.clear();
  const long long step = 1LL << level;
  for (long long s = first; s < last; s += step)
  {
    out.push_back(static_cast<int>(s));
  }
  out.push_back(last);
}

int edgeSampleCount(int first, int last, int level)
{
  const long long step = 1LL << level;
  return static_cast<int>((static_cast<long long>(last) - first + step - 1) / step) + 1;
}

} // namespace gmm
