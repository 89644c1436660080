// VTK-HeaderTest-Exclude: vtkGeoMipMapSharedHeights.cxx
#include "vtkGeoMipMapSharedHeights.h"
#include "vtkGeoMipMapSoftwareRenderer.h"

#include "vtkDataArray.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <sstream>

#ifndef GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD
#define GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD 0x9160 // GL_AMD_pinned_memory
#endif

//------------------------------------------------------------------------------
bool vtkGeoMipMapSharedHeights::Usable(vtkOpenGLRenderWindow*)
{
  return vtkGeoMipMapSoftwareRenderer::IsCurrent() && glewIsSupported("GL_AMD_pinned_memory") && glewIsSupported("GL_ARB_texture_buffer_object");
}

bool vtkGeoMipMapSharedHeights::SharesFormat(vtkDataArray* a, vtkGeoMipMapSampleTexture::Format f)
{
  if (a->GetNumberOfComponents() != 1)
  {
    return false;
  }
  switch (f)
  {
    case vtkGeoMipMapSampleTexture::Float32:
      return a->GetDataType() == VTK_FLOAT;
    case vtkGeoMipMapSampleTexture::Int16:
    case vtkGeoMipMapSampleTexture::UInt16:
      return true; // FormatFor picks these for 1-component 16-bit arrays only
    default:
      return false;
  }
}

vtkGeoMipMapSharedHeights::vtkGeoMipMapSharedHeights() = default;
vtkGeoMipMapSharedHeights::~vtkGeoMipMapSharedHeights() = default;

vtkGeoMipMapSharedHeights::Attempt vtkGeoMipMapSharedHeights::AttemptOf(
  vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format, vtkIdType maxBandTexels)
{
  return Attempt{ array, array->GetMTime(), format, maxBandTexels };
}

bool vtkGeoMipMapSharedHeights::IsCurrent(
  vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format, vtkIdType maxBandTexels) const
{
  return this->HasData() && this->Last == AttemptOf(array, format, maxBandTexels);
}

bool vtkGeoMipMapSharedHeights::Failed(
  vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format, vtkIdType maxBandTexels) const
{
  return !this->HasData() && this->Last == AttemptOf(array, format, maxBandTexels);
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapSharedHeights::Share(vtkOpenGLRenderWindow* win, vtkDataArray* array,
  vtkGeoMipMapSampleTexture::Format format, vtkIdType samples, vtkIdType maxBandTexels)
{
  const std::string why = this->ShareBands(win, array, format, samples, maxBandTexels);
  this->Last = AttemptOf(array, format, maxBandTexels); // ShareBands released the previous one
  if (why.empty())
  {
    this->Source = array;
  }
  return why;
}

std::string vtkGeoMipMapSharedHeights::ShareBands(vtkOpenGLRenderWindow* win, vtkDataArray* array,
  vtkGeoMipMapSampleTexture::Format format, vtkIdType samples, vtkIdType maxBandTexels)
{
  this->Release(win);
  const size_t sampleBytes = vtkGeoMipMapSampleTexture::BytesPerTexel(format);
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  // One sample a texel while one band holds them all; else four, so that a band holds four
  // times as many and fewer branches pick them (every branch costs on llvmpipe).
  const vtkIdType texels = maxBandTexels > 0 ? std::min<vtkIdType>(maxBandTexels, maxTexels) : maxTexels;
  const int perTexel = samples <= texels ? 1 : kMaxPerTexel;
  // Bands of a power of two samples, so that the shader finds a sample's band by a shift.
  int shift = perTexel == 1 ? 0 : 2;
  while (shift < 30 && (vtkIdType(1) << (shift + 1)) <= texels * perTexel)
  {
    ++shift;
  }
  const vtkIdType bandSamples = vtkIdType(1) << shift;
  const vtkIdType bands = (samples + bandSamples - 1) / bandSamples;
  // The last band's texels end at the last whole texel: a texel across the array's end
  // could lie on memory that is not the array's. The last samples (fewer than a texel's)
  // are handed to the shaders as uniforms.
  const vtkIdType packed = samples - samples % perTexel;
  if (maxTexels < 1 || bands > kMaxBands || samples > VTK_INT_MAX || packed == 0)
  {
    std::ostringstream why;
    why << samples << " samples need " << bands << " buffer textures of " << bandSamples
        << " samples (at most " << kMaxBands << ")";
    return why.str();
  }
  while (glGetError() != GL_NO_ERROR)
  {
    // Errors of earlier calls are not ours to report.
  }
  const bool four = perTexel == kMaxPerTexel;
  const GLenum internal = format == vtkGeoMipMapSampleTexture::Int16 ? (four ? GL_RGBA16I : GL_R16I)
    : format == vtkGeoMipMapSampleTexture::UInt16                    ? (four ? GL_RGBA16UI : GL_R16UI)
                                                                     : (four ? GL_RGBA32F : GL_R32F);
  const unsigned char* base = static_cast<const unsigned char*>(array->GetVoidPointer(0));
  GLenum err = GL_NO_ERROR;
  for (vtkIdType k = 0; k < bands && err == GL_NO_ERROR; ++k)
  {
    const vtkIdType first = k * bandSamples;
    const vtkIdType count = std::min(bandSamples, packed - first);
    if (count <= 0)
    {
      break; // the last band holds only the tail
    }
    Band b;
    glGenBuffers(1, &b.Buffer);
    glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, b.Buffer);
    // The array's memory becomes the buffer's storage (the driver does not copy it).
    glBufferData(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, static_cast<GLsizeiptr>(count * sampleBytes),
      base + first * sampleBytes, GL_STATIC_DRAW);
    glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, 0);
    glGenTextures(1, &b.Texture);
    glBindTexture(GL_TEXTURE_BUFFER, b.Texture);
    glTexBuffer(GL_TEXTURE_BUFFER, internal, b.Buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    b.Unit = vtkSmartPointer<vtkTextureObject>::New();
    b.Unit->SetContext(win);
    b.Unit->AssignToExistingTexture(b.Texture, GL_TEXTURE_BUFFER);
    this->Bands.push_back(b);
    err = glGetError();
  }
  if (err != GL_NO_ERROR)
  {
    this->Release(win);
    std::ostringstream why;
    why << "OpenGL could not read the " << samples << " heights in place: error 0x" << std::hex << err;
    return why.str();
  }
  this->BandShift = shift;
  this->PerTexel = perTexel;
  this->TailStart = packed;
  std::fill(std::begin(this->Tail), std::end(this->Tail), 0.0f);
  for (vtkIdType k = packed; k < samples; ++k)
  {
    this->Tail[k - packed] = static_cast<float>(array->GetComponent(k, 0));
  }
  return std::string();
}

//------------------------------------------------------------------------------
void vtkGeoMipMapSharedHeights::Activate(std::vector<int>& units)
{
  units.clear();
  for (Band& b : this->Bands)
  {
    b.Unit->Activate();
    units.push_back(b.Unit->GetTextureUnit());
  }
}

void vtkGeoMipMapSharedHeights::Deactivate()
{
  for (Band& b : this->Bands)
  {
    b.Unit->Deactivate();
  }
}

void vtkGeoMipMapSharedHeights::Release(vtkWindow* win)
{
  for (Band& b : this->Bands)
  {
    b.Unit->ReleaseGraphicsResources(win); // frees its unit; does not own the handle
    glDeleteTextures(1, &b.Texture);
    glDeleteBuffers(1, &b.Buffer);
  }
  this->Forget();
}

void vtkGeoMipMapSharedHeights::Forget()
{
  this->Bands.clear();
  this->Source = nullptr;
  this->Last = Attempt();
}
