/**
 * @class   vtkGeoMipMapMapper
 * @brief   Draws a heightfield image with view-dependent GeoMipMapping level of detail.
 *
 * Input: a 2D vtkImageData (nx x ny x 1) whose active point scalars are heights, any
 * numeric type (vtkDEMReader's output plugs in directly, as does
 * vtkGeoMipMapTerrainReader's "Elevation"). NaN marks nodata: no triangle touches it.
 *
 * When the input changes (MTime), the mapper converts it to a gmm::Heightfield, builds the
 * engine (quadtree and error table) and one vtkPolyData over ALL samples with smooth
 * full-resolution normals, the input scalars (for LUT colouring) and, only while the
 * actor has a texture, texture coordinates 0..1 over the extent; its vertex buffers are
 * uploaded once. Every render it converts
 * the renderer's active camera and viewport to a gmm::View in the data's coordinates
 * (through the inverse of the actor's matrix), runs the engine with PixelError and draws
 * the selected triangles. Only the triangle index buffer is re-uploaded, and only when
 * the engine reports that the indices changed. Lighting, LUT colouring, textures, actor
 * transforms, parallel projection and the VBO shift/scale for large coordinates work as
 * with vtkOpenGLPolyDataMapper.
 *
 * Several renderers may share one mapper: the LOD follows the camera being rendered (the
 * indices are re-uploaded when renderers with different cameras alternate).
 *
 * Limits: the error bound is exact for rotations, translations and uniform scale; with a
 * non-uniform actor scale it is approximate. Surface, wireframe and points
 * representations are supported; edge visibility and hardware picking of cells are not.
 * The camera's window centre / view shear are ignored.
 *
 * @sa vtkGeoMipMapFilter (the same triangles as a vtkPolyData)
 */
#ifndef vtkGeoMipMapMapper_h
#define vtkGeoMipMapMapper_h

#include "geomipmapRenderingModule.h" // For export macro
#include "vtkNew.h"                   // For vtkNew
#include "vtkOpenGLPolyDataMapper.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkPolyData;

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
  vtkGetMacro(PixelError, double);
  ///@}

  ///@{
  /**
   * Largest block side in quads (>= 2). Default 64. Changing it rebuilds the engine's
   * quadtree and error table at the next render; the vertex buffers are kept.
   */
  void SetBlockSize(int quads);
  vtkGetMacro(BlockSize, int);
  ///@}

  ///@{
  /**
   * Statistics of the last rendered frame (the last renderer that drew this mapper).
   * LastUpdateTime is the LOD work (cull, select, tessellate) in seconds;
   * MaximumScreenSpaceError is the engine's certified bound in pixels; IndicesReused is
   * true when the frame's triangles equal the previous frame's. After a render that
   * drew nothing because of an error (bad camera, no input) they are 0. When VTK culls the
   * whole actor (its bounds outside the view) the mapper is not called at all, and they
   * keep describing the last frame it drew.
   */
  vtkIdType GetNumberOfRenderedTriangles() const;
  int GetNumberOfVisibleBlocks() const;
  int GetNumberOfCulledBlocks() const;
  double GetMaximumScreenSpaceError() const;
  bool GetIndicesReused() const;
  vtkGetMacro(LastUpdateTime, double);
  ///@}

  ///@{
  /**
   * Instrumentation: how many times the vertex buffers (positions, normals, colours,
   * texture coordinates) and the triangle index buffer were uploaded to OpenGL.
   */
  vtkGetMacro(NumberOfVertexUploads, int);
  vtkGetMacro(NumberOfIndexUploads, int);
  ///@}

  /**
   * Wall time, in seconds, spent uploading the triangle index buffer during the last
   * rendered frame (0 when the indices were reused).
   */
  vtkGetMacro(LastIndexUploadTime, double);

  /**
   * Bounds of the valid (non-NaN) samples.
   */
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* win) override;

protected:
  vtkGeoMipMapMapper();
  ~vtkGeoMipMapMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void ComputeBounds() override;

  // Rebuild the VBOs only for input, property, texture or colouring changes, not for
  // PixelError / BlockSize (those change indices only).
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  // Uploads the engine's triangles instead of the (cell-less) mesh's cells.
  void BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly) override;

  // Rebuilds heightfield, engine and mesh when the input image or block size changed.
  bool UpdateMesh(vtkImageData* image);
  // Adds texture coordinates (0..1 over the extent) to the mesh, or drops them.
  void UpdateTextureCoordinates(bool wanted);
  void UploadIndices(vtkActor* act);
  // Marks the mapper modified for a change that needs new indices but no new VBOs.
  void ModifiedIndicesOnly();

  double PixelError = 1.0;
  int BlockSize = 64;
  double LastUpdateTime = 0.0;
  int NumberOfVertexUploads = 0;
  int NumberOfIndexUploads = 0;
  double LastIndexUploadTime = 0.0;
  bool LastFrameDrawn = false; // the engine ran in the last RenderPiece (else stats are 0)

  vtkNew<vtkPolyData> Mesh;
  vtkMTimeType MeshInputTime = 0;    // input image MTime the engine was built from
  vtkMTimeType MeshVerticesTime = 0; // input image MTime the mesh (VBO source) was built from
  int MeshBlockSize = 0;
  vtkMTimeType IndicesOnlyMTime = 0;
  bool IndicesDirty = true;
  double ValidBounds[6];

private:
  vtkGeoMipMapMapper(const vtkGeoMipMapMapper&) = delete;
  void operator=(const vtkGeoMipMapMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
