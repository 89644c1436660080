// Which levels a block may take, and how its edges are sampled at a level.
//
// Level m samples every 2^m-th sample from the block's first row/column, plus the last one
// (a thin strip when the step does not divide the block). A block is drawn in one of three
// shapes, and a level is valid only when it gives one of them:
//   ring:     2^m < width and 2^m < height. Inner grid plus four side strips (see Tessellate.h).
//   one quad: 2^m >= width and 2^m >= height. Two triangles over the four corners.
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

BlockShape blockShape(int widthQuads, int heightQuads, int level);

// Highest level of a block: the first one that makes it one quad (ceil(log2(max side))).
int topLevel(int widthQuads, int heightQuads);

// Samples along an edge [first, last] at level m: first, first + 2^m, ... (< last), last.
void edgeSamples(int first, int last, int level, std::vector<int>& out);

// Number of samples edgeSamples would produce.
int edgeSampleCount(int first, int last, int level);

} // namespace gmm
