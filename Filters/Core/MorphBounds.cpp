#include "MorphBounds.h"

#include "Morph.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gmm
{

namespace
{
// One triangle's contribution to a part's four corner errors: every sample it covers
// (integer barycentric test, edges included), its drawn height S, the interpolated
// displacements of its edge (dE) and ring (dR) vertices, against the sample's height.
// Returns false when nodata is involved.
bool rasterise(const Heightfield& hf, const GridTriangle& t, const double h[3], const double d[3],
  const bool onEdge[3], double err[4])
{
  const long long I[3] = { t.v[0].i, t.v[1].i, t.v[2].i }, J[3] = { t.v[0].j, t.v[1].j, t.v[2].j };
  long long area = (I[1] - I[0]) * (J[2] - J[0]) - (I[2] - I[0]) * (J[1] - J[0]);
  if (area == 0)
  {
    return true;
  }
  const double sign = area < 0 ? -1.0 : 1.0;
  const double inv = 1.0 / static_cast<double>(area < 0 ? -area : area);
  const long long i0 = std::min({ I[0], I[1], I[2] }), i1 = std::max({ I[0], I[1], I[2] });
  const long long j0 = std::min({ J[0], J[1], J[2] }), j1 = std::max({ J[0], J[1], J[2] });
  for (long long j = j0; j <= j1; ++j)
  {
    for (long long i = i0; i <= i1; ++i)
    {
      const long long w[3] = { (I[2] - I[1]) * (j - J[1]) - (J[2] - J[1]) * (i - I[1]),
        (I[0] - I[2]) * (j - J[2]) - (J[0] - J[2]) * (i - I[2]),
        (I[1] - I[0]) * (j - J[0]) - (J[1] - J[0]) * (i - I[0]) };
      double l[3];
      bool inside = true;
      for (int k = 0; k < 3; ++k)
      {
        l[k] = sign * static_cast<double>(w[k]) * inv;
        inside = inside && l[k] >= 0.0;
      }
      if (!inside)
      {
        continue;
      }
      const double H = hf.height(static_cast<int>(i), static_cast<int>(j));
      double s = 0.0, dE = 0.0, dR = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        // relative to vertex 0, so that a large datum costs no precision
        s += l[k] * (h[k] - h[0]);
        (onEdge[k] ? dE : dR) += l[k] * d[k];
      }
      s -= H - h[0];
      if (!std::isfinite(s) || !std::isfinite(dE) || !std::isfinite(dR))
      {
        return false;
      }
      err[0] = std::max(err[0], std::fabs(s));
      err[1] = std::max(err[1], std::fabs(s + dR));
      err[2] = std::max(err[2], std::fabs(s + dE));
      err[3] = std::max(err[3], std::fabs(s + dE + dR));
    }
  }
  return true;
}
} // namespace

double stripBound(const double e[4], double te, double tb)
{
  return (1.0 - te) * ((1.0 - tb) * e[0] + tb * e[1]) + te * ((1.0 - tb) * e[2] + tb * e[3]);
}

PartErrors morphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, EmitScratch& scratch)
{
  PartErrors out;
  updateMorphPartErrors(hf, qt, block, config, target, edgeTarget, kAllMorphParts, out, scratch);
  return out;
}

void updateMorphPartErrors(const Heightfield& hf, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts,
  PartErrors& out, EmitScratch& scratch)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  std::vector<GridTriangle> tris;
  for (int p = 0; p < 5; ++p)
  {
    if (!(parts & (1u << p)))
    {
      continue;
    }
    const BlockPart part = p == 0 ? BlockPart::Inner : static_cast<BlockPart>(static_cast<int>(BlockPart::StripSouth) + p - 1);
    tris.clear();
    emitBlockGrid(qt, block, config, part, tris, scratch);
    double err[4] = { 0.0, 0.0, 0.0, 0.0 };
    bool finite = true;
    for (const GridTriangle& t : tris)
    {
      double h[3], d[3];
      bool onEdge[3];
      for (int k = 0; k < 3; ++k)
      {
        const int i = t.v[k].i, j = t.v[k].j;
        h[k] = hf.height(i, j);
        d[k] = blockVertexTarget(hf, qt, block, target, edgeTarget, i, j) - h[k];
        onEdge[k] = i == i0 || i == i1 || j == j0 || j == j1;
      }
      if (!rasterise(hf, t, h, d, onEdge, err))
      {
        finite = false;
        break;
      }
    }
    if (p == 0)
    {
      out.inner[0] = err[0];
      out.inner[1] = err[1];
      out.innerFrozen = !finite;
    }
    else
    {
      std::copy(err, err + 4, out.side[p - 1]);
      out.sideFrozen[p - 1] = !finite;
    }
  }
}

} // namespace gmm
