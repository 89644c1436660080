// VTK-HeaderTest-Exclude: vtkGeoMipMapTextures.cxx
#include "vtkGeoMipMapTextures.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkScalarsToColors.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "HalfFloat.h"   // gmm::halfOf
#include "Heightfield.h" // gmm::kMaxHeight
#include "Parallel.h"    // gmm::parallelChunks

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

namespace
{


struct GLFormat
{
  GLenum internal, format, type;
};

GLFormat GLFormatOf(vtkGeoMipMapSampleTexture::Format f)
{
  switch (f)
  {
    case vtkGeoMipMapSampleTexture::Int16:
      return { GL_R16I, GL_RED_INTEGER, GL_SHORT };
    case vtkGeoMipMapSampleTexture::UInt16:
      return { GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT };
    case vtkGeoMipMapSampleTexture::RGBA8:
      return { GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE };
    case vtkGeoMipMapSampleTexture::Slopes16F:
      return { GL_RG16F, GL_RG, GL_HALF_FLOAT }; // converted by UploadSlopes, copied by GL
    default:
      return { GL_R32F, GL_RED, GL_FLOAT };
  }
}

// True when the array's memory is already laid out as the texels (no conversion).
bool UploadsDirectly(vtkDataArray* a, vtkGeoMipMapSampleTexture::Format f)
{
  const int comps = a->GetNumberOfComponents();
  switch (f)
  {
    case vtkGeoMipMapSampleTexture::Float32:
      return a->GetDataType() == VTK_FLOAT && comps == 1;
    case vtkGeoMipMapSampleTexture::Int16:
    case vtkGeoMipMapSampleTexture::UInt16:
      return comps == 1; // FormatFor only picks these for 1-component 16-bit arrays
    default:
      return a->GetDataType() == VTK_UNSIGNED_CHAR && comps == 4;
  }
}

// One tile of the array converted to texels (float: component 0, values beyond the
// engine's height range become NaN as in the heightfield; RGBA8: grey, grey + alpha, RGB
// or RGBA unsigned char).
void ConvertTile(vtkDataArray* a, vtkGeoMipMapSampleTexture::Format f, int nx, int i0, int j0,
  int w, int h, std::vector<unsigned char>& out)
{
  const int comps = a->GetNumberOfComponents();
  if (f == vtkGeoMipMapSampleTexture::RGBA8)
  {
    out.resize(static_cast<size_t>(w) * h * 4);
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const vtkIdType k = static_cast<vtkIdType>(j0 + j) * nx + i0 + i;
        unsigned char* t = &out[(static_cast<size_t>(j) * w + i) * 4];
        double c[4] = { 0, 0, 0, 255 };
        for (int m = 0; m < comps && m < 4; ++m)
        {
          c[m] = a->GetComponent(k, m);
        }
        if (comps <= 2) // grey (+ alpha)
        {
          c[3] = comps == 2 ? c[1] : 255;
          c[1] = c[2] = c[0];
        }
        for (int m = 0; m < 4; ++m)
        {
          t[m] = static_cast<unsigned char>(std::min(255.0, std::max(0.0, c[m])));
        }
      }
    }
    return;
  }
  out.resize(static_cast<size_t>(w) * h * sizeof(float));
  float* t = reinterpret_cast<float*>(out.data());
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double v = a->GetComponent(static_cast<vtkIdType>(j0 + j) * nx + i0 + i, 0);
      t[static_cast<size_t>(j) * w + i] = std::abs(v) <= gmm::kMaxHeight
        ? static_cast<float>(v)
        : std::numeric_limits<float>::quiet_NaN();
    }
  }
}

} // namespace

//------------------------------------------------------------------------------
std::string vtkGeoMipMapTileLayout::Plan(int nx_, int ny_, int maxSize, int maxLayers)
{
  this->nx = nx_;
  this->ny = ny_;
  this->tilesX = (nx_ + maxSize - 1) / maxSize;
  this->tilesY = (ny_ + maxSize - 1) / maxSize;
  this->tileW = (nx_ + this->tilesX - 1) / this->tilesX;
  this->tileH = (ny_ + this->tilesY - 1) / this->tilesY;
  if (this->Layers() > maxLayers)
  {
    std::ostringstream why;
    why << nx_ << " x " << ny_ << " samples need " << this->Layers() << " texture layers of "
        << this->tileW << " x " << this->tileH << "; this OpenGL allows " << maxLayers;
    return why.str();
  }
  return std::string();
}

//------------------------------------------------------------------------------
vtkGeoMipMapSampleTexture::Format vtkGeoMipMapSampleTexture::FormatFor(vtkDataArray* a, bool asColors)
{
  if (asColors)
  {
    return RGBA8;
  }
  if (a->GetNumberOfComponents() == 1 && a->GetDataType() == VTK_SHORT)
  {
    return Int16;
  }
  if (a->GetNumberOfComponents() == 1 && a->GetDataType() == VTK_UNSIGNED_SHORT)
  {
    return UInt16;
  }
  return Float32;
}

size_t vtkGeoMipMapSampleTexture::BytesPerTexel(Format f)
{
  return f == Int16 || f == UInt16 ? 2 : 4; // RG16F: 2 x 2 bytes
}

vtkGeoMipMapSampleTexture::vtkGeoMipMapSampleTexture() = default;
vtkGeoMipMapSampleTexture::~vtkGeoMipMapSampleTexture() = default;

bool vtkGeoMipMapSampleTexture::IsCurrent(
  vtkDataArray* array, Format format, const vtkGeoMipMapTileLayout& layout) const
{
  return this->Handle != 0 && this->Source == array && this->SourceTime == array->GetMTime() &&
    this->Stored == format && this->Layout == layout;
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapSampleTexture::Upload(vtkOpenGLRenderWindow* win, vtkDataArray* array,
  Format format, const vtkGeoMipMapTileLayout& layout)
{
  const bool direct = UploadsDirectly(array, format);
  const unsigned char* base = static_cast<const unsigned char*>(array->GetVoidPointer(0));
  const size_t texel = BytesPerTexel(format);
  std::string err = this->UploadTiles(win, format, layout,
    [&](int i0, int j0, int w, int h, const void*& pixels, int& rowLength,
      std::vector<unsigned char>& scratch) {
      if (direct)
      {
        // Straight from the input: rows of nx samples, starting at the tile's corner.
        pixels = base + (static_cast<size_t>(j0) * layout.nx + i0) * texel;
        rowLength = layout.nx;
        return;
      }
      ConvertTile(array, format, layout.nx, i0, j0, w, h, scratch);
      pixels = scratch.data();
      rowLength = w;
    });
  if (err.empty())
  {
    this->Source = array;
    this->SourceTime = array->GetMTime();
  }
  return err;
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapSampleTexture::UploadSlopes(vtkOpenGLRenderWindow* win,
  const gmm::Heightfield& hf, vtkDataArray* source, const vtkGeoMipMapTileLayout& layout)
{
  std::string err = this->UploadTiles(win, Slopes16F, layout,
    [&](int i0, int j0, int w, int h, const void*& pixels, int& rowLength,
      std::vector<unsigned char>& scratch) {
      scratch.resize(static_cast<size_t>(w) * h * 2 * sizeof(uint16_t));
      uint16_t* out = reinterpret_cast<uint16_t*>(scratch.data());
      // Halves made here, on all cores: Mesa converts a GL_FLOAT upload to RG16F texel by
      // texel on one thread. The band's rows go to the cores in chunks (a band is a few MB:
      // each chunk is worth a thread's while).
      auto rows = [&](int first, int last) {
        for (int j = first; j < last; ++j)
        {
          for (int i = i0; i < i0 + w; ++i)
          {
            uint16_t* t = out + 2 * ((static_cast<size_t>(j - j0)) * w + (i - i0));
            t[0] = gmm::halfOf(static_cast<float>(gmm::sampleSlope(hf, i, j, true)));
            t[1] = gmm::halfOf(static_cast<float>(gmm::sampleSlope(hf, i, j, false)));
          }
        }
      };
      constexpr std::size_t kRowsPerChunk = 64;
      gmm::parallelChunks(static_cast<std::size_t>(h), kRowsPerChunk, 0,
        [&](std::size_t first, std::size_t last) { rows(j0 + static_cast<int>(first), j0 + static_cast<int>(last)); });
      pixels = scratch.data();
      rowLength = w;
    });
  if (err.empty())
  {
    this->Source = source;
    this->SourceTime = source->GetMTime();
  }
  return err;
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapSampleTexture::UploadTiles(vtkOpenGLRenderWindow* win, Format format,
  const vtkGeoMipMapTileLayout& layout, const TileSource& source)
{
  this->Release(win);
  const GLFormat gl = GLFormatOf(format);
  const size_t texel = BytesPerTexel(format);
  while (glGetError() != GL_NO_ERROR)
  {
    // Errors of earlier calls are not ours to report.
  }
  glGenTextures(1, &this->Handle);
  this->Unit->SetContext(win);
  this->Unit->AssignToExistingTexture(this->Handle, GL_TEXTURE_2D_ARRAY);
  this->Unit->Activate();
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
  if (format == Slopes16F)
  {
    this->Unit->SetMinificationFilter(vtkTextureObject::Linear);
    this->Unit->SetMagnificationFilter(vtkTextureObject::Linear);
  }
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, gl.internal, layout.tileW, layout.tileH, layout.Layers(), 0,
    gl.format, gl.type, nullptr);
  GLenum err = glGetError();
  if (err == GL_NO_ERROR)
  {
    std::vector<unsigned char> scratch;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int ty = 0; ty < layout.tilesY && err == GL_NO_ERROR; ++ty)
    {
      for (int tx = 0; tx < layout.tilesX && err == GL_NO_ERROR; ++tx)
      {
        const int i0 = tx * layout.tileW, j0 = ty * layout.tileH;
        const int w = std::min(layout.tileW, layout.nx - i0), h = std::min(layout.tileH, layout.ny - j0);
        // In bands of rows: data converted or computed on the way (scratch) never takes
        // more than about kBandBytes, whatever the DEM's size.
        constexpr size_t kBandBytes = size_t(16) << 20;
        const int band = static_cast<int>(std::max<size_t>(1, kBandBytes / (static_cast<size_t>(w) * 8)));
        for (int jb = 0; jb < h && err == GL_NO_ERROR; jb += band)
        {
          const int hb = std::min(band, h - jb);
          const void* pixels = nullptr;
          int rowLength = w;
          source(i0, j0 + jb, w, hb, pixels, rowLength, scratch);
          glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength == w ? 0 : rowLength);
          glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, jb, ty * layout.tilesX + tx, w, hb, 1,
            gl.format, gl.type, pixels);
          err = glGetError();
        }
      }
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  }
  this->Unit->Deactivate();
  if (err != GL_NO_ERROR)
  {
    std::ostringstream why;
    why << "OpenGL could not store " << layout.nx << " x " << layout.ny << " samples ("
        << (layout.Layers() * static_cast<double>(layout.tileW) * layout.tileH * texel / 1048576.0)
        << " MiB in " << layout.Layers() << " layers of " << layout.tileW << " x " << layout.tileH
        << "): " << (err == GL_OUT_OF_MEMORY ? "out of memory" : "error ") << std::hex
        << (err == GL_OUT_OF_MEMORY ? 0u : err);
    this->Release(win);
    return why.str();
  }
  this->Stored = format;
  this->Bytes = static_cast<size_t>(layout.Layers()) * layout.tileW * layout.tileH * texel;
  this->Layout = layout;
  return std::string();
}

//------------------------------------------------------------------------------
int vtkGeoMipMapSampleTexture::Activate()
{
  this->Unit->Activate();
  return this->Unit->GetTextureUnit();
}

void vtkGeoMipMapSampleTexture::Deactivate()
{
  this->Unit->Deactivate();
}

void vtkGeoMipMapSampleTexture::Release(vtkWindow* win)
{
  if (this->Handle)
  {
    this->Unit->ReleaseGraphicsResources(win); // frees its unit; does not own the handle
    glDeleteTextures(1, &this->Handle);
    this->Handle = 0;
  }
  this->Bytes = 0;
  this->Source = nullptr;
  this->SourceTime = 0;
}

void vtkGeoMipMapSampleTexture::Forget()
{
  this->Handle = 0;
  this->Bytes = 0;
  this->Source = nullptr;
  this->SourceTime = 0;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapColorTable::EntriesFor(vtkScalarsToColors* lut)
{
  const vtkIdType n = lut->GetNumberOfAvailableColors();
  return static_cast<int>(std::max<vtkIdType>(256, std::min<vtkIdType>(4096, n)));
}

vtkGeoMipMapColorTable::vtkGeoMipMapColorTable() = default;
vtkGeoMipMapColorTable::~vtkGeoMipMapColorTable() = default;

void vtkGeoMipMapColorTable::Update(
  vtkOpenGLRenderWindow* win, vtkScalarsToColors* lut, const double range[2])
{
  if (this->Texture->GetHandle() && this->Source == lut && this->SourceTime == lut->GetMTime() &&
    this->Range[0] == range[0] && this->Range[1] == range[1])
  {
    return;
  }
  this->Source = lut;
  this->SourceTime = lut->GetMTime();
  this->Range[0] = range[0];
  this->Range[1] = range[1];
  this->LogScale = lut->UsingLogScale() != 0 && range[0] > 0.0 && range[1] > 0.0;
  const int n = EntriesFor(lut);
  this->Entries = n;
  // Entry k holds the colour of the centre of bin k of the (linear or log) range, as the
  // lookup table maps it; the shader picks the bin of each fragment's value.
  std::vector<unsigned char> rgba(static_cast<size_t>(n + 3) * 4);
  auto put = [&rgba, lut](int texel, double v) {
    const unsigned char* c = lut->MapValue(v);
    std::copy(c, c + 4, &rgba[static_cast<size_t>(texel) * 4]);
  };
  const double lo = range[0], hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  const double a = this->LogScale ? std::log10(lo) : lo, b = this->LogScale ? std::log10(hi) : hi;
  auto valueAt = [&](double t) { return this->LogScale ? std::pow(10.0, a + t * (b - a)) : a + t * (b - a); };
  put(0, valueAt(-1e-3));
  for (int k = 0; k < n; ++k)
  {
    put(k + 1, valueAt((k + 0.5) / n));
  }
  put(n + 1, valueAt(1.0 + 1e-3));
  put(n + 2, std::numeric_limits<double>::quiet_NaN());
  this->Texture->SetContext(win);
  this->Texture->Create2DFromRaw(n + 3, 1, 4, VTK_UNSIGNED_CHAR, rgba.data());
}

int vtkGeoMipMapColorTable::Activate()
{
  this->Texture->Activate();
  return this->Texture->GetTextureUnit();
}

void vtkGeoMipMapColorTable::Deactivate()
{
  this->Texture->Deactivate();
}

void vtkGeoMipMapColorTable::Release(vtkWindow* win)
{
  this->Texture->ReleaseGraphicsResources(win);
  this->Source = nullptr;
}

size_t vtkGeoMipMapColorTable::GetBytes() const
{
  return this->Entries > 0 ? static_cast<size_t>(this->Entries + 3) * 4 : 0;
}

//------------------------------------------------------------------------------
vtkGeoMipMapDrapeTexture::vtkGeoMipMapDrapeTexture() = default;
vtkGeoMipMapDrapeTexture::~vtkGeoMipMapDrapeTexture() = default;

bool vtkGeoMipMapDrapeTexture::HasData() const
{
  return this->Texture->GetHandle() != 0 && this->Source != nullptr;
}

std::string vtkGeoMipMapDrapeTexture::Update(vtkOpenGLRenderWindow* win, vtkImageData* image)
{
  vtkDataArray* rgb = image->GetPointData()->GetScalars();
  const vtkMTimeType time = std::max(image->GetMTime(), rgb ? rgb->GetMTime() : 0);
  if (this->HasData() && this->Source == image && this->SourceTime == time)
  {
    return std::string();
  }
  this->Release(win);
  int dims[3];
  image->GetDimensions(dims);
  const int comps = rgb ? rgb->GetNumberOfComponents() : 0;
  std::ostringstream why;
  if (!rgb || rgb->GetDataType() != VTK_UNSIGNED_CHAR || (comps != 3 && comps != 4))
  {
    why << "its point scalars are not unsigned char RGB or RGBA";
    return why.str();
  }
  if (dims[2] != 1 || dims[0] < 1 || dims[1] < 1)
  {
    why << "it is not a 2D image (" << dims[0] << " x " << dims[1] << " x " << dims[2] << ")";
    return why.str();
  }
  if (!image->GetDirectionMatrix()->IsIdentity())
  {
    why << "it is not axis-aligned (its direction matrix is not the identity)";
    return why.str();
  }
  const int maxSize = vtkTextureObject::GetMaximumTextureSize(win);
  if (dims[0] > maxSize || dims[1] > maxSize)
  {
    why << "it is " << dims[0] << " x " << dims[1] << " pixels, more than this OpenGL's "
        << "largest texture (" << maxSize << " a side): make it smaller "
        << "(vtkGeoMipMapImageDrape::SetMaximumSize)";
    return why.str();
  }
  // RGBA, premultiplied by alpha: filtering and mipmaps then blend the image's edge into
  // the terrain's own colour instead of into black.
  const size_t n = static_cast<size_t>(dims[0]) * dims[1];
  std::vector<unsigned char> texels(n * 4);
  const unsigned char* src = static_cast<const unsigned char*>(rgb->GetVoidPointer(0));
  for (size_t k = 0; k < n; ++k)
  {
    const unsigned a = comps == 4 ? src[4 * k + 3] : 255u;
    for (int c = 0; c < 3; ++c)
    {
      texels[4 * k + c] = static_cast<unsigned char>((src[comps * k + c] * a + 127) / 255);
    }
    texels[4 * k + 3] = static_cast<unsigned char>(a);
  }
  while (glGetError() != GL_NO_ERROR)
  {
    // Errors of earlier calls are not ours to report.
  }
  vtkTextureObject* t = this->Texture;
  t->SetContext(win);
  t->SetGenerateMipmap(true);
  t->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
  t->SetMagnificationFilter(vtkTextureObject::Linear);
  t->SetWrapS(vtkTextureObject::ClampToBorder);
  t->SetWrapT(vtkTextureObject::ClampToBorder);
  t->SetBorderColor(0.0f, 0.0f, 0.0f, 0.0f);
  // No anisotropic filtering: at 8x, llvmpipe moved texels by up to a pixel even in a
  // view from straight above (TestDrape's markers, 1.05 px against 0.06 px without).
  t->SetMaximumAnisotropicFiltering(1.0f);
  if (!t->Create2DFromRaw(dims[0], dims[1], 4, VTK_UNSIGNED_CHAR, texels.data()) ||
    glGetError() != GL_NO_ERROR)
  {
    t->ReleaseGraphicsResources(win);
    why << "OpenGL could not store its " << dims[0] << " x " << dims[1] << " pixels";
    return why.str();
  }
  double p0[3], p1[3];
  image->TransformIndexToPhysicalPoint(0, 0, 0, p0);
  image->TransformIndexToPhysicalPoint(1, 1, 0, p1);
  this->First[0] = p0[0];
  this->First[1] = p0[1];
  this->Step[0] = p1[0] - p0[0];
  this->Step[1] = p1[1] - p0[1];
  this->Size[0] = dims[0];
  this->Size[1] = dims[1];
  this->Bytes = n * 4 * 4 / 3; // with its mipmaps
  this->Source = image;
  this->SourceTime = time;
  return std::string();
}

void vtkGeoMipMapDrapeTexture::GetMap(double x0, double y0, double dx, double dy, float map[4]) const
{
  // s = ((x0 + g.x dx - First.x) / Step.x + 0.5) / width, likewise t: computed in double,
  // handed to the shader as one multiply-add per axis.
  map[0] = static_cast<float>(dx / this->Step[0] / this->Size[0]);
  map[1] = static_cast<float>(dy / this->Step[1] / this->Size[1]);
  map[2] = static_cast<float>(((x0 - this->First[0]) / this->Step[0] + 0.5) / this->Size[0]);
  map[3] = static_cast<float>(((y0 - this->First[1]) / this->Step[1] + 0.5) / this->Size[1]);
}

int vtkGeoMipMapDrapeTexture::Activate()
{
  this->Texture->Activate();
  return this->Texture->GetTextureUnit();
}

void vtkGeoMipMapDrapeTexture::Deactivate()
{
  this->Texture->Deactivate();
}

void vtkGeoMipMapDrapeTexture::Release(vtkWindow* win)
{
  this->Texture->ReleaseGraphicsResources(win);
  this->Source = nullptr;
  this->SourceTime = 0;
  this->Bytes = 0;
}
