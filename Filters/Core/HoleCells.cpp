#include "HoleCells.h"

#include "Tessellate.h"

namespace gmm
{

namespace
{
// The cell across `side` of cell (a, b) in a grid of nc x nr cells, or -1 across the
// block's border.
int neighbourCell(int nc, int nr, int a, int b, int side)
{
  switch (side)
  {
    case South:
      return b > 0 ? (b - 1) * nc + a : -1;
    case East:
      return a + 1 < nc ? b * nc + a + 1 : -1;
    case North:
      return b + 1 < nr ? (b + 1) * nc + a : -1;
    default: // West
      return a > 0 ? b * nc + a - 1 : -1;
  }
}

bool anyFineSide(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b)
{
  bool fine[4];
  fineCellSides(C, R, kind, a, b, fine);
  return fine[South] || fine[East] || fine[North] || fine[West];
}
} // namespace

void classifyHoleCells(const Quadtree& qt, int block, const std::vector<int>& C,
  const std::vector<int>& R, std::vector<CellKind>& kind)
{
  const int nc = static_cast<int>(C.size()) - 1, nr = static_cast<int>(R.size()) - 1;
  kind.assign(static_cast<std::size_t>(nc) * nr, CellKind::Plain);
  for (int b = 0; b < nr; ++b)
  {
    for (int a = 0; a < nc; ++a)
    {
      bool nodata = false;
      for (int j = R[b]; j <= R[b + 1] && !nodata; ++j)
      {
        for (int i = C[a]; i <= C[a + 1] && !nodata; ++i)
        {
          nodata = qt.sampleIsNodata(block, i, j);
        }
      }
      if (nodata)
      {
        kind[static_cast<std::size_t>(b) * nc + a] = CellKind::FullResolution;
      }
    }
  }
  // A cell with a fine side needs a sample inside for its fan; a cell under 2 quads wide
  // or tall (a level's narrower last column or row) has none, so it is drawn at full
  // resolution too, which may give its neighbours fine sides in turn.
  for (bool grew = true; grew;)
  {
    grew = false;
    for (int b = 0; b < nr; ++b)
    {
      for (int a = 0; a < nc; ++a)
      {
        CellKind& k = kind[static_cast<std::size_t>(b) * nc + a];
        if (k == CellKind::Plain && (C[a + 1] - C[a] < 2 || R[b + 1] - R[b] < 2) &&
          anyFineSide(C, R, kind, a, b))
        {
          k = CellKind::FullResolution;
          grew = true;
        }
      }
    }
  }
  for (int b = 0; b < nr; ++b)
  {
    for (int a = 0; a < nc; ++a)
    {
      CellKind& k = kind[static_cast<std::size_t>(b) * nc + a];
      if (k == CellKind::Plain && anyFineSide(C, R, kind, a, b))
      {
        k = CellKind::Fanned;
      }
    }
  }
}

bool fineCellSide(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, int side)
{
  const int n = neighbourCell(static_cast<int>(C.size()) - 1, static_cast<int>(R.size()) - 1, a, b, side);
  return n < 0 || kind[n] == CellKind::FullResolution;
}

void fineCellSides(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, bool fine[4])
{
  for (int side = South; side <= West; ++side)
  {
    fine[side] = fineCellSide(C, R, kind, a, b, side);
  }
}

std::size_t holeCellsTriangleCount(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind)
{
  const int nc = static_cast<int>(C.size()) - 1, nr = static_cast<int>(R.size()) - 1;
  std::size_t n = 0;
  for (int b = 0; b < nr; ++b)
  {
    for (int a = 0; a < nc; ++a)
    {
      const std::size_t w = static_cast<std::size_t>(C[a + 1] - C[a]);
      const std::size_t h = static_cast<std::size_t>(R[b + 1] - R[b]);
      switch (cellAt(C, kind, a, b))
      {
        case CellKind::Plain:
          n += 2;
          break;
        case CellKind::FullResolution:
          n += 2 * w * h;
          break;
        case CellKind::Fanned:
        {
          bool fine[4];
          fineCellSides(C, R, kind, a, b, fine);
          n += fannedCellTriangleCount(static_cast<int>(w), static_cast<int>(h), fine);
          break;
        }
      }
    }
  }
  return n;
}

std::size_t fannedCellTriangleCount(int w, int h, const bool fine[4])
{
  std::size_t n = coarseCorner(fine) >= 0 ? 2 : 4;
  for (int side = South; side <= West; ++side)
  {
    if (fine[side])
    {
      n += static_cast<std::size_t>(side == South || side == North ? w : h) - 1;
    }
  }
  return n;
}

bool oneQuadFineSides(const Quadtree& qt, int block, bool fine[4])
{
  bool any = false;
  for (int side = South; side <= West; ++side)
  {
    fine[side] = qt.sideAtFullResolution(block, side);
    any = any || fine[side];
  }
  return any && qt.blockWidth(block) >= 2 && qt.blockHeight(block) >= 2;
}

} // namespace gmm
