/**
 * @file   vtkGeoMipMapShaders.h
 * @brief  What vtkGeoMipMapMapper changes in vtkOpenGLPolyDataMapper's shaders.
 *
 * VTK generates the shaders (lighting, textures, clipping, picking, edges, render passes);
 * these functions make them read the terrain from textures instead of vertex buffers:
 * - vertex shader: vertexMC is computed from gl_VertexID (sample j * nx + i) and the height
 *   texture, relative to an anchor sample near the camera (the mapper's camera matrices
 *   carry the anchor's position, in double), so large coordinates keep their precision;
 *   the grid position (i, j) goes to the fragment shader; texture coordinates are
 *   (i / (nx - 1), j / (ny - 1)). With Morph, the height is first placed as
 *   gmm::morphedHeight places it (Morph.h: glided edges' samples on their polylines, then
 *   geomorphing toward the morph target), from the morph texture.
 * - fragment shader: the normal (when lit) comes from the full-resolution slopes at the
 *   fragment's grid position (bilinearly filtered on a one-layer DEM, interpolated on the
 *   level-0 triangle under the fragment otherwise), so shading does not depend on the level
 *   drawn; a second scalar array or RGB(A) colours are interpolated on that triangle;
 *   colouring by height uses the drawn surface's height, interpolated from the vertices;
 *   a draped image (texture coordinates affine in the grid position) is laid over that
 *   colour by its alpha, before lighting.
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapShaders_h
#define vtkGeoMipMapShaders_h

#include "vtkShader.h" // For vtkShader::Type

#include <map>    // For std::map
#include <string> // For std::string

namespace vtkGeoMipMapShaders
{
// How heights are stored and what colours the surface.
struct Options
{
  enum Heights
  {
    FloatHeights,
    Int16Heights,
    UInt16Heights
  } HeightFormat = FloatHeights;
  enum Coloring
  {
    PropertyColor, // the actor's colour
    MapHeights,    // the height texture through the lookup table
    MapScalars,    // a separate float scalar texture through the lookup table
    DirectColors   // an RGBA texture
  } Color = PropertyColor;
  bool TextureCoordinates = false; // the actor is textured
  bool SingleLayer = true;         // the heights fit one texture layer
  bool LogScale = false;           // the lookup table maps log10 of the scalars
  bool Drape = false;              // an image is draped over the colouring
  bool Morph = false;              // vertices placed from vtkGeoMipMapMorphTexture.h
  int HeightBands = 0; // > 0: heights read in place from this many buffer textures
                       // (vtkGeoMipMapSharedHeights.h) instead of the height texture
  int HeightsPerTexel = 1; // samples in one texel of those buffer textures (a power of two)
  bool SlopesFromHeights = false; // lit: slopes computed per fragment, no slope texture
  bool VertexNormals = false; // lit: normals at the vertices, interpolated (no fragment normal)

  /** A short string that differs when the shader source must differ. */
  std::string Key() const;
};

/**
 * Before VTK's own replacements: leaves markers next to the tags VTK consumes.
 */
void PrepareTemplates(std::map<vtkShader::Type, vtkShader*>& shaders);

/**
 * After VTK's replacements: the terrain code. VTK must have been given a proxy with
 * normals (and texture coordinates when textured) so that it declared them.
 */
void InsertTerrainCode(std::map<vtkShader::Type, vtkShader*>& shaders, const Options& options);
}

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapShaders.h
