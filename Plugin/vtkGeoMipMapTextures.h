/**
 * @file   vtkGeoMipMapTextures.h
 * @brief  GPU storage of per-sample DEM data for vtkGeoMipMapMapper: one texel per sample.
 *
 * vtkGeoMipMapSampleTexture holds one value (or an RGBA colour) per DEM sample in a 2D
 * array texture. A DEM wider or taller than GL_MAX_TEXTURE_SIZE is cut into tiles of
 * tileW x tileH texels, one layer each, that do not overlap: sample (i, j) lives in layer
 * (j / tileH) * tilesX + i / tileW at texel (i % tileW, j % tileH). The shaders fetch
 * exact texels (texelFetch), so tiles need no shared borders and show no seams; each
 * layer is uploaded on its own (glTexSubImage3D straight from the input array, no CPU
 * copy for float and 16-bit data), so tiles can later be made resident one at a time.
 *
 * Storage: float heights as R32F, 16-bit integer heights as R16I / R16UI (converted to
 * metres in the shader), other scalar types as R32F (converted tile by tile), unsigned
 * char RGB(A) colours as RGBA8, and the heights' slopes as RG16F (computed tile by tile:
 * the fragment shader's normals, 4 fetches instead of 12 height fetches).
 *
 * vtkGeoMipMapColorTable holds a lookup table as a 1D row of colours for the shader.
 *
 * vtkGeoMipMapDrapeTexture holds an image draped over the terrain (an orthophoto brought
 * into the terrain's frame, vtkGeoMipMapImageDrape) at its own resolution: one RGBA8 2D
 * texture, premultiplied by alpha, mipmapped, bordered by transparent texels, with the
 * affine map from the terrain's grid position to texture coordinates.
 *
 * Both live in one OpenGL context; the mapper releases them when it changes window.
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapTextures_h
#define vtkGeoMipMapTextures_h

#include "vtkNew.h"
#include "vtkType.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace gmm
{
struct Heightfield;
}
class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkScalarsToColors;
class vtkTextureObject;
class vtkWindow;

// How samples are split into layers.
struct vtkGeoMipMapTileLayout
{
  int nx = 0, ny = 0;         // samples
  int tileW = 0, tileH = 0;   // texels per layer
  int tilesX = 0, tilesY = 0; // layers = tilesX * tilesY

  /**
   * The fewest tiles per axis whose size fits maxSize, sized evenly (so a 16385 x 16385
   * DEM under a 16384 limit takes 2 x 2 layers of 8193 x 8193, not 4 of 16384). Returns ""
   * or why it cannot fit (more layers than maxLayers).
   */
  std::string Plan(int nx, int ny, int maxSize, int maxLayers);
  int Layers() const { return this->tilesX * this->tilesY; }
  bool operator==(const vtkGeoMipMapTileLayout& o) const
  {
    return nx == o.nx && ny == o.ny && tileW == o.tileW && tileH == o.tileH && tilesX == o.tilesX &&
      tilesY == o.tilesY;
  }
};

class vtkGeoMipMapSampleTexture
{
public:
  enum Format
  {
    Float32,
    Int16,
    UInt16,
    RGBA8,
    Slopes16F // two half floats per sample (dh/dx, dh/dy), computed by UploadSlopes
  };

  /**
   * The texel format that stores `array` (component 0, or colours when `asColors`).
   */
  static Format FormatFor(vtkDataArray* array, bool asColors);
  static size_t BytesPerTexel(Format f);

  vtkGeoMipMapSampleTexture();
  ~vtkGeoMipMapSampleTexture();

  /**
   * Uploads `array` (layout.nx * layout.ny tuples) in `format`. Returns "" or the reason
   * (the driver ran out of memory, the window cannot make the texture); nothing is held
   * then. The window's context must be current.
   */
  std::string Upload(vtkOpenGLRenderWindow* win, vtkDataArray* array, Format format,
    const vtkGeoMipMapTileLayout& layout);

  /**
   * Uploads the slopes of the engine's heights `hf` as Slopes16F: dh/dx and dh/dy by
   * gmm::sampleSlope (Heightfield.h). `source` identifies the heights for IsCurrent.
   */
  std::string UploadSlopes(vtkOpenGLRenderWindow* win, const gmm::Heightfield& hf,
    vtkDataArray* source, const vtkGeoMipMapTileLayout& layout);

  bool IsCurrent(vtkDataArray* array, Format format, const vtkGeoMipMapTileLayout& layout) const;
  bool HasData() const { return this->Handle != 0; }
  Format GetFormat() const { return this->Stored; }
  size_t GetBytes() const { return this->Bytes; }

  /** Binds to a free texture unit (returned) for a draw; Deactivate() after it. */
  int Activate();
  void Deactivate();

  /** Deletes the texture; `win`'s context must be current (the mapper pushes it). */
  void Release(vtkWindow* win);

  /** Drops the handle without a GL call: its context (window) is gone, and it with it. */
  void Forget();

private:
  vtkGeoMipMapSampleTexture(const vtkGeoMipMapSampleTexture&) = delete;
  void operator=(const vtkGeoMipMapSampleTexture&) = delete;

  // Fills the texels of one tile (i0, j0, w x h samples): either points `pixels` at data
  // laid out with a row length of `rowLength` texels, or writes `scratch` (row length w).
  using TileSource = std::function<void(int i0, int j0, int w, int h, const void*& pixels,
    int& rowLength, std::vector<unsigned char>& scratch)>;
  std::string UploadTiles(vtkOpenGLRenderWindow* win, Format format,
    const vtkGeoMipMapTileLayout& layout, const TileSource& source);

  unsigned int Handle = 0;
  vtkNew<vtkTextureObject> Unit; // texture-unit bookkeeping of the window, around Handle
  Format Stored = Float32;
  size_t Bytes = 0;
  vtkDataArray* Source = nullptr; // identity only, never dereferenced
  vtkMTimeType SourceTime = 0;
  vtkGeoMipMapTileLayout Layout;
};

class vtkGeoMipMapColorTable
{
public:
  /**
   * Number of table entries: the lookup table's own colour count, within [256, 4096].
   * Texel 0 is the below-range colour, texels 1..N the table, N + 1 above range, N + 2
   * the NaN colour, all as the lookup table maps them.
   */
  static int EntriesFor(vtkScalarsToColors* lut);

  vtkGeoMipMapColorTable();
  ~vtkGeoMipMapColorTable();

  /** Rebuilds when the table or the range changed. */
  void Update(vtkOpenGLRenderWindow* win, vtkScalarsToColors* lut, const double range[2]);
  int Activate();
  void Deactivate();
  void Release(vtkWindow* win);
  int GetEntries() const { return this->Entries; }
  bool GetLogScale() const { return this->LogScale; }
  const double* GetRange() const { return this->Range; }
  size_t GetBytes() const;

private:
  vtkGeoMipMapColorTable(const vtkGeoMipMapColorTable&) = delete;
  void operator=(const vtkGeoMipMapColorTable&) = delete;

  vtkNew<vtkTextureObject> Texture;
  vtkScalarsToColors* Source = nullptr;
  vtkMTimeType SourceTime = 0;
  double Range[2] = { 0.0, 1.0 };
  int Entries = 0;
  bool LogScale = false;
};

class vtkGeoMipMapDrapeTexture
{
public:
  vtkGeoMipMapDrapeTexture();
  ~vtkGeoMipMapDrapeTexture();

  /**
   * Uploads `image` (2D, axis-aligned, unsigned char RGB or RGBA point scalars; pixel
   * centres at its points) unless it is the one stored already. Returns "" or why it
   * cannot be stored (larger than GL_MAX_TEXTURE_SIZE, wrong type); nothing is held then.
   */
  std::string Update(vtkOpenGLRenderWindow* win, vtkImageData* image);
  bool HasData() const;
  size_t GetBytes() const { return this->Bytes; }

  /**
   * Texture coordinates of the terrain's grid position g (sample i, j of a grid whose
   * sample (0, 0) is at (x0, y0), spacing dx, dy): st = g * map[0..1] + map[2..3].
   */
  void GetMap(double x0, double y0, double dx, double dy, float map[4]) const;

  int Activate();
  void Deactivate();
  void Release(vtkWindow* win);

private:
  vtkGeoMipMapDrapeTexture(const vtkGeoMipMapDrapeTexture&) = delete;
  void operator=(const vtkGeoMipMapDrapeTexture&) = delete;

  vtkNew<vtkTextureObject> Texture;
  vtkImageData* Source = nullptr; // identity only, never dereferenced
  vtkMTimeType SourceTime = 0;
  double First[2] = { 0, 0 }; // centre of pixel (0, 0)
  double Step[2] = { 1, 1 };  // pixel spacing (signed)
  int Size[2] = { 0, 0 };
  size_t Bytes = 0;
};

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapTextures.h
