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

// How a ring block splits its regular cells, at every level (the union-jack rule): cell
// (u, v) of the block's level grid, counted from its south-west corner, on its
// (i1, j0)-(i0, j1) diagonal when u + v is odd, else on its (i0, j0)-(i1, j1) one. A level
// then nests in the next coarser one wherever the block's step divides it (a power-of-two
// block): each coarse cell is four fine cells whose splits lie along its own, so a level
// drawn with its vertices moved onto the coarser level's surface is that surface
// (Documentation/decisions/002-levels-that-nest.md). With an even number of cells a side,
// the rule also splits the ring's corner cells as the side strips meet there (SW and NE on
// the first diagonal, SE and NW on the second: ringCellAntiDiagonal).
inline bool cellAntiDiagonal(int u, int v)
{
  return ((u + v) & 1) != 0;
}

// The split of full-resolution quad (i, i + 1) x (j, j + 1) of the DEM: the union-jack
// rule counted from the DEM's first sample. Bands start on even samples (splitBands,
// Quadtree.h), so this is also every block's own rule at level 0: the full-resolution
// surface (RayCast.h) is what level 0 draws.
inline bool fullResolutionAntiDiagonal(int i, int j)
{
  return cellAntiDiagonal(i, j);
}

// The split of cell (u, v) of a ring block with nu x nv cells at its level, as Tessellate
// draws it: the corner cells as the side strips meet there (from the block's corner to the
// inner ring's corner: SE and NW on the (i1, j0)-(i0, j1) diagonal), the others by
// cellAntiDiagonal. The two agree everywhere when nu and nv are even.
inline bool ringCellAntiDiagonal(int u, int v, int nu, int nv)
{
  const bool west = u == 0, east = u == nu - 1, south = v == 0, north = v == nv - 1;
  if ((west || east) && (south || north))
  {
    return (east && south) || (west && north);
  }
  return cellAntiDiagonal(u, v);
}

// Height at (fx, fy) in [0, 1]^2 of a quad with corner heights h00 (its (i0, j0)), h10, h01
// and h11, on its two triangles: split along (i0, j0)-(i1, j1), or (i1, j0)-(i0, j1) when
// `anti` (the split of cellAntiDiagonal and fullResolutionAntiDiagonal). The one
// interpolation of a split cell: morph targets (MorphTargets.cpp; the vertex shader mirrors it) and
// the full-resolution surface (RayCast.cpp).
inline double splitQuadHeight(double h00, double h10, double h01, double h11, double fx, double fy, bool anti)
{
  if (!anti)
  {
    return fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);
  }
  return fx + fy <= 1.0 ? h00 + fx * (h10 - h00) + fy * (h01 - h00)
                        : h11 + (1.0 - fx) * (h01 - h11) + (1.0 - fy) * (h10 - h11);
}

// Number of samples edgeSamples would produce.
int edgeSampleCount(int first, int last, int level);

} // namespace gmm
