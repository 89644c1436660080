// Which levels a block may take, and how its edges are sampled at a level.
//
// Level m samples every 2^m-th sample from the block's first row/column, plus the last one
// (a thin strip when the step does not divide the block). A block is drawn in one of three
// shapes, and a level is valid only when it gives one of them:
//   ring:     2^m < width and 2^m < height. Inner grid plus four side strips (see Tessellate.h).
//   one quad: 2^m >= width and 2^m >= height. Two triangles over the four corners, split
//             along the diagonal oneQuadAntiDiagonal (Quadtree.h) chooses.
//   thin:     level 0 of a block one quad wide or tall (only when the whole DEM is).
// Levels with 2^m >= one side but < the other are skipped: they would need a strip whose
// error depends on two neighbours at once, which the error table does not hold.
#pragma once

#include <vector>

namespace gmm
{

enum class BlockShape
{
  Ring,
  OneQuad,
  Thin,
  Invalid
};

// Inline: selection, geomorphing and tessellation ask these for every block of a frame.
inline BlockShape blockShape(int widthQuads, int heightQuads, int level)
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

// ceil(log2(n)) for n >= 1 (0 for n <= 1): the least m with 2^m >= n. Without a loop (a loop
// here was 3.4 % of the instructions of a mapper-default frame: every level rule calls it).
inline int ceilLog2(int n)
{
  if (n <= 1)
  {
    return 0;
  }
#if defined(__GNUC__) || defined(__clang__)
  return 32 - __builtin_clz(static_cast<unsigned>(n - 1));
#else
  int m = 0;
  while ((1LL << m) < n)
  {
    ++m;
  }
  return m;
#endif
}

// Highest level of a block: the first one that makes it one quad (ceil(log2(max side))).
inline int topLevel(int widthQuads, int heightQuads)
{
  return ceilLog2(widthQuads > heightQuads ? widthQuads : heightQuads);
}

// The next valid level above m for a w x h block, or -1 when m is its top level: m + 1
// while it is a ring, else the top level (the levels between give no shape; a level >= 1
// is one quad only from the top up). Geomorphing's chain of targets (Morph.h, MorphRamp.h).
inline int nextValidLevel(int widthQuads, int heightQuads, int m)
{
  const int top = topLevel(widthQuads, heightQuads);
  if (m + 1 > top)
  {
    return -1;
  }
  const int narrow = widthQuads < heightQuads ? widthQuads : heightQuads;
  return (1LL << (m + 1)) < narrow ? m + 1 : top;
}

// Samples along an edge [first, last] at level m: first, first + 2^m, ... (< last), last.
// Inline: a frame drawn from scratch at small blocks asks for tens of thousands of these
// short lists.
inline void edgeSamples(int first, int last, int level, std::vector<int>& out)
{
  out.clear();
  const long long step = 1LL << level;
  for (long long s = first; s < last; s += step)
  {
    out.push_back(static_cast<int>(s));
  }
  out.push_back(last);
}

// Number of samples edgeSamples would produce.
int edgeSampleCount(int first, int last, int level);

} // namespace gmm
