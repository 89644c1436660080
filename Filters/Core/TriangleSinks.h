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

} // namespace gmm
