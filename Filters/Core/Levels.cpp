#include "Levels.h"

namespace gmm
{

int edgeSampleCount(int first, int last, int level)
{
  const long long step = 1LL << level;
  return static_cast<int>((static_cast<long long>(last) - first + step - 1) / step) + 1;
}

} // namespace gmm
