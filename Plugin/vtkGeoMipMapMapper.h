/**
 * @class   vtkGeoMipMapMapper
 * @brief   Draws a heightfield image with view-dependent GeoMipMapping level of detail,
 *          the heights resident on the GPU.
 *
 * Input: a 2D vtkImageData (nx x ny x 1) whose active point scalars are heights, any
 * numeric type (vtkDEMReader's output plugs in directly, as does
 * vtkGeoMipMapTerrainReader's "Elevation"). NaN marks nodata: no triangle touches it.
 * The surface is at (x, y, origin z + HeightScale * h), as vtkWarpScalar would put it.
 *
 * Memory: each height is stored once on the GPU, in a 2D array texture (float, or 16-bit
 * integers as they are for short / unsigned short input), split into layers when the DEM
 * is larger than GL_MAX_TEXTURE_SIZE. There is no vertex buffer: the vertex shader makes
 * each vertex from its sample index and the height texture. On the CPU the engine's
 * quadtree and error tables (vtkGeoMipMapTerrain, shared with every other mapper and
 * filter of the same image) share float heights with the input. Before the first upload
 * the mapper estimates what the DEM needs and refuses a DEM that does not fit the
 * MemoryLimit (default: the memory available now) with an error naming both; a driver
 * that still runs out of memory is reported and the frame goes on without the terrain.
 *
 * Every render it converts the renderer's active camera, viewport and the actor's matrix
 * to a gmm::View, runs the engine with PixelError and draws the selected triangles; only
 * the triangle index buffer is re-uploaded, and only when the indices changed. The
 * certified bound is exact under any invertible affine actor matrix (non-uniform scale
 * and shear included) and HeightScale; culling follows the camera's exact projection
 * (window centre and view shear included); the bound assumes no view shear.
 *
 * Shading comes from the full-resolution heights: the fragment shader computes each
 * fragment's normal from them (central differences, interpolated on the full-resolution
 * triangle under the fragment), or the vertex shader each drawn vertex's (NormalMode: by
 * default per fragment on a GPU, per vertex on a CPU renderer in frames certified within
 * a pixel), and each fragment's scalar colour from the
 * full-resolution samples of the colouring array (interpolated, then mapped through the
 * lookup table: InterpolateScalarsBeforeMapping is implied). Colouring: point scalars
 * (the heights, or another point array selected with SelectColorArray / ScalarMode),
 * one component through the lookup table (linear or log scale, below/above-range and
 * NaN colours as the table maps them), or unsigned char RGB(A) arrays as direct colours
 * (ColorMode default). Cell scalars are not supported (the surface takes the actor's
 * colour, with an error).
 *
 * Geomorphing (SetGeomorphing, on by default): vertices glide toward a block's next coarser
 * level as it nears its switch, in the vertex shader, from a small per-frame texture of
 * per-block and per-edge factors; the morphed surface keeps the certified bound.
 *
 * Frame budgets: SetTriangleBudget caps the triangles of every frame, and with
 * FollowAllocatedRenderTime on, interactive renders (a window DesiredUpdateRate above the
 * interactor's StillUpdateRate) get the budget that fits the actor's AllocatedRenderTime,
 * learnt from this mapper's own recent frames; the frame then reports the smallest
 * certified error that budget allows. Still renders go back to PixelError alone. Blocks
 * and merged nodes are drawn front to back (FrontToBack) so the depth test rejects hidden
 * fragments early.
 *
 * Draped imagery: SetDrapeImage lays a georeferenced image (an orthophoto brought into
 * the terrain's frame by vtkGeoMipMapImageDrape) over the terrain at its own resolution.
 *
 * Works as with vtkOpenGLPolyDataMapper: lighting, LUT colouring, a texture stretched over
 * the extent (actor texture; texture coordinates 0..1 over the samples), actor transforms, parallel
 * projection, clipping planes, surface / wireframe / points representations and surface
 * with edges, several renderers and several render windows (the GPU data follow the
 * window being rendered), vtkPropPicker and vtkWorldPointPicker. Large coordinates: vertex
 * positions are computed relative to a sample near the camera whose position goes into
 * the camera matrices in double, so a DEM at 6.4e6 m draws as at the origin.
 *
 * Picking: vtkCellPicker and vtkPointPicker intersect a mapper's input data set, here the
 * flat image, and cannot see the terrain: use vtkGeoMipMapPicker (exact ray-terrain
 * intersection, with image point and cell ids), vtkWorldPointPicker or vtkPropPicker.
 * Hardware cell or point selection (vtkHardwareSelector) returns ids of the drawn LOD
 * triangles, not of the image.
 *
 * @sa vtkGeoMipMapFilter (the same triangles as a vtkPolyData), vtkGeoMipMapPicker
 */
#ifndef vtkGeoMipMapMapper_h
#define vtkGeoMipMapMapper_h

#include "geomipmapRenderingModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkOpenGLRenderWindow;

class GEOMIPMAPRENDERING_EXPORT vtkGeoMipMapMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkGeoMipMapMapper* New();
  vtkTypeMacro(vtkGeoMipMapMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Sets the input image directly (vtkPolyDataMapper's SetInputData takes a vtkPolyData;
   * SetInputConnection works as usual).
   */
  void SetInputData(vtkImageData* image);

  ///@{
  /**
   * Largest screen-space error, in pixels, the engine may leave (tau). Default 1.0.
   * Negative or NaN values are rejected with an error and the previous value is kept.
   */
  void SetPixelError(double tau);
  double GetPixelError();
  ///@}

  ///@{
  /**
   * Largest block side in quads, at least gmm::kMinBlockQuads (4). Default
   * GetDefaultBlockSize() (32). Blocks are a power of two quads, as large as halving the DEM
   * would make them within this size (gmm::bandWidth): 32 on a 4097^2 DEM, 16 on an SRTM
   * tile. A smaller value is refused with an error and the previous one
   * kept. Changing it rebuilds the quadtree and error tables at the next render; the height
   * texture is kept.
   */
  void SetBlockSize(int quads);
  vtkGetMacro(BlockSize, int);
  ///@}

  /**
   * The smallest BlockSize accepted (gmm::kMinBlockQuads, 4): the one rule the mapper, the
   * filter and the command-line tools apply.
   */
  static int GetMinimumBlockSize();

  /**
   * The BlockSize of a new mapper or filter and the tools' default (gmm::kDefaultBlockQuads,
   * 32; chosen by measurement: Documentation/benchmarks-core.md, "The default block size is
   * now 32").
   */
  static int GetDefaultBlockSize();

  ///@{
  /**
   * On a software OpenGL (Mesa's llvmpipe or softpipe), the first render of any mapper sets
   * the C library's heap policy for the whole process (glibc's mallopt: blocks under
   * 32 MiB from the heap, up to 64 MiB of freed memory kept mapped), so that the
   * renderer's per-draw work buffers stop costing page faults in every frame
   * (vtkGeoMipMapSoftwareRenderer.h). Measured on the benchmark VM: a frame-rate flight
   * that starts at 64 k triangles took about 4000 faults a frame, half of its time, for
   * tens of frames; in a 100 ms budget over Puget Sound it drew 142 k triangles instead of
   * 460 k. On by default; a process-wide switch, read at each mapper's first render in a
   * window. Off leaves the C library's policy alone (a policy already set stays). Nothing
   * is changed on a hardware renderer or without glibc.
   */
  static void SetGlobalRetainHeapOnSoftwareRenderer(bool retain);
  static bool GetGlobalRetainHeapOnSoftwareRenderer();
  ///@}

  ///@{
  /**
   * Error table cache (see vtkGeoMipMapTerrain), on by default: the tables of a DEM of
   * 2^20 samples or more are saved to a file keyed by the heights' content hash and the
   * block size, and the next open of the same DEM reads them instead of building them.
   * TableCacheDirectory: where; null or empty (default) uses
   * vtkGeoMipMapTerrain::DefaultTableCacheDirectory() ($GEOMIPMAP_CACHE_DIR,
   * $XDG_CACHE_HOME/geomipmap or ~/.cache/geomipmap). A location that cannot be written
   * gives a warning; the tables are built as without a cache.
   */
  vtkSetMacro(TableCache, bool);
  vtkGetMacro(TableCache, bool);
  vtkBooleanMacro(TableCache, bool);
  vtkSetStringMacro(TableCacheDirectory);
  vtkGetStringMacro(TableCacheDirectory);
  ///@}

  ///@{
  /**
   * Vertical exaggeration: the surface is at origin z + HeightScale * h. Finite and > 0,
   * else refused with an error. Default 1. Culling, normals and the certified bound all
   * see the scaled surface; changing it per frame rebuilds nothing (errors scale
   * linearly), unlike an actor scale it keeps picking and GetHeightAt in data units.
   */
  void SetHeightScale(double scale);
  double GetHeightScale();
  ///@}

  ///@{
  /**
   * An image draped over the terrain, at its own resolution: a 2D vtkImageData with
   * unsigned char RGB or RGBA point scalars whose points are the pixel centres in the
   * terrain's data coordinates (x, y), as vtkGeoMipMapImageDrape makes from a
   * georeferenced orthophoto. Each fragment takes the image's colour at its x, y
   * (bilinear, mipmapped), over the terrain's own colouring by the image's alpha, and is
   * then lit as usual; outside the image (or where alpha is 0) the terrain keeps its own
   * colouring (scalars, lookup table or the actor's colour). The image is one texture: an
   * image larger than GL_MAX_TEXTURE_SIZE (16384 here) is refused with an error and the
   * terrain is drawn without it (vtkGeoMipMapImageDrape::SetMaximumSize resamples). The
   * image is used as it is (update its pipeline first); a change of it (its MTime) is
   * uploaded at the next render. Null (default): no drape.
   */
  void SetDrapeImage(vtkImageData* image);
  vtkImageData* GetDrapeImage();
  ///@}

  ///@{
  /**
   * Largest side, in texels, of one layer of the height texture; 0 (default) is the
   * OpenGL limit (GL_MAX_TEXTURE_SIZE). A DEM larger than this is split into layers with
   * no seam; a smaller value trades texture layers for smaller uploads. Heights read in
   * place (ShareHeights) are cut into bands of at most its square of texels.
   */
  vtkSetClampMacro(MaximumTileSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumTileSize, int);
  ///@}

  ///@{
  /**
   * Read the heights array in place instead of copying it into a texture, where the
   * renderer runs on the CPU (Mesa llvmpipe or softpipe) and offers GL_AMD_pinned_memory:
   * no upload, and the DEM is held once instead of twice (a 16385^2 float DEM: 1 GiB and
   * about 4.6 s less at the first render on the benchmark VM). Float and 16-bit integer
   * heights only; other types, and GPUs with their own memory, use the texture. Where
   * sharing is possible but fails (more than 16 buffer textures of
   * GL_MAX_TEXTURE_BUFFER_SIZE samples, or OpenGL refuses the memory), the texture is used
   * too and a warning says why, once per array and context. The picture is the same
   * either way. On by default.
   */
  vtkSetMacro(ShareHeights, bool);
  vtkGetMacro(ShareHeights, bool);
  vtkBooleanMacro(ShareHeights, bool);
  ///@}

  ///@{
  /**
   * Lit terrain takes its normals from the full-resolution slopes. Off (default): they are
   * computed per fragment from the heights (central differences, one-sided beside the
   * border and nodata; 10 height fetches). On: from a slope texture made once from the
   * heights (4 bytes a sample, RG16F; one to three fetches per fragment). The texture costs
   * its memory and its making (a 16385^2 DEM on llvmpipe: 1 GB and 3.6 s more at the first
   * render) and saves frame time on llvmpipe (frames 1.09x faster at 4097^2, 1.23x at
   * 16385^2; not measured on a GPU). The two differ by the texture's half-float rounding.
   */
  vtkSetMacro(SlopeTexture, bool);
  vtkGetMacro(SlopeTexture, bool);
  vtkBooleanMacro(SlopeTexture, bool);
  ///@}

  /** Where lit terrain takes its normals (NormalMode). */
  enum NormalModes
  {
    NORMALS_AUTOMATIC = 0,
    NORMALS_PER_VERTEX = 1,
    NORMALS_PER_FRAGMENT = 2
  };

  ///@{
  /**
   * Where lit terrain takes its normals, always from the full-resolution slopes:
   * - NORMALS_PER_FRAGMENT: at every fragment (the rule and sources above). Inside a coarse
   *   triangle the shading keeps the detail of the samples the geometry skips.
   * - NORMALS_PER_VERTEX: at the drawn vertices, each the full-resolution normal of its own
   *   sample (the rule above, four height fetches a vertex), interpolated across the
   *   triangle as vtkPolyDataMapper shades a mesh with point normals. A fragment fetches
   *   nothing for its normal, so a frame whose cost is its pixels is cheaper (on llvmpipe
   *   the per-fragment normal is most of that cost), but inside a coarse triangle the
   *   shading loses the detail of the samples it skips (the geometry keeps its certified
   *   error). Overrides SlopeTexture.
   * - NORMALS_AUTOMATIC (default): per fragment on a GPU, where ten height fetches a
   *   fragment are cheap. Where OpenGL runs on the CPU (Mesa's llvmpipe or softpipe), where
   *   the per-fragment normal is most of a fill-bound frame, per vertex while the frame's
   *   certified bound (that of its morphed surface, as GetMaximumScreenSpaceError reports
   *   it when the morph is drawn) is at most
   *   GetAutomaticVertexNormalsPixels() (1 px), per fragment above: within a pixel the two
   *   differ little from the full-resolution render, above it per vertex loses detail
   *   (decision record 004 has the figures).
   */
  vtkSetClampMacro(NormalMode, int, NORMALS_AUTOMATIC, NORMALS_PER_FRAGMENT);
  vtkGetMacro(NormalMode, int);
  void SetNormalModeToAutomatic() { this->SetNormalMode(NORMALS_AUTOMATIC); }
  void SetNormalModeToPerVertex() { this->SetNormalMode(NORMALS_PER_VERTEX); }
  void SetNormalModeToPerFragment() { this->SetNormalMode(NORMALS_PER_FRAGMENT); }
  const char* GetNormalModeAsString();
  ///@}

  /** The largest certified error (pixels) at which NORMALS_AUTOMATIC shades per vertex on a
   * renderer that runs on the CPU. */
  static double GetAutomaticVertexNormalsPixels();

  ///@{
  /**
   * NormalMode by a switch: on is NORMALS_PER_VERTEX, off NORMALS_PER_FRAGMENT; Get is
   * true for NORMALS_PER_VERTEX only.
   */
  void SetVertexNormals(bool on);
  bool GetVertexNormals();
  void VertexNormalsOn() { this->SetVertexNormals(true); }
  void VertexNormalsOff() { this->SetVertexNormals(false); }
  ///@}

  /** Whether the last frame drawn was shaded with normals per vertex (NormalMode). */
  vtkGetMacro(LastFrameVertexNormals, bool);

  /** True when the last render read the heights in place (see ShareHeights). */
  bool GetHeightsShared() const;

  ///@{
  /**
   * Memory, in bytes, a DEM may take (GPU textures, plus the engine's tables and any
   * height copy); 0 (default) means the memory available on this machine now. A DEM
   * estimated to need more is refused before anything is allocated.
   */
  vtkSetMacro(MemoryLimit, vtkTypeInt64);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Freezes the level of detail, to inspect it from another viewpoint: while on, a render
   * draws the triangles the engine selected last, for the camera of that frame, instead of
   * selecting new ones for the current camera (no index upload, LastUpdateTime 0,
   * IndicesReused true). The statistics keep describing that selection: its certified
   * error holds for the camera it was selected for, not for the current one. PixelError
   * changes wait until it is off again. A render with nothing to keep (the first one, or
   * after a new input or BlockSize) still selects, for its own camera. Off by default.
   */
  void SetFreezeLevelOfDetail(bool freeze);
  vtkGetMacro(FreezeLevelOfDetail, bool);
  vtkBooleanMacro(FreezeLevelOfDetail, bool);
  ///@}

  ///@{
  /**
   * Geomorphing (on by default): the vertex shader moves each vertex that a block's next
   * coarser level drops toward that level's surface, by a per-block factor that grows as
   * the block nears its switch, so that level changes do not pop; vertices on a shared
   * edge follow one per-edge factor, so no crack opens. The factors keep the certificate:
   * the morphed surface is within PixelError (MaximumScreenSpaceError is then its bound,
   * from error-table bounds for the blocks whose budget those already prove, so it may lie
   * above the measured error by more than without geomorphing), or in a frame drawn within
   * a triangle budget, within that frame's certified error.
   * Only heights move (x, y stay), so draped images and shading do not swim. Per frame a
   * few bytes per block are uploaded; nothing per vertex. vtkGeoMipMapFilter with the same
   * setting outputs the same positions. See Documentation/design.md, "Geomorphing".
   */
  void SetGeomorphing(bool on);
  bool GetGeomorphing();
  vtkBooleanMacro(Geomorphing, bool);
  ///@}

  ///@{
  /**
   * How gradually geomorphing changes levels (default 2): while geomorphing, a block moves
   * through its levels by at most one level per this factor of change in its distance, and
   * its morph factor never rises faster than that from one frame to the next (nor, where a
   * neighbour's switch frees a block or an edge, by more than 0.1 px of vertex motion a
   * frame), so that no frame pops where two levels' errors are close.
   * Larger is smoother where levels do not nest (a block's side strips, merged nodes; inside
   * a block they do) and draws more triangles, since blocks stay finer than PixelError needs
   * while they glide. Measured against no geomorphing at PixelError 2 (measure_popping.py,
   * decision record 002), with GeomorphMerges on: 1.17x the triangles over N48W125 and 1.34x
   * over N41E001 at 2; worst pop between frames 0.85 and 0.62 px over those tiles (0.09 and
   * 0.20 px as the mean of the frames' worst), 0.27 over measure_pop_causes' fractal. Without
   * GeomorphMerges, 1.05x and 1.28x at 2 (worst pop 1.85 and 1.78 px), 1.30x and 1.78x at 3;
   * on bench_core's whole-DEM 4097^2 flight at PixelError 1, 1.30x at 2 and 2.56x at 3. 1 or
   * less selects the coarsest levels within PixelError and morphs each block as far as its certificate allows. The
   * certificate holds at any range.
   */
  void SetGeomorphRange(double range);
  double GetGeomorphRange();
  ///@}

  ///@{
  /**
   * Geomorph merges too (on by default): while geomorphing, far terrain is drawn as a
   * merged quadtree node only where the node's blocks have reached their coarsest level on
   * the geomorphing path. A node over 2 x 2 blocks then draws exactly what its blocks
   * drew, so merging and splitting it moves nothing; in a node of more blocks, whose fan is
   * not its children's surface, the block corners inside it first glide onto its fan, and
   * it merges where what that leaves to change projects within 0.3 px (nodes over nodata,
   * or high in the tree where only a bound of their error is kept: where their error does).
   * With it off, a merge replaces blocks that the path still holds several levels finer,
   * and the surface jumps by up to about PixelError. Measured at PixelError 2 and the
   * default block size and range (measure_popping.py's slow flights, 40 frames; decision
   * record 002), off against on: the worst jump between frames 1.85 against 0.85 px over
   * N48W125 and 1.78 against 0.62 over N41E001, the mean of the frames' worst 0.29 / 0.09
   * and 0.77 / 0.20 px, for 11 % and 8 % more triangles. The price is in wide views, where
   * blocks stay finer for longer: on
   * bench_core's flight with a whole DEM ahead at PixelError 1, 3 % more triangles and a
   * LOD update of 1.34 ms instead of 0.68 ms at 16385^2, 6 % and 2.2 instead of 1.5 ms at
   * 4097^2.
   */
  void SetGeomorphMerges(bool on);
  bool GetGeomorphMerges();
  vtkBooleanMacro(GeomorphMerges, bool);
  ///@}

  ///@{
  /**
   * The most full-resolution samples a frame rasterises to measure geomorphing's exact
   * errors (default 131072; 0: no limit). A block's morph factor is chosen from the errors
   * of its parts at its level and its configuration; when the camera jumps, nearly every
   * drawn block changes configuration, and measuring them all was three quarters of the
   * frame's CPU work. Past the limit the nearest blocks are measured first; the others
   * morph by the error table's bounds (certified, looser: they morph less) or, where the
   * table gives none, not at all, and are measured in the frames that follow, each again
   * within the limit. PixelError holds in every frame. A smooth flight measures far less
   * than the default a frame (over a 30 m fractal at PixelError 2, pops change only at 480 m
   * a frame: the mean of the frames' worst 0.71 -> 0.75 px); the first frame measures
   * everything. Measured with
   * bench_core's jumps (views 30 degrees apart around a 4097^2 DEM, PixelError 1): 9.0 ms
   * a frame against 22.5 ms with no limit (2.8 ms without geomorphing).
   */
  void SetGeomorphMeasureSamples(vtkIdType samples);
  vtkIdType GetGeomorphMeasureSamples();
  ///@}

  ///@{
  /**
   * Triangle budget of every frame (0, the default: none). The engine refines the drawn
   * block with the largest projected error until the next refinement would exceed the
   * budget or every error is within PixelError, whichever comes first
   * (gmm::Engine::update with a budget): MaximumScreenSpaceError is then the smallest
   * certified error the budget allows. If even the coarsest selection (every visible block
   * one quad) exceeds it, that selection is drawn and GetOverTriangleBudget() is true.
   * Budgeted frames use merged nodes as tau-driven ones do (Documentation/design.md,
   * "Triangle budgets"). Negative values are refused with an error.
   */
  void SetTriangleBudget(vtkIdType budget);
  vtkIdType GetTriangleBudget();
  ///@}

  ///@{
  /**
   * VTK's frame-rate contract. While on, an interactive render (the render window's
   * DesiredUpdateRate above its interactor's StillUpdateRate, or above VTK's still rate
   * 0.0001 without an interactor) selects within the triangle budget whose predicted
   * draw time is the actor's AllocatedRenderTime. The cost model (seconds = fixed +
   * per-triangle * triangles) is learnt from this mapper's own interactive frames, timed
   * from the start of RenderPiece to a glFinish after the draw, and the budget moves only
   * when its predicted time is more than 10 % off (gmm::BudgetController). A still
   * render uses PixelError (and TriangleBudget, if set) as without this mode. Off by
   * default.
   */
  void SetFollowAllocatedRenderTime(bool follow);
  vtkGetMacro(FollowAllocatedRenderTime, bool);
  vtkBooleanMacro(FollowAllocatedRenderTime, bool);
  ///@}

  ///@{
  /**
   * Draws the selected blocks sorted front to back from the eye (glMultiDrawElements over
   * the index buffer's per-block slots, nothing re-uploaded), so that early depth testing
   * rejects the fragments of what nearer blocks hide before they are shaded. Needs the
   * fixed primitive-restart index (OpenGL 4.3 / ES 3.0) and a surface or points
   * representation; otherwise blocks are drawn in block order. On by default.
   */
  vtkSetMacro(FrontToBack, bool);
  vtkGetMacro(FrontToBack, bool);
  vtkBooleanMacro(FrontToBack, bool);
  ///@}

  ///@{
  /**
   * Budget statistics of the last rendered frame: the triangle budget in force (0 = none,
   * PixelError alone), whether the budget rather than PixelError stopped refinement,
   * whether even the coarsest selection exceeded it, whether the frame was interactive
   * (FollowAllocatedRenderTime and a non-still update rate), the time it was allocated
   * (the actor's AllocatedRenderTime) and the time it took (RenderPiece to a glFinish;
   * 0 unless the frame was interactive, the only frames that are timed so).
   */
  vtkIdType GetTriangleBudgetInForce() const;
  bool GetTriangleBudgetReached() const;
  bool GetOverTriangleBudget() const;
  vtkGetMacro(LastFrameInteractive, bool);
  vtkGetMacro(LastAllocatedRenderTime, double);
  vtkGetMacro(LastRenderTime, double);
  ///@}

  /**
   * Where the last frame's budgeted search started (gmm::Engine::update's startTau): the
   * tau the budgeted frame before it ended at, so that a moving view's search is short; 0
   * for a cold start or a frame without a budget. vtkGeoMipMapFilter::SetBudgetStartTau
   * with this value, the same camera and budget reproduces the frame's triangles.
   */
  double GetLastBudgetStartTau() const;

  ///@{
  /**
   * Instrumentation: when on, each draw counts the samples that pass the depth test
   * (GL_SAMPLES_PASSED; waits for the result), i.e. the fragments shaded when the
   * fragment shader runs after an early depth test, for measuring FrontToBack; and the
   * vertex shader's runs (GL_VERTEX_SHADER_INVOCATIONS; -1 where the driver lacks
   * ARB_pipeline_statistics_query), for measuring vertex reuse (gmm::drawPitch).
   * A heap corruption seen once with counting and FrontToBack together (Debian 12's
   * llvmpipe, before merged nodes joined the draw order) no longer reproduces: 120 frames
   * of Puget Sound in both orders run clean (Documentation/benchmarks.md, issue #14). Its
   * cause was not identified.
   */
  vtkSetMacro(CountFragments, bool);
  vtkGetMacro(CountFragments, bool);
  vtkGetMacro(LastFragmentsPassed, vtkTypeInt64);
  vtkGetMacro(LastVertexInvocations, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Statistics of the last rendered frame (the last renderer that drew this mapper).
   * LastUpdateTime is the LOD work (cull, select, tessellate, and with Geomorphing the
   * morph factors) in seconds; NumberOfVisibleBlocks counts the blocks drawn (in view and
   * holding a valid sample: a block all nodata is never drawn), NumberOfCulledBlocks the others;
   * MaximumScreenSpaceError is the engine's certified bound in pixels and
   * MaximumGeometricError in data units; IndicesReused is true when the frame's triangles
   * equal the previous frame's. After a render that drew nothing because of an error (bad
   * camera, no input, too big) they are 0. When VTK culls the whole actor (its bounds
   * outside the view) the mapper is not called at all, and they keep describing the last
   * frame it drew.
   */
  vtkIdType GetNumberOfRenderedTriangles() const;
  int GetNumberOfVisibleBlocks() const;
  int GetNumberOfCulledBlocks() const;
  double GetMaximumScreenSpaceError() const;
  double GetMaximumGeometricError() const;
  bool GetIndicesReused() const;
  vtkGetMacro(LastUpdateTime, double);
  ///@}

  ///@{
  /**
   * Instrumentation: how many times the heights (and colouring arrays) were uploaded to
   * textures, and the triangle index buffer to OpenGL; the time the last height upload and
   * the last terrain build (tables) took, in seconds, and whether that build read the
   * tables from the table cache.
   */
  vtkGetMacro(NumberOfHeightUploads, int);
  vtkGetMacro(NumberOfIndexUploads, int);
  vtkGetMacro(LastHeightUploadTime, double);
  vtkGetMacro(LastTerrainBuildTime, double);
  vtkGetMacro(LastTablesFromCache, bool);
  ///@}

  ///@{
  /**
   * Wall time, in seconds, spent uploading the triangle index buffer during the last
   * rendered frame (0 when the indices were reused), and the bytes uploaded. The buffer
   * mirrors the engine's index arena (gmm::IndexArena): a frame uploads only the slots of
   * the blocks whose triangles changed, unless the arena was rewritten (first frame,
   * growth, compaction), the representation is wireframe, or OpenGL lacks the fixed
   * primitive-restart index (4.3 / ES 3.0); then the whole list is uploaded.
   */
  vtkGetMacro(LastIndexUploadTime, double);
  vtkGetMacro(LastIndexUploadBytes, vtkTypeInt64);
  ///@}

  /**
   * Bytes of geomorph factors uploaded for the last rendered frame: only the rows of the
   * morph texture where a block's or an edge's factor changed (0 for a still camera, or with
   * Geomorphing off).
   */
  vtkGetMacro(LastMorphUploadBytes, vtkTypeInt64);

  /**
   * Bytes held on the GPU: height, colour, lookup-table and drape textures and the index
   * buffer.
   */
  vtkTypeInt64 GetGPUMemoryBytes() const;

  /**
   * Height of the full-resolution surface at data coordinates (x, y): origin z +
   * HeightScale * h, linear on the level-0 triangle under it, whatever the LOD draws; NaN
   * outside the DEM or over nodata. Updates the input when needed.
   */
  double GetHeightAt(double x, double y);

  /**
   * Exact first intersection of the segment p1 -> p2 (data coordinates) with the
   * full-resolution surface. Returns true and sets t (in [0, 1]), the point x, the unit
   * normal, the image point id of the nearest vertex of the hit triangle and the image
   * cell id under the hit; false when the segment misses. Used by vtkGeoMipMapPicker.
   */
  bool IntersectWithLine(const double p1[3], const double p2[3], double& t, double x[3],
    double normal[3], vtkIdType& pointId, vtkIdType& cellId);

  /**
   * Bounds of the valid (non-NaN) samples: x, y of the rows and columns that hold one,
   * z of the scaled surface. Uninitialised when there is none.
   */
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* win) override;

  ///@{
  /**
   * VTK's buffer build maps the mapper's input to per-vertex colours (4 bytes a sample
   * here); colours come from the fragment shader instead, so only the scalar-free proxy
   * vertex is mapped.
   */
  using Superclass::MapScalars;
  vtkUnsignedCharArray* MapScalars(double alpha) override;
  vtkUnsignedCharArray* MapScalars(double alpha, int& cellFlag) override;
  ///@}

protected:
  vtkGeoMipMapMapper();
  ~vtkGeoMipMapMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void ComputeBounds() override;

  // Rebuild the (tiny, proxy) vertex buffers only for property, texture or colouring
  // changes, not for PixelError / BlockSize / HeightScale (those change indices only).
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  // Uploads the engine's triangles instead of the (cell-less) proxy's cells.
  void BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly) override;
  // Draws the triangles with glDrawElements (the proxy's one vertex is no range).
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  // Terrain code in VTK's generated shaders (vtkGeoMipMapShaders.h).
  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  // Terrain uniforms, and clipping planes relative to the anchor sample.
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  // Camera matrices with the anchor's translation folded in, in double.
  void SetCameraShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  // Gets the shared terrain of the input image; false (with an error) when unusable.
  bool UpdateTerrain(vtkImageData* image);
  // Heights, colouring arrays and lookup table on the GPU of `win`; false on failure.
  bool UpdateTextures(vtkOpenGLRenderWindow* win, vtkImageData* image, vtkActor* act);
  // Uploads the frame's indices: the arena's changed ranges, or everything when `whole`
  // (a new buffer) or when the buffer does not mirror the previous frame's arena.
  void UploadIndices(vtkActor* act, bool whole);
  // Frees the GPU data of the window they live in (its context made current).
  void ReleaseWindowResources();
  // Marks the mapper modified for a change that needs new indices but no new buffers.
  void ModifiedIndicesOnly();
  // The triangle budget for this render (0 = none), and whether it is interactive.
  std::size_t FrameTriangleBudget(vtkRenderer* ren, vtkActor* act, bool& interactive);
  // Issues the draw of the triangles in the bound index buffer, front to back when asked
  // and possible.
  void DrawTriangles(unsigned int mode, std::size_t indexCount);

  // The LOD settings shared with vtkGeoMipMapFilter (PixelError, TriangleBudget,
  // HeightScale, Geomorphing, GeomorphRange, GeomorphMerges, GeomorphMeasureSamples) are one
  // gmm::FrameSettings in the internals.
  int BlockSize; // gmm::kDefaultBlockQuads
  bool TableCache = true;
  char* TableCacheDirectory = nullptr;
  vtkTypeInt64 MemoryLimit = 0;
  int MaximumTileSize = 0;
  bool ShareHeights = true;
  bool SlopeTexture = false;
  int NormalMode = NORMALS_AUTOMATIC;
  // Whether the slope texture is made: SlopeTexture unless NormalMode overrides it
  // (NORMALS_PER_VERTEX makes none, automatic normals keep it for frames shaded per pixel).
  bool SlopeTextureWanted() const { return this->SlopeTexture && this->NormalMode != NORMALS_PER_VERTEX; }
  bool LastFrameVertexNormals = false;
  double LastUpdateTime = 0.0;
  int NumberOfHeightUploads = 0;
  int NumberOfIndexUploads = 0;
  double LastIndexUploadTime = 0.0;
  vtkTypeInt64 LastIndexUploadBytes = 0;
  vtkTypeInt64 LastMorphUploadBytes = 0;
  double LastHeightUploadTime = 0.0;
  double LastTerrainBuildTime = 0.0;
  bool LastTablesFromCache = false;
  bool LastFrameDrawn = false; // the engine ran in the last RenderPiece (else stats are 0)
  bool FreezeLevelOfDetail = false;
  bool LastFrameFrozen = false; // the last RenderPiece kept the frozen selection
  bool FollowAllocatedRenderTime = false;
  bool FrontToBack = true;
  bool CountFragments = false;
  bool LastFrameInteractive = false;
  double LastAllocatedRenderTime = 0.0;
  double LastRenderTime = 0.0;
  vtkTypeInt64 LastFragmentsPassed = 0;
  vtkTypeInt64 LastVertexInvocations = 0;
  vtkMTimeType IndicesOnlyMTime = 0;
  bool IndicesDirty = true;

private:
  vtkGeoMipMapMapper(const vtkGeoMipMapMapper&) = delete;
  void operator=(const vtkGeoMipMapMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
