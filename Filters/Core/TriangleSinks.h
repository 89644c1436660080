// The two sinks every tessellation emits into (private to the engine's tessellation
// files, Tessellate.cpp and MergedNodes.cpp): vertex indices for drawing, or grid points
// for the error table.
#pragma once

#include "Heightfield.h"
#include "Tessellate.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace gmm
{

// The two triangles of quad (i0, j0)-(i1, j1), counter-clockwise, split along its
// (i0, j0)-(i1, j1) diagonal or, when `anti`, its (i1, j0)-(i0, j1) one.
template <typename Sink>
void splitQuad(Sink& sink, int i0, int j0, int i1, int j1, bool anti)
{
  if (anti)
  {
    sink.triangle({ i0, j0 }, { i1, j0 }, { i0, j1 });
    sink.triangle({ i1, j0 }, { i1, j1 }, { i0, j1 });
  }
  else
  {
    sink.triangle({ i0, j0 }, { i1, j0 }, { i1, j1 });
    sink.triangle({ i0, j0 }, { i1, j1 }, { i0, j1 });
  }
}

// Collects triangles for one block: converts grid points to vertex indices, drops triangles
// touching nodata unless asked to keep them, and keeps counter-clockwise world winding.
class TriangleSink
{
public:
  TriangleSink(const Heightfield& hf, std::vector<uint32_t>& out, bool keepNodata)
    : hf_(hf)
    , out_(out)
    , keepNodata_(keepNodata)
    , mirrored_(hf.mirrored())
  {
  }

  // a, b, c are counter-clockwise in (i, j) grid space.
  void triangle(GridPoint a, GridPoint b, GridPoint c)
  {
    const uint32_t ia = static_cast<uint32_t>(hf_.index(a.i, a.j));
    const uint32_t ib = static_cast<uint32_t>(hf_.index(b.i, b.j));
    const uint32_t ic = static_cast<uint32_t>(hf_.index(c.i, c.j));
    const float* z = hf_.heights();
    if (!keepNodata_ && (std::isnan(z[ia]) || std::isnan(z[ib]) || std::isnan(z[ic])))
    {
      return;
    }
    out_.push_back(ia);
    // A mirrored grid -> world map reverses orientation: swap to stay CCW in world space.
    out_.push_back(mirrored_ ? ic : ib);
    out_.push_back(mirrored_ ? ib : ic);
  }

  // Quad with corners (i0, j0)-(i1, j1), split along its (i0, j0)-(i1, j1) diagonal, or its
  // (i1, j0)-(i0, j1) one when `anti` (cellAntiDiagonal, Levels.h).
  void quad(int i0, int j0, int i1, int j1, bool anti = false) { splitQuad(*this, i0, j0, i1, j1, anti); }

private:
  const Heightfield& hf_;
  std::vector<uint32_t>& out_;
  bool keepNodata_;
  bool mirrored_;
};

// Collects triangles as grid points, counter-clockwise in (i, j), nodata or not: what the
// error table rasterises (no vertex index to divide back into a grid position).
class GridSink
{
public:
  explicit GridSink(std::vector<GridTriangle>& out)
    : out_(out)
  {
  }
  void triangle(GridPoint a, GridPoint b, GridPoint c) { out_.push_back(GridTriangle{ { a, b, c } }); }
  void quad(int i0, int j0, int i1, int j1, bool anti = false) { splitQuad(*this, i0, j0, i1, j1, anti); }

private:
  std::vector<GridTriangle>& out_;
};

// Passes triangles on to `base`, cutting each triangle side that lies on a glided edge of
// the block (BlockConfig::cutsSide) at the edge's finer samples (BlockConfig::sampleLevel:
// every 2^level-th sample from the block's first row or column), by a fan from the opposite
// vertex. Those samples lie on the side (sideBaseHeight), so the fan is the triangle's own
// surface; it shares them with the finer block across, which draws its own cells up to them.
template <typename Sink>
class EdgeCutSink
{
public:
  EdgeCutSink(Sink& base, int i0, int i1, int j0, int j1, const BlockConfig& config)
    : base_(base)
    , i0_(i0)
    , i1_(i1)
    , j0_(j0)
    , j1_(j1)
  {
    for (int side = 0; side < 4; ++side)
    {
      step_[side] = config.cutsSide(side) ? 1 << config.sampleLevel[side] : 0;
    }
  }

  // a, b, c counter-clockwise in (i, j).
  void triangle(GridPoint a, GridPoint b, GridPoint c)
  {
    const GridPoint v[3] = { a, b, c };
    for (int k = 0; k < 3; ++k)
    {
      const GridPoint p = v[k], q = v[(k + 1) % 3], o = v[(k + 2) % 3];
      const int side = sideOf(p, q);
      if (side < 0 || step_[side] == 0)
      {
        continue;
      }
      // The samples strictly between p and q along the side, from p to q: a fan from o.
      const bool rows = side == South || side == North;
      const int from = rows ? p.i : p.j, to = rows ? q.i : q.j, origin = rows ? i0_ : j0_;
      const int step = step_[side], dir = to > from ? 1 : -1;
      int x = dir > 0 ? origin + ((from - origin) / step + 1) * step : origin + ((from - origin - 1) / step) * step;
      if (dir * (to - x) <= 0)
      {
        continue; // no sample between them
      }
      GridPoint prev = p;
      for (; dir * (to - x) > 0; x += dir * step)
      {
        const GridPoint next = rows ? GridPoint{ x, p.j } : GridPoint{ p.i, x };
        triangle(prev, next, o);
        prev = next;
      }
      triangle(prev, q, o);
      return;
    }
    base_.triangle(a, b, c);
  }

  void quad(int qi0, int qj0, int qi1, int qj1, bool anti = false) { splitQuad(*this, qi0, qj0, qi1, qj1, anti); }

private:
  // The side of the block both points lie on (-1 if none): a triangle side along it.
  int sideOf(GridPoint p, GridPoint q) const
  {
    if (p.j == q.j && p.i != q.i)
    {
      return p.j == j0_ ? South : p.j == j1_ ? North : -1;
    }
    if (p.i == q.i && p.j != q.j)
    {
      return p.i == i0_ ? West : p.i == i1_ ? East : -1;
    }
    return -1;
  }

  Sink& base_;
  int i0_, i1_, j0_, j1_;
  int step_[4];
};

} // namespace gmm
