/**
 * @file   vtkGeoMipMapMorphTexture.h
 * @brief  The per-frame geomorph data of vtkGeoMipMapMapper on the GPU (Morph.h).
 *
 * Two textures, so that the vertex shader (vtkGeoMipMapShaders.h) places and moves a
 * vertex exactly as gmm::morphedHeight does, from its sample (i, j) alone:
 * - gmmMorph, RGB32F 2D, texel = (target level, factor, edge level) of a block or a shared
 *   edge (the edge level: the polyline a glided edge's samples are drawn on, EdgeHeights.h;
 *   -1 for a block or an edge not drawn):
 *     rows [0, br):          blocks (c, r)
 *     rows [br, 2 br):       vertical edges (line 0..bc, r)
 *     rows [2 br, 3 br + 1): horizontal edges (c, line 0..br)
 *   with bc x br blocks, in columns [0, max(bc, br) + 1), and beside them, from column
 *   max(bc, br) + 1 on, the block corners (line 0..bc, line 0..br) in rows [0, br + 1),
 *   texel = (the merging node's fan height there, factor, unused) (gmm::MorphFrame::cornerT).
 *   It is the only data uploaded per frame for placing vertices (a few bytes per block);
 *   nothing per vertex. Uploaded with geomorphing off too (factors 0):
 *   glided edges need their levels.
 * - gmmSampleBands, RGBA32F 2D, made once per quadtree: the block band of every sample
 *   column, then of every sample row, as (band, first sample, last sample), 2^w texels a
 *   row, at most 64 (column i at (i mod 2^w, i >> w); row j likewise after the columns'
 *   rows). One
 *   fetch finds a vertex's band: the binary search over the band starts that it replaces
 *   cost each vertex a loop of fetches, which llvmpipe runs to the longest lane.
 * Lives in one OpenGL context.
 *
 * Per frame only the texels of the blocks drawn now or at the last upload (gmm::MorphFrame
 * ::blocks) and their edges, and of the corners moving now or then, are rewritten, and only
 * each row's span of changed texels is uploaded (glTexSubImage2D): a frozen frame uploads
 * nothing, and the CPU work follows the drawn blocks, not the DEM (65 536 blocks at 16385²,
 * block 64). A new layout or context builds the texture whole.
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapMorphTexture_h
#define vtkGeoMipMapMorphTexture_h

#include "vtkNew.h"

#include <cstddef> // For size_t
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;
namespace gmm
{
struct MorphFrame;
struct Quadtree;
}

class vtkGeoMipMapMorphTexture
{
public:
  vtkGeoMipMapMorphTexture();
  ~vtkGeoMipMapMorphTexture();

  /**
   * Uploads one frame's morph data. Returns "" or why it cannot be stored (more blocks or
   * samples than the texture or a float index can hold): the mapper then draws unmorphed.
   */
  std::string Update(vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt, const gmm::MorphFrame& frame);
  bool HasData() const;
  /** Binds a texture unit for a draw; Deactivate() after it. */
  void Activate();
  void Deactivate();
  /** gmmMorph, gmmSampleBands (the units), gmmMorphLayout (bc, br), gmmSampleBandsLayout. */
  void SetUniforms(vtkShaderProgram* program) const;
  void Release(vtkWindow* win);
  void Forget();
  size_t GetBytes() const { return this->Data.size() * sizeof(float) + this->BandBytes; }
  /** Bytes the last Update uploaded (0 when no texel changed). */
  size_t GetLastUploadBytes() const { return this->LastUploadBytes; }

private:
  vtkGeoMipMapMorphTexture(const vtkGeoMipMapMorphTexture&) = delete;
  void operator=(const vtkGeoMipMapMorphTexture&) = delete;

  std::string Build(vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt, const gmm::MorphFrame& frame);
  std::string BuildSampleBands(vtkOpenGLRenderWindow* win, const gmm::Quadtree& qt);

  vtkNew<vtkTextureObject> Texture;
  vtkNew<vtkTextureObject> SampleBands;
  int SampleBandsLayout[2] = { 0, 0 }; // log2 texels a row, rows of the column entries
  std::vector<int> ColStart, RowStart;  // the band starts gmmSampleBands was made from
  size_t BandBytes = 0;
  std::vector<float> Data;
  std::vector<int> Written; // the blocks whose texels the last upload set from a frame
  std::vector<int> WrittenCorners; // the corners (MorphFrame::corners) the last upload set
  std::vector<int> SpanLo, SpanHi; // per row, the texels an Update changed (scratch)
  int Blocks[2] = { 0, 0 };
  int Size[2] = { 0, 0 };
  int Unit = -1;
  int BandsUnit = -1;
  size_t LastUploadBytes = 0;
};

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapMorphTexture.h
