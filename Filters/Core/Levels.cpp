#include "Levels.h"

namespace gmm
{

BlockShape blockShape(int widthQuads, int heightQuads, int level)
{
  if (level < 0 || level > 30 || widthQuads < 1 || heightQuads < 1)
  {
    return BlockShape::Invalid;
  }
  const long long step = 1LL << level;
  if (step < widthQuads && step < heightQuads)
  {
    return BlockShape::Ring;
  }
  if (step >= widthQuads && step >= heightQuads)
  {
    return BlockShape::OneQuad;
  }
  if (level == 0)
  {
    return BlockShape::Thin; // one side is a single quad, the other longer
  }
  return BlockShape::Invalid;
}

int topLevel(int widthQuads, int heightQuads)
{
  const int side = widthQuads > heightQuads ? widthQuads : heightQuads;
  int m = 0;
  while ((1LL << m) < side)
  {
    ++m;
  }
  return m;
}

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
