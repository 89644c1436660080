// VTK-HeaderTest-Exclude: vtkGeoMipMapMorphTexture.cxx
#include "vtkGeoMipMapMorphTexture.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "Morph.h"

#include <algorithm>

vtkGeoMipMapMorphTexture::vtkGeoMipMapMorphTexture() = default;
vtkGeoMipMapMorphTexture::~vtkGeoMipMapMorphTexture() = default;

std::string vtkGeoMipMapMorphTexture::Update(
  vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt, const gmm::MorphFrame& frame)
{
  const int bc = qt.blockCols, br = qt.blockRows;
  const int width = std::max(bc, br) + 1, height = 3 * br + 3;
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
  this->Data.assign(static_cast<size_t>(width) * height * 2, 0.0f);
  auto put = [&](int x, int y, float a, float b) {
    float* t = &this->Data[(static_cast<size_t>(y) * width + x) * 2];
    t[0] = a;
    t[1] = b;
  };
  for (int r = 0; r < br; ++r)
  {
    for (int c = 0; c < bc; ++c)
    {
      const int b = qt.blockIndex(c, r);
      put(c, r, frame.blockTarget[b], frame.blockTarget[b] >= 0 ? frame.blockT[b] : 0.0f);
    }
    for (int line = 0; line <= bc; ++line)
    {
      const gmm::MorphEdge& e = frame.vEdges[static_cast<size_t>(r) * (bc + 1) + line];
      put(line, br + r, e.target, e.target >= 0 ? e.t : 0.0f);
    }
  }
  for (int line = 0; line <= br; ++line)
  {
    for (int c = 0; c < bc; ++c)
    {
      const gmm::MorphEdge& e = frame.hEdges[static_cast<size_t>(line) * bc + c];
      put(c, 2 * br + line, e.target, e.target >= 0 ? e.t : 0.0f);
    }
  }
  for (int c = 0; c <= bc; ++c)
  {
    put(c, 3 * br + 1, static_cast<float>(qt.colStart[c]), 0.0f);
  }
  for (int r = 0; r <= br; ++r)
  {
    put(r, 3 * br + 2, static_cast<float>(qt.rowStart[r]), 0.0f);
  }
  this->Blocks[0] = bc;
  this->Blocks[1] = br;
  this->Texture->SetContext(win);
  if (!this->Texture->Create2DFromRaw(width, height, 2, VTK_FLOAT, this->Data.data()))
  {
    return "geomorphing: the RG32F texture could not be created: drawn unmorphed";
  }
  return std::string();
}

bool vtkGeoMipMapMorphTexture::HasData() const
{
  return this->Texture->GetHandle() != 0 && this->Blocks[0] > 0;
}

void vtkGeoMipMapMorphTexture::Activate()
{
  this->Texture->Activate();
  this->Unit = this->Texture->GetTextureUnit();
}

void vtkGeoMipMapMorphTexture::Deactivate()
{
  this->Texture->Deactivate();
  this->Unit = -1;
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
}

void vtkGeoMipMapMorphTexture::Release(vtkWindow* win)
{
  this->Texture->ReleaseGraphicsResources(win);
  this->Blocks[0] = this->Blocks[1] = 0;
}

void vtkGeoMipMapMorphTexture::Forget()
{
  // The context is gone with the texture: no GL call (as for the colour table).
  this->Blocks[0] = this->Blocks[1] = 0;
}
