/**
 * @class   vtkGeoMipMapFilter
 * @brief   The triangles vtkGeoMipMapMapper would draw, as a vtkPolyData.
 *
 * Input: a 2D vtkImageData with heights as active point scalars (NaN = nodata), as for
 * vtkGeoMipMapMapper. Output: the GeoMipMapping triangulation for one camera and viewport
 * (or for a geometric error), with only the samples the triangles use (compacted, at
 * their full-resolution positions (x, y, origin z + HeightScale * h)), point scalars
 * "Elevation" (h), point normals "Normals" (full-resolution central differences of the
 * scaled surface, the normals the mapper shades with), and field data with the frame's
 * statistics: Triangles, VisibleBlocks, CulledBlocks, MaximumScreenSpaceError,
 * MaximumGeometricError (data units). With Geomorphing (default on) and a camera, the
 * points carry the morphed heights the mapper's vertex shader draws for that camera
 * ("Elevation" too), and MaximumScreenSpaceError is the morphed surface's bound. The quadtree and error tables are those of
 * vtkGeoMipMapTerrain: built once per input image and shared with every mapper of it.
 *
 * Modes:
 * - view-dependent (a Camera is set and MaximumGeometricError <= 0): the same
 *   conversion and engine call as the mapper, with ViewportSize as the viewport and the
 *   camera's current clipping range; same camera and viewport give the same triangles.
 * - view-independent (MaximumGeometricError > 0, or no Camera): every block at the
 *   coarsest level within that many metres. The default (no camera, error 0) is a
 *   lossless triangulation: flat regions coarsen, everything else stays at full
 *   resolution.
 *
 * The camera is in world coordinates; ModelMatrix is the data -> world matrix of the
 * actor that would draw the terrain (none = identity), so that the filter gives the
 * triangles vtkGeoMipMapMapper draws for that actor.
 *
 * @sa vtkGeoMipMapMapper
 */
#ifndef vtkGeoMipMapFilter_h
#define vtkGeoMipMapFilter_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For std::unique_ptr

class vtkCamera;
class vtkMatrix4x4;

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGeoMipMapFilter* New();
  vtkTypeMacro(vtkGeoMipMapFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Camera for the view-dependent mode (not owned exclusively; reference counted).
   * Changes to the camera re-execute the filter.
   */
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /**
   * Viewport size in pixels for the view-dependent mode. Default 1280 x 720.
   */
  vtkSetVector2Macro(ViewportSize, int);
  vtkGetVector2Macro(ViewportSize, int);
  ///@}

  ///@{
  /**
   * Largest screen-space error in pixels (tau) in view-dependent mode. Default 1.0.
   * Negative or NaN values are rejected with an error and the previous value is kept
   * (as vtkGeoMipMapMapper::SetPixelError).
   */
  void SetPixelError(double tau);
  double GetPixelError();
  ///@}

  ///@{
  /**
   * Triangle budget in view-dependent mode (0, the default: none), as
   * vtkGeoMipMapMapper::SetTriangleBudget: the smallest certified error within this many
   * triangles and PixelError. Negative values are rejected with an error.
   */
  void SetTriangleBudget(vtkIdType budget);
  vtkIdType GetTriangleBudget();
  ///@}

  ///@{
  /**
   * Where a budgeted frame's search for its tau starts (gmm::Engine::update's startTau;
   * 0, the default: from the coarsest selection). Give it
   * vtkGeoMipMapMapper::GetLastBudgetStartTau() to reproduce a frame the mapper drew.
   * Values that are not finite and >= 0 are refused with an error.
   */
  void SetBudgetStartTau(double tau);
  double GetBudgetStartTau();
  ///@}

  ///@{
  /**
   * Data -> world matrix of the actor (vtkProp3D::GetMatrix()) in view-dependent mode;
   * null (default) is the identity. Any invertible affine matrix.
   */
  void SetModelMatrix(vtkMatrix4x4* matrix);
  vtkGetObjectMacro(ModelMatrix, vtkMatrix4x4);
  ///@}

  ///@{
  /**
   * Largest block side in quads, at least gmm::kMinBlockQuads (4). Default
   * gmm::kDefaultBlockQuads (32), as the mapper's. Blocks are a power of two quads, as large
   * as halving the DEM would make them within this size (gmm::bandWidth). A smaller value is refused with an error
   * and the previous one kept.
   */
  void SetBlockSize(int quads);
  vtkGetMacro(BlockSize, int);
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
   * else refused with an error (previous value kept). Default 1. Changing it does not
   * rebuild the error tables.
   */
  void SetHeightScale(double scale);
  double GetHeightScale();
  ///@}

  ///@{
  /**
   * When > 0, view-independent mode with this error bound in data units (metres of the
   * scaled surface). Default 0.
   */
  vtkSetClampMacro(MaximumGeometricError, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumGeometricError, double);
  ///@}

  ///@{
  /**
   * Geomorphing (default on, as vtkGeoMipMapMapper::SetGeomorphing): in view-dependent
   * mode, vertices that a block's next coarser level drops are moved toward that level's
   * surface by a per-block factor, so that level changes do not pop; the moved surface is
   * still within PixelError, or with a TriangleBudget within the frame's certified error
   * (see Documentation/design.md, "Geomorphing"). Points keep
   * their x, y; only heights move. Ignored in view-independent mode.
   */
  void SetGeomorphing(bool on);
  bool GetGeomorphing();
  vtkBooleanMacro(Geomorphing, bool);
  ///@}

  ///@{
  /**
   * How gradually geomorphing changes levels (as vtkGeoMipMapMapper::SetGeomorphRange):
   * while geomorphing, a block moves through its levels by at most one level per this
   * factor of change in its distance (default 2), and a morph factor never rises faster
   * than that from one Update to the next, so that no frame pops. Larger is smoother and
   * draws more triangles (blocks stay finer than PixelError needs near their switches);
   * 1 or less selects the coarsest levels within PixelError and morphs each block as far
   * as its certificate allows, frame by frame. The output of an Update then depends on the
   * cameras of earlier Updates of this filter (the rise limit), not on the camera alone.
   * See Documentation/design.md, "Geomorphing".
   */
  void SetGeomorphRange(double range);
  double GetGeomorphRange();
  ///@}

  ///@{
  /**
   * Geomorph merges too (on by default; as vtkGeoMipMapMapper::SetGeomorphMerges, which
   * has the measured pops and costs): while geomorphing, far terrain is drawn as a merged
   * quadtree node only where the node's blocks have reached their coarsest level on the
   * geomorphing path, so that a merge or a split does not skip the path's levels. It costs
   * LOD time in wide views of large DEMs.
   */
  void SetGeomorphMerges(bool on);
  bool GetGeomorphMerges();
  vtkBooleanMacro(GeomorphMerges, bool);
  ///@}

  ///@{
  /**
   * The most full-resolution samples an Update rasterises to measure geomorphing's exact
   * errors (as vtkGeoMipMapMapper::SetGeomorphMeasureSamples; default 131072, 0: no limit).
   * After a jump of the camera the blocks past it morph by looser certified bounds until
   * later Updates measure them, so the output depends on the earlier Updates' cameras.
   */
  void SetGeomorphMeasureSamples(vtkIdType samples);
  vtkIdType GetGeomorphMeasureSamples();
  ///@}

  /**
   * Height of the full-resolution surface at data coordinates (x, y): origin z +
   * HeightScale * h, linear on the level-0 triangle under it (the triangulation the mesh
   * uses at full resolution), whatever level of detail the output holds; NaN outside the
   * DEM or over nodata. Updates the input when needed.
   */
  double GetHeightAt(double x, double y);

  vtkMTimeType GetMTime() override;

protected:
  vtkGeoMipMapFilter();
  ~vtkGeoMipMapFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkCamera* Camera = nullptr;
  vtkMatrix4x4* ModelMatrix = nullptr;
  int ViewportSize[2] = { 1280, 720 };
  // The LOD settings shared with vtkGeoMipMapMapper (PixelError, TriangleBudget,
  // BudgetStartTau, HeightScale, Geomorphing, GeomorphRange, GeomorphMerges,
  // GeomorphMeasureSamples) are one gmm::FrameSettings in the internals.
  int BlockSize; // gmm::kDefaultBlockQuads
  bool TableCache = true;
  char* TableCacheDirectory = nullptr;
  double MaximumGeometricError = 0.0;

private:
  vtkGeoMipMapFilter(const vtkGeoMipMapFilter&) = delete;
  void operator=(const vtkGeoMipMapFilter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
