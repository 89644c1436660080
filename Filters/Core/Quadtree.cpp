#include "Quadtree.h"

#include "HugePages.h"
#include "Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{

// Bands of `width` quads from `begin`, the remainder in a band of its own (splitBands). A
// remainder of one quad joins the band before it; when that makes it wider than maxQuads,
// the two are split in halves, the first rounded down to an even number of quads.
void splitInto(int begin, int end, int width, int maxQuads, std::vector<int>& starts)
{
  int s = begin;
  while (end - s > width)
  {
    starts.push_back(s);
    s += width;
  }
  if (s > begin && end - s == 1)
  {
    s = starts.back();
    starts.pop_back();
    if (width + 1 > maxQuads)
    {
      starts.push_back(s);
      s += std::max(2, (width + 1) / 4 * 2);
    }
  }
  starts.push_back(s);
}

Box emptyBox()
{
  const double inf = std::numeric_limits<double>::infinity();
  return Box{ glm::dvec3(inf), glm::dvec3(-inf) };
}

void grow(Box& b, const Box& o)
{
  b.lo = glm::min(b.lo, o.lo);
  b.hi = glm::max(b.hi, o.hi);
}

// Leaf box over samples [i0, i1] x [j0, j1]; z from valid heights only. A block whose
// samples are all nodata (allNodata) gets an empty z range at 0: it draws nothing, and the
// selection's walks skip it (QuadtreeNode::allNodata).
Box sampleBox(const Heightfield& hf, int i0, int i1, int j0, int j1, bool& hasNodata, bool& allNodata)
{
  float zmin = std::numeric_limits<float>::infinity();
  float zmax = -zmin;
  hasNodata = false;
  for (int j = j0; j <= j1; ++j)
  {
    const float* row = hf.heights() + hf.index(0, j);
    for (int i = i0; i <= i1; ++i)
    {
      const float h = row[i];
      if (std::isnan(h))
      {
        hasNodata = true;
        continue;
      }
      zmin = std::min(zmin, h);
      zmax = std::max(zmax, h);
    }
  }
  allNodata = zmin > zmax; // no valid sample
  if (allNodata)
  {
    zmin = zmax = 0.0f;
  }
  const double xa = hf.worldX(i0), xb = hf.worldX(i1);
  const double ya = hf.worldY(j0), yb = hf.worldY(j1);
  return Box{ glm::dvec3(std::min(xa, xb), std::min(ya, yb), zmin),
    glm::dvec3(std::max(xa, xb), std::max(ya, yb), zmax) };
}

// Builds the node over block columns [c0, c1) and rows [r0, r1) into qt.nodes[nodeIndex].
void buildNode(Quadtree& qt, int nodeIndex, int c0, int c1, int r0, int r1)
{
  QuadtreeNode& node = qt.nodes[nodeIndex];
  node.colBegin = c0;
  node.colEnd = c1;
  node.rowBegin = r0;
  node.rowEnd = r1;
  if (c1 - c0 == 1 && r1 - r0 == 1)
  {
    const int b = qt.blockIndex(c0, r0);
    qt.nodes[nodeIndex].block = b;
    qt.nodes[nodeIndex].box = qt.blockBox[b];
    qt.nodes[nodeIndex].allNodata = qt.blockAllNodata[b] != 0;
    return;
  }
  // Each child covers a contiguous range of bands (splitBand).
  const int cm = splitBand(c0, c1);
  const int rm = splitBand(r0, r1);
  int ranges[4][4];
  int n = 0;
  const int cs[3] = { c0, cm, c1 };
  const int rs[3] = { r0, rm, r1 };
  for (int rr = 0; rr < 2; ++rr)
  {
    for (int cc = 0; cc < 2; ++cc)
    {
      if (cs[cc] < cs[cc + 1] && rs[rr] < rs[rr + 1])
      {
        ranges[n][0] = cs[cc];
        ranges[n][1] = cs[cc + 1];
        ranges[n][2] = rs[rr];
        ranges[n][3] = rs[rr + 1];
        ++n;
      }
    }
  }
  const int first = static_cast<int>(qt.nodes.size());
  qt.nodes.resize(qt.nodes.size() + n);
  qt.nodes[nodeIndex].firstChild = first;
  qt.nodes[nodeIndex].childCount = n;
  Box box = emptyBox();
  int height = 0;
  bool allNodata = true;
  for (int k = 0; k < n; ++k)
  {
    buildNode(qt, first + k, ranges[k][0], ranges[k][1], ranges[k][2], ranges[k][3]);
    grow(box, qt.nodes[first + k].box);
    height = std::max(height, qt.nodes[first + k].height + 1);
    allNodata = allNodata && qt.nodes[first + k].allNodata;
  }
  qt.nodes[nodeIndex].box = box;
  qt.nodes[nodeIndex].height = height;
  qt.nodes[nodeIndex].allNodata = allNodata;
}

} // namespace

std::string validateBlockSize(int maxBlockQuads)
{
  if (maxBlockQuads >= kMinBlockQuads)
  {
    return std::string();
  }
  return "block size " + std::to_string(maxBlockQuads) + " is below the minimum of " +
    std::to_string(kMinBlockQuads) + " quads";
}

int bandWidth(int quads, int maxQuads)
{
  maxQuads = std::max(1, maxQuads);
  if (quads <= maxQuads)
  {
    return quads;
  }
  int halvings = 0;
  while (static_cast<int64_t>(maxQuads) << halvings < quads)
  {
    ++halvings;
  }
  const int halved = quads >> halvings;
  int width = 2;
  while (width * 2 <= halved)
  {
    width *= 2;
  }
  return width;
}

std::vector<int> splitBands(int quads, int maxQuads, int lowCollar, int highCollar)
{
  // Collars widened to keep the bands between them starting on even samples.
  lowCollar = std::max(lowCollar, 0);
  lowCollar += lowCollar & 1;
  highCollar = std::max(highCollar, 0);
  highCollar += highCollar > 0 ? (quads - highCollar) & 1 : 0;
  if (quads - lowCollar - highCollar < kMinBlockQuads)
  {
    lowCollar = highCollar = 0;
  }
  std::vector<int> starts;
  if (lowCollar > 0)
  {
    starts.push_back(0);
  }
  splitInto(lowCollar, quads - highCollar, bandWidth(quads - lowCollar - highCollar, maxQuads),
    std::max(1, maxQuads), starts);
  if (highCollar > 0)
  {
    starts.push_back(quads - highCollar);
  }
  starts.push_back(quads);
  return starts;
}

namespace
{
// The collar of one side (Quadtree.h, nodataCollar) over the lines [first, last] across
// it: one more than the longest run of nodata from the border, counting only runs shorter
// than `limit`. Sample k of line l is at(l, k); each line has `length` samples.
template <typename At>
int collarWidth(int first, int last, int length, int limit, At at)
{
  int widest = 0;
  for (int l = first; l <= last; ++l)
  {
    int run = 0;
    while (run < length && run < limit && std::isnan(at(l, run)))
    {
      ++run;
    }
    if (run < limit)
    {
      widest = std::max(widest, run);
    }
  }
  return widest > 0 ? widest + 1 : 0;
}
} // namespace

NodataCollar nodataCollar(const Heightfield& hf, int maxBlockQuads)
{
  NodataCollar c;
  const int limit = std::max(kMinBlockQuads, maxBlockQuads) - kMinBlockQuads;
  if (limit < 2) // the smallest block size: no band could be narrower
  {
    return c;
  }
  const float* z = hf.heights();
  const int nx = hf.nx, ny = hf.ny;
  const auto fromWest = [&](int j, int k) { return z[hf.index(k, j)]; };
  const auto fromEast = [&](int j, int k) { return z[hf.index(nx - 1 - k, j)]; };
  const auto fromSouth = [&](int i, int k) { return z[hf.index(i, k)]; };
  const auto fromNorth = [&](int i, int k) { return z[hf.index(i, ny - 1 - k)]; };
  // A corner belongs to two collars: a wedge along the west also starts the first columns
  // with nodata seen from the north. So the columns are counted between the west and east
  // collars, then the rows again between the south and north ones.
  c.west = collarWidth(0, ny - 1, nx, limit, fromWest);
  c.east = collarWidth(0, ny - 1, nx, limit, fromEast);
  c.south = collarWidth(c.west, nx - 1 - c.east, ny, limit, fromSouth);
  c.north = collarWidth(c.west, nx - 1 - c.east, ny, limit, fromNorth);
  c.west = collarWidth(c.south, ny - 1 - c.north, nx, limit, fromWest);
  c.east = collarWidth(c.south, ny - 1 - c.north, nx, limit, fromEast);
  return c;
}

namespace
{
// Bands [b0, b1), the upper half of their parent's split when `isUpper`: each band gets
// the flag of the split that makes it a range of one.
void markUpperHalves(int b0, int b1, uint8_t isUpper, std::vector<uint8_t>& upper)
{
  if (b1 - b0 == 1)
  {
    upper[b0] = isUpper;
    return;
  }
  const int mid = splitBand(b0, b1);
  markUpperHalves(b0, mid, 0, upper);
  markUpperHalves(mid, b1, 1, upper);
}
} // namespace

std::vector<uint8_t> upperHalfBands(int bands)
{
  std::vector<uint8_t> upper(static_cast<std::size_t>(std::max(bands, 0)), 0);
  if (bands > 0)
  {
    markUpperHalves(0, bands, 0, upper);
  }
  return upper;
}

namespace
{
// Quadtree::nodataBits for every block with nodata (blockHasNodata set).
void recordNodataBits(const Heightfield& hf, Quadtree& qt, int threads)
{
  const int blocks = qt.blockCount();
  uint64_t words = 0;
  std::vector<uint64_t> at;
  for (int b = 0; b < blocks; ++b)
  {
    if (qt.blockHasNodata[b])
    {
      if (at.empty())
      {
        at.assign(static_cast<std::size_t>(blocks), 0);
      }
      at[b] = words;
      const uint64_t bits = static_cast<uint64_t>(qt.blockWidth(b) + 1) * (qt.blockHeight(b) + 1);
      words += (bits + 63) / 64;
    }
  }
  if (at.empty())
  {
    return;
  }
  qt.nodataBitsAt = std::move(at);
  qt.nodataBits.assign(words, 0);
  qt.nodataDepth.assign(4 * static_cast<std::size_t>(blocks), 0);
  // Rows of blocks in parallel: each block writes its own words.
  parallelChunks(static_cast<std::size_t>(qt.blockRows), 1, threads, [&](std::size_t first, std::size_t last) {
    for (int r = static_cast<int>(first); r < static_cast<int>(last); ++r)
    {
      for (int c = 0; c < qt.blockCols; ++c)
      {
        const int b = qt.blockIndex(c, r);
        if (!qt.blockHasNodata[b])
        {
          continue;
        }
        uint64_t* w = qt.nodataBits.data() + qt.nodataBitsAt[b];
        uint64_t bit = 0;
        const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
        int depth[4] = { 65535, 65535, 65535, 65535 };
        for (int j = j0; j <= j1; ++j)
        {
          const float* row = hf.heights() + hf.index(0, j);
          for (int i = i0; i <= i1; ++i, ++bit)
          {
            if (std::isnan(row[i]))
            {
              w[bit / 64] |= uint64_t(1) << (bit % 64);
              depth[0] = std::min(depth[0], j - j0); // South, East, North, West
              depth[1] = std::min(depth[1], i1 - i);
              depth[2] = std::min(depth[2], j1 - j);
              depth[3] = std::min(depth[3], i - i0);
            }
          }
        }
        for (int side = 0; side < 4; ++side)
        {
          qt.nodataDepth[4 * static_cast<std::size_t>(b) + side] = static_cast<uint16_t>(depth[side]);
        }
      }
    }
  });
}
} // namespace

Quadtree buildQuadtree(const Heightfield& hf, int maxBlockQuads, int threads)
{
  Quadtree qt;
  maxBlockQuads = std::max(kMinBlockQuads, maxBlockQuads);
  const NodataCollar collar = nodataCollar(hf, maxBlockQuads);
  qt.colStart = splitBands(hf.nx - 1, maxBlockQuads, collar.west, collar.east);
  qt.rowStart = splitBands(hf.ny - 1, maxBlockQuads, collar.south, collar.north);
  qt.blockCols = static_cast<int>(qt.colStart.size()) - 1;
  qt.blockRows = static_cast<int>(qt.rowStart.size()) - 1;
  qt.colUpperHalf = upperHalfBands(qt.blockCols);
  qt.rowUpperHalf = upperHalfBands(qt.blockRows);
  resizeOnHugePages(qt.blockBox, qt.blockCount());
  resizeOnHugePages(qt.blockHasNodata, qt.blockCount());
  qt.blockAllNodata.resize(static_cast<std::size_t>(qt.blockCount()));
  qt.blockWidths.resize(qt.blockCount());
  qt.blockHeights.resize(qt.blockCount());
  qt.blockTopLevels.resize(qt.blockCount());
  qt.blockRingLevels.resize(qt.blockCount());
  // Rows of blocks in parallel: each writes its own blocks' entries.
  parallelChunks(static_cast<std::size_t>(qt.blockRows), 1, threads, [&](std::size_t first, std::size_t last) {
    for (int r = static_cast<int>(first); r < static_cast<int>(last); ++r)
    {
      for (int c = 0; c < qt.blockCols; ++c)
      {
        bool nodata = false, allNodata = false;
        const int b = qt.blockIndex(c, r);
        qt.blockBox[b] =
          sampleBox(hf, qt.colStart[c], qt.colStart[c + 1], qt.rowStart[r], qt.rowStart[r + 1], nodata, allNodata);
        qt.blockHasNodata[b] = nodata ? 1 : 0;
        qt.blockAllNodata[b] = allNodata ? 1 : 0;
        qt.blockWidths[b] = qt.colStart[c + 1] - qt.colStart[c];
        qt.blockHeights[b] = qt.rowStart[r + 1] - qt.rowStart[r];
        qt.blockTopLevels[b] = static_cast<uint8_t>(topLevel(qt.blockWidths[b], qt.blockHeights[b]));
        qt.blockRingLevels[b] = static_cast<uint8_t>(ceilLog2(std::min(qt.blockWidths[b], qt.blockHeights[b])));
      }
    }
  });
  recordNodataBits(hf, qt, threads);
  qt.nodes.reserve(2 * static_cast<std::size_t>(qt.blockCount()));
  qt.nodes.resize(1);
  buildNode(qt, 0, 0, qt.blockCols, 0, qt.blockRows);
  return qt;
}

} // namespace gmm
