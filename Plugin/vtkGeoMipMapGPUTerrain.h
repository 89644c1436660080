/**
 * @file   vtkGeoMipMapGPUTerrain.h
 * @brief  Everything vtkGeoMipMapMapper keeps on the GPU for one DEM, in one OpenGL context.
 *
 * The heights (always), their slopes (while lit), a colouring array (another point array
 * through the lookup table, or RGB(A) colours) and the lookup table, all in one tile
 * layout (vtkGeoMipMapTextures.h); and a draped image (vtkGeoMipMapDrapeTexture), at its
 * own resolution. Update() uploads only what changed; Bind() / Unbind()
 * hold texture units around a draw; SetUniforms() hands the shaders
 * (vtkGeoMipMapShaders.h) what they read. The shader options (height format, colouring,
 * layers, log scale) follow from what is stored.
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapGPUTerrain_h
#define vtkGeoMipMapGPUTerrain_h

#include "vtkGeoMipMapShaders.h"       // For vtkGeoMipMapShaders::Options
#include "vtkGeoMipMapSharedHeights.h" // For the heights read in place
#include "vtkGeoMipMapTextures.h"      // For the textures

#include <string> // For std::string
#include <vector> // For std::vector

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkScalarsToColors;
class vtkShaderProgram;
class vtkWindow;

namespace gmm
{
struct Heightfield;
}

class vtkGeoMipMapGPUTerrain
{
public:
  // What to store. `heights` is the array the engine's heightfield `hf` was made from.
  struct Inputs
  {
    vtkDataArray* Heights = nullptr;
    const gmm::Heightfield* HF = nullptr;
    bool Lit = false;           // slopes wanted for the fragment normals
    bool SlopeTexture = false;  // lit: slopes from a texture (kept), else from the heights per fragment
    bool VertexNormals = false; // lit: this frame's normals per vertex from the heights
    int MaximumTileSize = 0;    // 0: GL_MAX_TEXTURE_SIZE
    bool ShareHeights = true;   // read the heights in place where the renderer allows
                                // (vtkGeoMipMapSharedHeights::Usable)
    vtkDataArray* Color = nullptr; // colouring array, or null for the actor's colour
    bool DirectColors = false;  // Color holds unsigned char colours, not scalars
    vtkScalarsToColors* Lookup = nullptr; // for scalars, its range already set
    vtkImageData* Drape = nullptr; // image draped over the terrain, or null
  };
  // What Update did.
  struct Result
  {
    std::string HeightsError; // the heights (or slopes) could not be stored: do not draw
    std::string ColorError;   // the colouring array could not be stored: actor's colour
    std::string DrapeError;   // the drape could not be stored: drawn without it
    std::string ShareError;   // the heights could not be read in place: a texture holds them
    int Uploads = 0;          // arrays uploaded (heights, colouring)
    double UploadSeconds = 0.0;
  };

  Result Update(vtkOpenGLRenderWindow* win, const Inputs& inputs);

  const vtkGeoMipMapShaders::Options& GetShading() const { return this->Shading; }
  void SetTextureCoordinates(bool on) { this->Shading.TextureCoordinates = on; }
  void SetMorph(bool on) { this->Shading.Morph = on; }
  bool HasHeights() const { return this->Heights.HasData() || this->Shared.HasData(); }
  /** True when the heights are read in place (no height texture). */
  bool SharesHeights() const { return this->Shared.HasData(); }
  size_t GetBytes() const;

  /** Texture units for a draw; Unbind() after it. */
  void Bind();
  void Unbind();

  /**
   * The terrain uniforms: grid, tiles, spacing, height scale, anchor sample and reference
   * height (model coordinates are relative to them), texture units and the colour map.
   */
  void SetUniforms(vtkShaderProgram* program, const gmm::Heightfield& hf, double heightScale,
    int anchorI, int anchorJ, float heightRef) const;

  /** Deletes the textures; `win`'s context must be current. */
  void Release(vtkWindow* win);
  /** Drops the handles without GL calls: their context is gone. */
  void Forget();

private:
  vtkGeoMipMapTileLayout Layout;
  vtkGeoMipMapSampleTexture Heights;
  vtkGeoMipMapSharedHeights Shared; // instead of Heights, where it applies
  std::vector<int> BandUnits;
  vtkGeoMipMapSampleTexture Slopes;
  vtkGeoMipMapSampleTexture Colors;
  vtkGeoMipMapColorTable Table;
  vtkGeoMipMapDrapeTexture Drape;
  vtkGeoMipMapShaders::Options Shading;
  bool Lit = false;
  int HeightsUnit = -1, SlopesUnit = -1, ColorsUnit = -1, TableUnit = -1, DrapeUnit = -1;
};

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapGPUTerrain.h
