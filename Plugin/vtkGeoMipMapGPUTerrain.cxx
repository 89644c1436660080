// VTK-HeaderTest-Exclude: vtkGeoMipMapGPUTerrain.cxx
#include "vtkGeoMipMapGPUTerrain.h"

#include "vtkDataArray.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "Heightfield.h"
#include "VertexPitch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace
{
double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

//------------------------------------------------------------------------------
vtkGeoMipMapGPUTerrain::Result vtkGeoMipMapGPUTerrain::Update(
  vtkOpenGLRenderWindow* win, const Inputs& in)
{
  using O = vtkGeoMipMapShaders::Options;
  Result r;
  const gmm::Heightfield& hf = *in.HF;
  GLint maxLayers = 256;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  int maxSize = vtkTextureObject::GetMaximumTextureSize(win);
  if (in.MaximumTileSize > 0)
  {
    maxSize = std::min(maxSize, in.MaximumTileSize);
  }
  r.HeightsError = this->Layout.Plan(hf.nx, hf.ny, maxSize, maxLayers);
  const auto heightFormat = vtkGeoMipMapSampleTexture::FormatFor(in.Heights, false);
  // Heights read in place where the renderer shares this process's memory; a texture
  // otherwise, or when sharing fails.
  const bool share = in.ShareHeights && vtkGeoMipMapSharedHeights::SharesFormat(in.Heights, heightFormat) &&
    vtkGeoMipMapSharedHeights::Usable(win);
  // MaximumTileSize bounds a band's texels as it bounds a layer's (tests use it for many bands).
  const vtkIdType maxBand = in.MaximumTileSize > 0 ? vtkIdType(in.MaximumTileSize) * in.MaximumTileSize : 0;
  // A share that failed is not tried again every frame (Failed), and is reported once.
  if (r.HeightsError.empty() && share && !this->Shared.IsCurrent(in.Heights, heightFormat, maxBand) &&
    !this->Shared.Failed(in.Heights, heightFormat, maxBand))
  {
    const auto start = std::chrono::steady_clock::now();
    const std::string why =
      this->Shared.Share(win, in.Heights, heightFormat, in.Heights->GetNumberOfTuples(), maxBand);
    r.UploadSeconds += SecondsSince(start);
    ++r.Uploads;
    if (why.empty())
    {
      this->Heights.Release(win);
    }
    else
    {
      r.ShareError = why;
    }
  }
  if (!share)
  {
    // Not to be shared (ShareHeights off, a GPU, another format). When sharing is wanted
    // but failed, nothing is held and the failed attempt is remembered (Failed).
    this->Shared.Release(win);
  }
  if (r.HeightsError.empty() && !this->Shared.HasData() &&
    !this->Heights.IsCurrent(in.Heights, heightFormat, this->Layout))
  {
    const auto start = std::chrono::steady_clock::now();
    r.HeightsError = this->Heights.Upload(win, in.Heights, heightFormat, this->Layout);
    r.UploadSeconds += SecondsSince(start);
    ++r.Uploads;
  }
  // Slopes for the fragment normals, only while lit (made from the engine's float heights);
  // vertex normals take them from the heights in the vertex shader. The slope texture is
  // kept while asked for, also through frames shaded per vertex (the mapper's automatic
  // normals switch between the two with the frame's error).
  this->Lit = in.Lit;
  this->Shading.VertexNormals = in.Lit && in.VertexNormals;
  this->Shading.SlopesFromHeights = in.Lit && !in.SlopeTexture && !in.VertexNormals;
  const bool slopeTexture = in.Lit && in.SlopeTexture;
  if (in.Lit && !slopeTexture)
  {
    this->Slopes.Release(win);
  }
  if (r.HeightsError.empty() && slopeTexture &&
    !this->Slopes.IsCurrent(in.Heights, vtkGeoMipMapSampleTexture::Slopes16F, this->Layout))
  {
    const auto start = std::chrono::steady_clock::now();
    r.HeightsError = this->Slopes.UploadSlopes(win, hf, in.Heights, this->Layout);
    r.UploadSeconds += SecondsSince(start);
  }
  if (!r.HeightsError.empty())
  {
    return r;
  }
  this->Shading.SingleLayer = this->Layout.Layers() == 1;
  this->Shading.HeightBands = this->Shared.GetBands();
  this->Shading.HeightsPerTexel = this->Shared.GetSamplesPerTexel();
  this->Shading.HeightFormat = heightFormat == vtkGeoMipMapSampleTexture::Int16 ? O::Int16Heights
    : heightFormat == vtkGeoMipMapSampleTexture::UInt16                         ? O::UInt16Heights
                                                                                 : O::FloatHeights;

  // The drape, whatever the colouring under it.
  this->Shading.Drape = false;
  if (in.Drape)
  {
    r.DrapeError = this->Drape.Update(win, in.Drape);
    this->Shading.Drape = r.DrapeError.empty();
  }
  else if (this->Drape.HasData())
  {
    this->Drape.Release(win);
  }

  this->Shading.Color = O::PropertyColor;
  if (!in.Color)
  {
    return r;
  }
  if (!in.DirectColors)
  {
    this->Table.Update(win, in.Lookup, in.Lookup->GetRange());
    this->Shading.LogScale = this->Table.GetLogScale();
    if (in.Color == in.Heights)
    {
      this->Shading.Color = O::MapHeights;
      return r;
    }
  }
  const auto stored = in.DirectColors ? vtkGeoMipMapSampleTexture::RGBA8 : vtkGeoMipMapSampleTexture::Float32;
  if (!this->Colors.IsCurrent(in.Color, stored, this->Layout))
  {
    const auto start = std::chrono::steady_clock::now();
    r.ColorError = this->Colors.Upload(win, in.Color, stored, this->Layout);
    r.UploadSeconds += SecondsSince(start);
    ++r.Uploads;
    if (!r.ColorError.empty())
    {
      return r;
    }
  }
  this->Shading.Color = in.DirectColors ? O::DirectColors : O::MapScalars;
  return r;
}

//------------------------------------------------------------------------------
size_t vtkGeoMipMapGPUTerrain::GetBytes() const
{
  return this->Heights.GetBytes() + this->Slopes.GetBytes() + this->Colors.GetBytes() +
    this->Table.GetBytes() + this->Drape.GetBytes();
}

void vtkGeoMipMapGPUTerrain::Bind()
{
  using O = vtkGeoMipMapShaders::Options;
  const O::Coloring c = this->Shading.Color;
  if (this->Shared.HasData())
  {
    this->Shared.Activate(this->BandUnits);
  }
  else
  {
    this->HeightsUnit = this->Heights.Activate();
  }
  this->SlopesUnit =
    this->Lit && !this->Shading.VertexNormals && this->Slopes.HasData() ? this->Slopes.Activate() : -1;
  this->ColorsUnit = c == O::MapScalars || c == O::DirectColors ? this->Colors.Activate() : -1;
  this->TableUnit = c == O::MapHeights || c == O::MapScalars ? this->Table.Activate() : -1;
  this->DrapeUnit = this->Shading.Drape ? this->Drape.Activate() : -1;
}

void vtkGeoMipMapGPUTerrain::Unbind()
{
  if (this->DrapeUnit >= 0)
  {
    this->Drape.Deactivate();
  }
  if (this->TableUnit >= 0)
  {
    this->Table.Deactivate();
  }
  if (this->ColorsUnit >= 0)
  {
    this->Colors.Deactivate();
  }
  if (this->SlopesUnit >= 0)
  {
    this->Slopes.Deactivate();
  }
  if (this->Shared.HasData())
  {
    this->Shared.Deactivate();
  }
  else
  {
    this->Heights.Deactivate();
  }
  this->BandUnits.clear();
  this->HeightsUnit = this->SlopesUnit = this->ColorsUnit = this->TableUnit = this->DrapeUnit = -1;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapGPUTerrain::SetUniforms(vtkShaderProgram* p, const gmm::Heightfield& hf,
  double heightScale, int anchorI, int anchorJ, float heightRef) const
{
  auto seti = [p](const char* name, int v) {
    if (p->IsUniformUsed(name))
      p->SetUniformi(name, v);
  };
  auto set2i = [p](const char* name, int a, int b) {
    const int v[2] = { a, b };
    if (p->IsUniformUsed(name))
      p->SetUniform2i(name, v);
  };
  auto setf = [p](const char* name, double v) {
    if (p->IsUniformUsed(name))
      p->SetUniformf(name, static_cast<float>(v));
  };
  auto set2f = [p](const char* name, double a, double b) {
    const float v[2] = { static_cast<float>(a), static_cast<float>(b) };
    if (p->IsUniformUsed(name))
      p->SetUniform2f(name, v);
  };
  seti("gmmHeights", this->HeightsUnit);
  for (std::size_t k = 0; k < this->BandUnits.size(); ++k)
  {
    seti(("gmmHeightBand" + std::to_string(k)).c_str(), this->BandUnits[k]);
  }
  seti("gmmBandShift", this->Shared.GetBandShift());
  if (p->IsUniformUsed("gmmTailStart"))
  {
    p->SetUniformi("gmmTailStart", static_cast<int>(this->Shared.GetTailStart()));
    p->SetUniform1fv("gmmTail", this->Shared.GetSamplesPerTexel() - 1, this->Shared.GetTail());
  }
  seti("gmmSlopes", this->SlopesUnit);
  seti("gmmColors", this->ColorsUnit);
  seti("gmmScalars", this->ColorsUnit);
  seti("gmmColorTable", this->TableUnit);
  seti("gmmDrape", this->DrapeUnit);
  if (p->IsUniformUsed("gmmDrapeMap"))
  {
    float map[4];
    this->Drape.GetMap(hf.worldX(0), hf.worldY(0), hf.dx, hf.dy, map);
    p->SetUniform4f("gmmDrapeMap", map);
  }
  set2i("gmmGridSize", hf.nx, hf.ny);
  const uint32_t pitch = gmm::drawPitch(hf.nx, hf.ny);
  seti("gmmVertexPitch", static_cast<int>(pitch));
  setf("gmmInvPitch", 1.0 / pitch);
  set2i("gmmTileSize", this->Layout.tileW, this->Layout.tileH);
  set2f("gmmTileScale", 1.0 / this->Layout.tileW, 1.0 / this->Layout.tileH);
  seti("gmmTilesX", this->Layout.tilesX);
  set2f("gmmSpacing", hf.dx, hf.dy);
  setf("gmmHeightScale", heightScale);
  set2i("gmmAnchor", anchorI, anchorJ);
  setf("gmmHeightRef", heightRef);
  if (p->IsUniformUsed("gmmColorMap"))
  {
    const double* r = this->Table.GetRange();
    const bool log = this->Table.GetLogScale();
    const double lo = log ? std::log10(r[0]) : r[0];
    const double hi = log ? std::log10(r[1]) : r[1];
    const float map[4] = { static_cast<float>(lo),
      static_cast<float>(hi > lo ? 1.0 / (hi - lo) : 1.0), 0.0f,
      static_cast<float>(this->Table.GetEntries()) };
    p->SetUniform4f("gmmColorMap", map);
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapGPUTerrain::Release(vtkWindow* win)
{
  this->Heights.Release(win);
  this->Shared.Release(win);
  this->Slopes.Release(win);
  this->Colors.Release(win);
  this->Table.Release(win);
  this->Drape.Release(win);
}

void vtkGeoMipMapGPUTerrain::Forget()
{
  this->Heights.Forget();
  this->Shared.Forget();
  this->Slopes.Forget();
  this->Colors.Forget();
}
