#include "HoleCells.h"

#include "Tessellate.h"

namespace gmm
{

namespace
{
// The cell across `side` of cell (a, b), or -1 outside the inner grid (cells a in [1, nc],
// b in [1, nr]).
int neighbourCell(int nc, int nr, int a, int b, int side)
{
  switch (side)
  {
    case South:
      return b > 1 ? (b - 2) * nc + (a - 1) : -1;
    case East:
      return a < nc ? (b - 1) * nc + a : -1;
    case North:
      return b < nr ? b * nc + (a - 1) : -1;
    default: // West
      return a > 1 ? (b - 1) * nc + (a - 2) : -1;
  }
}

// Whether any side of cell (a, b) is shared with a FullResolution cell.
bool besideAnyFullResolution(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b)
{
  for (int side = South; side <= West; ++side)
  {
    if (besideFullResolution(C, R, kind, a, b, side))
    {
      return true;
    }
  }
  return false;
}
} // namespace

void classifyHoleCells(const Quadtree& qt, int block, const std::vector<int>& C,
  const std::vector<int>& R, std::vector<CellKind>& kind)
{
  kind.clear();
  if (C.size() < 4 || R.size() < 4)
  {
    return; // no inner cells: any nodata lies in the strips
  }
  const int nc = static_cast<int>(C.size()) - 3, nr = static_cast<int>(R.size()) - 3;
  kind.assign(static_cast<std::size_t>(nc) * nr, CellKind::Plain);
  if (!qt.blockHasNodata[block])
  {
    return;
  }
  for (int b = 1; b <= nr; ++b)
  {
    for (int a = 1; a <= nc; ++a)
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
        kind[(b - 1) * nc + (a - 1)] = CellKind::FullResolution;
      }
    }
  }
  // A cell beside a full-resolution one needs a sample inside for its fan; a cell under
  // 2 quads wide or tall (a level's narrower last column or row) has none, so it is drawn
  // at full resolution too, which may make its neighbours need fans in turn.
  for (bool grew = true; grew;)
  {
    grew = false;
    for (int b = 1; b <= nr; ++b)
    {
      for (int a = 1; a <= nc; ++a)
      {
        CellKind& k = kind[(b - 1) * nc + (a - 1)];
        if (k == CellKind::Plain && (C[a + 1] - C[a] < 2 || R[b + 1] - R[b] < 2) &&
          besideAnyFullResolution(C, R, kind, a, b))
        {
          k = CellKind::FullResolution;
          grew = true;
        }
      }
    }
  }
  for (int b = 1; b <= nr; ++b)
  {
    for (int a = 1; a <= nc; ++a)
    {
      CellKind& k = kind[(b - 1) * nc + (a - 1)];
      if (k == CellKind::Plain && besideAnyFullResolution(C, R, kind, a, b))
      {
        k = CellKind::Fanned;
      }
    }
  }
}

bool besideFullResolution(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, int side)
{
  const int n = neighbourCell(static_cast<int>(C.size()) - 3, static_cast<int>(R.size()) - 3, a, b, side);
  return n >= 0 && kind[n] == CellKind::FullResolution;
}

std::size_t innerRingExtraSamples(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind, int side)
{
  if (kind.empty())
  {
    return 0;
  }
  const int nc = static_cast<int>(C.size()) - 3, nr = static_cast<int>(R.size()) - 3;
  const bool horizontal = side == South || side == North;
  std::size_t extra = 0;
  for (int k = 1; k <= (horizontal ? nc : nr); ++k)
  {
    const int a = horizontal ? k : (side == West ? 1 : nc);
    const int b = horizontal ? (side == South ? 1 : nr) : k;
    if (cellAt(C, kind, a, b) == CellKind::FullResolution)
    {
      extra += static_cast<std::size_t>(horizontal ? C[a + 1] - C[a] : R[b + 1] - R[b]) - 1;
    }
  }
  return extra;
}

std::size_t holeCellsTriangleCount(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind)
{
  const int nc = static_cast<int>(C.size()) - 3, nr = static_cast<int>(R.size()) - 3;
  std::size_t n = 0;
  for (int b = 1; b <= nr; ++b)
  {
    for (int a = 1; a <= nc; ++a)
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
          n += 4;
          for (int side = South; side <= West; ++side)
          {
            if (besideFullResolution(C, R, kind, a, b, side))
            {
              n += (side == South || side == North ? w : h) - 1;
            }
          }
          break;
      }
    }
  }
  return n;
}

} // namespace gmm
