// VTK-HeaderTest-Exclude: vtkGeoMipMapMorphTexture.cxx
#include "vtkGeoMipMapMorphTexture.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "Morph.h"

#include <algorithm>
#include <array>
#include <utility>

vtkGeoMipMapMorphTexture::vtkGeoMipMapMorphTexture() = default;
vtkGeoMipMapMorphTexture::~vtkGeoMipMapMorphTexture() = default;

namespace
{
// The first texel column of the block corners' band (the layout in the header).
int cornerColumn(const gmm::Quadtree& qt)
{
  return std::max(qt.blockCols, qt.blockRows) + 1;
}

// The texture's width and height for a quadtree (the layout in the header).
void textureSize(const gmm::Quadtree& qt, int& width, int& height)
{
  width = cornerColumn(qt) + qt.blockCols + 1;
  height = 3 * qt.blockRows + 1;
}

// The widest row of gmmSampleBands: a power of two, so that the shader finds a sample's
// texel by a shift and a mask (integer division is scalarised on software rasterisers).
// 64 texels: a 257-sample DEM already spans rows, so small test DEMs check the addressing,
// and (nx + ny) / 64 rows fit the 16384 of GL_MAX_TEXTURE_SIZE up to 2^19 samples a side.
constexpr int kMaxSampleBandsShift = 6;

// The (band, first sample, last sample, band's upper-half flag) of every sample along one
// axis of the quadtree's bands (`start`: band starts, then the end; `upper`: the quadtree's
// colUpperHalf or rowUpperHalf, for oneQuadAntiDiagonal), 4 floats each, appended to `out`: band k
// holds samples [start[k], start[k + 1]], its last sample shared with band k + 1, which
// gmm::morphedHeight's band search assigns to band k + 1 (the last one to the last band).
void appendSampleBands(const std::vector<int>& start, const std::vector<uint8_t>& upper, int rowTexels,
  std::vector<float>& out)
{
  const int samples = start.back() + 1;
  const size_t first = out.size();
  out.resize(first + (static_cast<size_t>(samples + rowTexels - 1) / rowTexels) * rowTexels * 4, 0.0f);
  int k = 0;
  for (int s = 0; s < samples; ++s)
  {
    while (k + 2 < static_cast<int>(start.size()) && start[k + 1] <= s)
    {
      ++k;
    }
    float* t = &out[first + static_cast<size_t>(s) * 4];
    t[0] = static_cast<float>(k);
    t[1] = static_cast<float>(start[k]);
    t[2] = static_cast<float>(start[k + 1]);
    t[3] = static_cast<float>(upper[k]);
  }
}

// Where block b's texel and its four edges' texels are (x, y), South, East, North, West.
struct BlockTexels
{
  int x[5], y[5];
};

BlockTexels texelsOf(const gmm::Quadtree& qt, int b)
{
  const int bc = qt.blockCols, br = qt.blockRows, c = b % bc, r = b / bc;
  return BlockTexels{ { c, c, c + 1, c, c }, { r, 2 * br + r, br + r, 2 * br + r + 1, br + r } };
}

// Texels are (target, factor, edge level): the block's or the edge's morph target and
// factor, and for an edge the level it is drawn at (-1 for a block, or an edge not drawn),
// whose polyline holds a glided edge's samples (EdgeHeights.h).
constexpr int kTexelFloats = 3;

// Writes the texels of block b and of its four edges from a frame into `data` (width
// texels a row); changed(x, y) is told of each texel whose value changed.
template <typename Changed>
void writeBlock(std::vector<float>& data, int width, const gmm::Quadtree& qt,
  const gmm::MorphFrame& f, int b, Changed changed)
{
  const BlockTexels t = texelsOf(qt, b);
  const std::array<const gmm::MorphEdge*, 4> e = gmm::blockEdges(qt, f, b);
  float v[5][kTexelFloats] = { { static_cast<float>(f.blockTarget[b]), f.blockTarget[b] >= 0 ? f.blockT[b] : 0.0f,
    -1.0f } };
  for (int k = 0; k < 4; ++k)
  {
    v[k + 1][0] = e[k]->target;
    v[k + 1][1] = e[k]->target >= 0 ? e[k]->t : 0.0f;
    v[k + 1][2] = e[k]->level;
  }
  for (int k = 0; k < 5; ++k)
  {
    float* p = &data[(static_cast<size_t>(t.y[k]) * width + t.x[k]) * kTexelFloats];
    if (p[0] != v[k][0] || p[1] != v[k][1] || p[2] != v[k][2])
    {
      std::copy(v[k], v[k] + kTexelFloats, p);
      changed(t.x[k], t.y[k]);
    }
  }
}
// Writes the texel of block corner k (MorphFrame::corners' index) from a frame into `data`;
// changed(x, y) is told when its value changed.
template <typename Changed>
void writeCorner(std::vector<float>& data, int width, const gmm::Quadtree& qt, const gmm::MorphFrame& f, int k,
  Changed changed)
{
  const int x = cornerColumn(qt) + k % (qt.blockCols + 1), y = k / (qt.blockCols + 1);
  const bool moving = static_cast<size_t>(k) < f.cornerT.size() && f.cornerT[k] > 0.0f;
  const float v[kTexelFloats] = { moving ? f.cornerTarget[k] : 0.0f, moving ? f.cornerT[k] : 0.0f, 0.0f };
  float* p = &data[(static_cast<size_t>(y) * width + x) * kTexelFloats];
  if (p[0] != v[0] || p[1] != v[1] || p[2] != v[2])
  {
    std::copy(v, v + kTexelFloats, p);
    changed(x, y);
  }
}
} // namespace

std::string vtkGeoMipMapMorphTexture::Update(
  vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt, const gmm::MorphFrame& frame)
{
  const int bc = qt.blockCols, br = qt.blockRows;
  int width = 0, height = 0;
  textureSize(qt, width, height);
  const bool sameLayout = this->Blocks[0] == bc && this->Blocks[1] == br && this->Size[0] == width &&
    this->Size[1] == height && this->Texture->GetHandle() != 0 && this->Texture->GetContext() == win &&
    this->SampleBands->GetHandle() != 0 && frame.blockT.size() == static_cast<size_t>(bc) * br &&
    this->ColStart == qt.colStart && this->RowStart == qt.rowStart; // another DEM, same block grid
  if (!sameLayout)
  {
    return this->Build(win, qt, frame);
  }
  // Rewrite the texels of the blocks drawn at the last upload (the frame has reset theirs)
  // and of those drawn now, and of the corners moving then or now; upload, row by row, the
  // span of each row that changed (the drawn blocks of a wide view are a wedge near the eye:
  // most rows change in a short span).
  this->SpanLo.assign(static_cast<size_t>(height), width);
  this->SpanHi.assign(static_cast<size_t>(height), -1);
  auto changed = [this](int x, int y) {
    this->SpanLo[y] = std::min(this->SpanLo[y], x);
    this->SpanHi[y] = std::max(this->SpanHi[y], x);
  };
  for (const std::vector<int>* blocks : { &std::as_const(this->Written), &frame.blocks })
  {
    for (int b : *blocks)
    {
      writeBlock(this->Data, width, qt, frame, b, changed);
    }
  }
  this->Written = frame.blocks;
  for (const std::vector<int>* corners : { &std::as_const(this->WrittenCorners), &frame.corners })
  {
    for (int k : *corners)
    {
      writeCorner(this->Data, width, qt, frame, k, changed);
    }
  }
  this->WrittenCorners = frame.corners;
  this->LastUploadBytes = 0;
  bool active = false;
  for (int y = 0; y < height; ++y)
  {
    const int lo = this->SpanLo[static_cast<size_t>(y)], hi = this->SpanHi[static_cast<size_t>(y)];
    if (hi < lo)
    {
      continue;
    }
    if (!active)
    {
      // Activate takes a texture unit of its own (Bind alone would rebind whatever
      // texture the active unit holds, e.g. the actor's), as Create2DFromRaw does.
      this->Texture->Activate();
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      active = true;
    }
    glTexSubImage2D(GL_TEXTURE_2D, 0, lo, y, hi - lo + 1, 1, GL_RGB, GL_FLOAT,
      &this->Data[(static_cast<size_t>(y) * width + lo) * kTexelFloats]);
    this->LastUploadBytes += static_cast<size_t>(hi - lo + 1) * kTexelFloats * sizeof(float);
  }
  if (active)
  {
    this->Texture->Deactivate();
  }
  return std::string();
}

std::string vtkGeoMipMapMorphTexture::Build(
  vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt, const gmm::MorphFrame& frame)
{
  this->Blocks[0] = this->Blocks[1] = 0;
  this->Size[0] = this->Size[1] = 0;
  this->Written.clear();
  this->WrittenCorners.clear();
  this->LastUploadBytes = 0;

  const int bc = qt.blockCols, br = qt.blockRows;
  int width = 0, height = 0;
  textureSize(qt, width, height);
  const int maxSize = vtkTextureObject::GetMaximumTextureSize(win);
  if (width > maxSize || height > maxSize)
  {
    return "geomorphing needs a " + std::to_string(width) + " x " + std::to_string(height) +
      " texture, more than GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize) + ": drawn unmorphed";
  }
  if (qt.colStart.back() >= (1 << 24) || qt.rowStart.back() >= (1 << 24))
  {
    return "geomorphing stores sample indices as floats, exact below 2^24 samples a side: drawn "
           "unmorphed";
  }
  // Blocks and edges not written by any block (none: every edge is some block's) read as
  // not morphing and not drawn.
  this->Data.assign(static_cast<size_t>(width) * height * kTexelFloats, 0.0f);
  // Every edge is one of some block's four: the blocks write every block and edge texel.
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    writeBlock(this->Data, width, qt, frame, b, [](int, int) {});
  }
  for (int k : frame.corners)
  {
    writeCorner(this->Data, width, qt, frame, k, [](int, int) {});
  }
  this->Blocks[0] = bc;
  this->Blocks[1] = br;
  this->Texture->SetContext(win);
  if (!this->Texture->Create2DFromRaw(width, height, kTexelFloats, VTK_FLOAT, this->Data.data()))
  {
    return "geomorphing: the RGB32F texture could not be created: drawn unmorphed";
  }
  const std::string why = this->BuildSampleBands(win, qt);
  if (!why.empty())
  {
    return why;
  }
  this->Size[0] = width;
  this->Size[1] = height;
  this->Written = frame.blocks;
  this->WrittenCorners = frame.corners;
  this->LastUploadBytes = this->GetBytes();
  return std::string();
}

std::string vtkGeoMipMapMorphTexture::BuildSampleBands(vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt)
{
  const int longest = std::max(qt.colStart.back(), qt.rowStart.back()) + 1;
  int shift = 0;
  while (shift < kMaxSampleBandsShift && (1 << shift) < longest)
  {
    ++shift;
  }
  const int rowTexels = 1 << shift;
  std::vector<float> bands;
  appendSampleBands(qt.colStart, qt.colUpperHalf, rowTexels, bands);
  const int columnRows = static_cast<int>(bands.size() / (4 * static_cast<size_t>(rowTexels)));
  appendSampleBands(qt.rowStart, qt.rowUpperHalf, rowTexels, bands);
  const int rows = static_cast<int>(bands.size() / (4 * static_cast<size_t>(rowTexels)));
  const int maxSize = vtkTextureObject::GetMaximumTextureSize(win);
  if (rowTexels > maxSize || rows > maxSize)
  {
    return "geomorphing needs a " + std::to_string(rowTexels) + " x " + std::to_string(rows) +
      " texture of block bands, more than GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize) + ": drawn unmorphed";
  }
  this->SampleBands->SetContext(win);
  if (!this->SampleBands->Create2DFromRaw(rowTexels, rows, 4, VTK_FLOAT, bands.data()))
  {
    return "geomorphing: the RGBA32F texture of block bands could not be created: drawn unmorphed";
  }
  this->SampleBandsLayout[0] = shift;
  this->SampleBandsLayout[1] = columnRows;
  this->ColStart = qt.colStart;
  this->RowStart = qt.rowStart;
  this->BandBytes = bands.size() * sizeof(float);
  return std::string();
}

bool vtkGeoMipMapMorphTexture::HasData() const
{
  return this->Texture->GetHandle() != 0 && this->SampleBands->GetHandle() != 0 && this->Blocks[0] > 0;
}

void vtkGeoMipMapMorphTexture::Activate()
{
  this->Texture->Activate();
  this->Unit = this->Texture->GetTextureUnit();
  this->SampleBands->Activate();
  this->BandsUnit = this->SampleBands->GetTextureUnit();
}

void vtkGeoMipMapMorphTexture::Deactivate()
{
  this->Texture->Deactivate();
  this->SampleBands->Deactivate();
  this->Unit = -1;
  this->BandsUnit = -1;
}

void vtkGeoMipMapMorphTexture::SetUniforms(vtkShaderProgram* p) const
{
  if (p->IsUniformUsed("gmmMorph"))
  {
    p->SetUniformi("gmmMorph", this->Unit);
  }
  if (p->IsUniformUsed("gmmMorphLayout"))
  {
    p->SetUniform2i("gmmMorphLayout", this->Blocks);
  }
  if (p->IsUniformUsed("gmmSampleBands"))
  {
    p->SetUniformi("gmmSampleBands", this->BandsUnit);
  }
  if (p->IsUniformUsed("gmmSampleBandsLayout"))
  {
    p->SetUniform2i("gmmSampleBandsLayout", this->SampleBandsLayout);
  }
}

void vtkGeoMipMapMorphTexture::Release(vtkWindow* win)
{
  this->Texture->ReleaseGraphicsResources(win);
  this->SampleBands->ReleaseGraphicsResources(win);
  this->Blocks[0] = this->Blocks[1] = 0;
}

void vtkGeoMipMapMorphTexture::Forget()
{
  // The context is gone with the texture: no GL call (as for the colour table).
  this->Blocks[0] = this->Blocks[1] = 0;
}
