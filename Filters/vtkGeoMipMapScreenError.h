/**
 * @class   vtkGeoMipMapScreenError
 * @brief   Measured screen-space error of any triangle mesh drawn over a heightfield.
 *
 * Independent of the engine's error bound (no gmm code is used): for every
 * full-resolution sample of the heightfield that lies inside the view frustum, the true
 * point (x, y, origin z + HeightScale * h) and the drawn surface's point (x, y, z) at the
 * same x, y are projected
 * to pixels with the given world-to-clip matrix, and their distance is taken. Reported:
 * the maximum, the 99th percentile and the mean of that distance over the in-view samples,
 * the number of in-view samples, and the number of in-view samples that could not be
 * measured (no triangle over that x, y, or the drawn point behind the camera).
 *
 * Inputs:
 * - Heightfield: a 2D vtkImageData (nx x ny x 1) with heights as active point scalars, any
 *   numeric type; negative spacing is allowed; NaN samples (nodata) are skipped.
 * - Mesh: any vtkPolyData of polygons (triangles, or polygons fanned into triangles) in
 *   the same world coordinates: the GeoMipMapping triangles, a greedy decimation, a
 *   uniform subsampling, a quadric clustering. The drawn z at a sample is found by
 *   rasterising every triangle over the grid's x, y (barycentric interpolation, samples on
 *   an edge count as inside). Where several triangles cover one sample (a mesh that is not
 *   a height field, e.g. quadric clustering folds), the worst of the lowest and highest
 *   drawn z is taken; vertical triangles (zero area in x, y) are ignored.
 * - ProjectionMatrix: world -> clip coordinates, as given by
 *   vtkCamera::GetCompositeProjectionTransformMatrix(width / height, -1, 1), and
 *   ViewportSize (pixels). A sample is in view when its clip w > 0 and its normalised
 *   x, y, z lie in [-1, 1] (inside the six frustum planes).
 *
 * With a ReferenceMesh, the reference point at a sample is that mesh's drawn point
 * instead of the true one (the heightfield then only gives the grid and which samples are
 * in view): the result is the screen displacement between two drawn surfaces, e.g. the
 * popping between two frames of a flight (reference = the previous frame's mesh, Mesh =
 * this frame's, matrix = this frame's camera). Samples that either mesh leaves uncovered
 * count as uncovered.
 *
 * The class takes a matrix rather than a vtkCamera so that this module does not depend
 * on VTK's rendering modules.
 */
#ifndef vtkGeoMipMapScreenError_h
#define vtkGeoMipMapScreenError_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkObject.h"

class vtkImageData;
class vtkMatrix4x4;
class vtkPolyData;

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapScreenError : public vtkObject
{
public:
  static vtkGeoMipMapScreenError* New();
  vtkTypeMacro(vtkGeoMipMapScreenError, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The full-resolution heightfield (the reference surface).
   */
  virtual void SetHeightfield(vtkImageData*);
  vtkGetObjectMacro(Heightfield, vtkImageData);
  ///@}

  ///@{
  /**
   * Vertical exaggeration of the true surface (origin z + HeightScale * h), to measure a
   * mesh drawn with a height scale. Default 1.
   */
  vtkSetMacro(HeightScale, double);
  vtkGetMacro(HeightScale, double);
  ///@}

  ///@{
  /**
   * The drawn triangles, in the heightfield's world coordinates.
   */
  virtual void SetMesh(vtkPolyData*);
  vtkGetObjectMacro(Mesh, vtkPolyData);
  ///@}

  ///@{
  /**
   * Optional second drawn surface (same world coordinates) to measure Mesh against,
   * instead of the heightfield's true surface. Default none.
   */
  virtual void SetReferenceMesh(vtkPolyData*);
  vtkGetObjectMacro(ReferenceMesh, vtkPolyData);
  ///@}

  ///@{
  /**
   * World -> clip matrix (a copy is kept) and viewport size in pixels (default 1280 x 720).
   */
  void SetProjectionMatrix(vtkMatrix4x4* m);
  vtkSetVector2Macro(ViewportSize, int);
  vtkGetVector2Macro(ViewportSize, int);
  ///@}

  /**
   * Measures. Returns true on success; on bad input reports an error (vtkErrorMacro)
   * naming the problem, leaves the results at zero and returns false.
   */
  bool Compute();

  ///@{
  /**
   * Results of the last Compute(), in pixels.
   */
  vtkGetMacro(MaximumError, double);
  vtkGetMacro(Percentile99Error, double);
  vtkGetMacro(MeanError, double);
  vtkGetMacro(NumberOfSamplesInView, vtkIdType);
  vtkGetMacro(NumberOfUncoveredSamples, vtkIdType);
  ///@}

protected:
  vtkGeoMipMapScreenError();
  ~vtkGeoMipMapScreenError() override;

  vtkImageData* Heightfield = nullptr;
  vtkPolyData* Mesh = nullptr;
  vtkPolyData* ReferenceMesh = nullptr;
  double Matrix[16];
  bool HasMatrix = false;
  int ViewportSize[2] = { 1280, 720 };
  double HeightScale = 1.0;

  double MaximumError = 0.0;
  double Percentile99Error = 0.0;
  double MeanError = 0.0;
  vtkIdType NumberOfSamplesInView = 0;
  vtkIdType NumberOfUncoveredSamples = 0;

private:
  vtkGeoMipMapScreenError(const vtkGeoMipMapScreenError&) = delete;
  void operator=(const vtkGeoMipMapScreenError&) = delete;
};

#endif
