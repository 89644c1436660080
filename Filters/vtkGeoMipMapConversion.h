/**
 * @file   vtkGeoMipMapConversion.h
 * @brief  The one place that translates VTK objects into the engine's plain types.
 *
 * vtkGeoMipMapMapper (drawing) and vtkGeoMipMapFilter (export, verification) both call
 * these functions, so what is drawn and what is verified cannot drift apart: same
 * heightfield from an image, same gmm::View from a camera, same normals.
 *
 * Not wrapped (it exposes gmm:: types); listed as a NOWRAP header of geomipmap::Filters.
 */
#ifndef vtkGeoMipMapConversion_h
#define vtkGeoMipMapConversion_h

#include "geomipmapFiltersModule.h" // For export macro

#include "Frame.h"       // gmm::FrameSettings
#include "Heightfield.h" // gmm::Heightfield
#include "View.h"        // gmm::View

#include "vtkIndent.h"

#include <cstddef>
#include <ostream>
#include <string>

class vtkCamera;
class vtkDataArray;
class vtkImageData;
class vtkMatrix4x4;
class vtkObject;

namespace vtkGeoMipMapConversion
{
/**
 * Heights of a 2D image (dimensions nx x ny x 1) as a heightfield. Heights come from
 * `heights` when given, else from the active point scalars (component 0, any numeric
 * type); NaN/Inf are nodata. Sample (i, j) sits at origin + (extent min + (i, j)) * spacing,
 * at height origin z + h (the datum hf.z0, kept in double, as vtkWarpScalar places the
 * surface); a direction matrix must be diagonal with entries +-1 (a flip becomes a
 * negative spacing). A one-component float array is shared, not copied (hf.external, the
 * array held by hf.owner) unless it holds heights beyond gmm::kMaxHeight.
 * Returns "" on success, else why the image cannot be used. The heightfield itself (sizes,
 * spacing, origin, heights) is checked once, by gmm::buildTerrain (validateHeightfield),
 * which every consumer calls next: a full pass over the samples is not made twice.
 */
GEOMIPMAPFILTERS_EXPORT std::string ImageToHeightfield(
  vtkImageData* image, gmm::Heightfield& hf, vtkDataArray* heights = nullptr);

/**
 * A camera and a viewport of width x height pixels as a gmm::View: the camera in world
 * coordinates with its exact world -> clip matrix (window centre and view shear included
 * in culling), and `dataToWorld`, the actor's matrix (nullptr = identity), as the view's
 * model matrix. The engine culls and bounds the error exactly under any invertible affine
 * actor matrix (non-uniform scale and shear included); a projective or singular one is
 * refused. The error bound assumes no view shear.
 * Returns "" on success, else why (no camera, bad matrix, empty viewport).
 */
GEOMIPMAPFILTERS_EXPORT std::string CameraToView(vtkCamera* camera, vtkMatrix4x4* dataToWorld,
  int width, int height, gmm::View& view);

/**
 * The rule of every tau in pixels the mapper and the filter take (SetPixelError, the
 * filter's SetBudgetStartTau): a finite tau >= 0 is stored in `current` and true is
 * returned when it differs (the caller then marks itself modified); anything else is
 * refused with an error reported by `self` naming `what`, and `current` is kept.
 */
GEOMIPMAPFILTERS_EXPORT bool AcceptPixelError(
  vtkObject* self, double tau, double& current, const char* what = "PixelError");

/**
 * Memory, in bytes, this machine can give a new allocation now (Linux: MemAvailable of
 * /proc/meminfo; elsewhere the free physical pages), 0 when unknown. Used to refuse a DEM
 * that cannot fit before allocating it.
 */
GEOMIPMAPFILTERS_EXPORT double AvailableMemoryBytes();

/**
 * The SetBlockSize rule of the mapper and the filter: a size >= gmm::kMinBlockQuads (4) is
 * stored in `current` and true returned when it differs; a smaller one is refused with an
 * error reported by `self` naming the minimum, and `current` is kept.
 */
GEOMIPMAPFILTERS_EXPORT bool AcceptBlockSize(vtkObject* self, int quads, int& current);

/**
 * The SetHeightScale rule of the mapper and the filter: a finite scale > 0 is stored in
 * `current` and true returned when it differs; anything else is refused with an error.
 */
GEOMIPMAPFILTERS_EXPORT bool AcceptHeightScale(vtkObject* self, double scale, double& current);

/**
 * The rule of a count setting of the mapper and the filter (TriangleBudget,
 * GeomorphMeasureSamples; `name` in the error): a count >= 0 (0: `zeroMeans`) is stored in
 * `current` and true returned when it differs; a negative one is refused with an error.
 */
GEOMIPMAPFILTERS_EXPORT bool AcceptCount(
  vtkObject* self, const char* name, const char* zeroMeans, long long count, std::size_t& current);

/**
 * A setting without a rule of its own (any value is meaningful): stored in `current`, true
 * when it differs.
 */
template <typename T>
bool AcceptSetting(T value, T& current)
{
  if (value == current)
  {
    return false;
  }
  current = value;
  return true;
}

/**
 * PrintSelf's lines for the LOD settings the mapper and the filter share, under their VTK
 * names.
 */
GEOMIPMAPFILTERS_EXPORT void PrintFrameSettings(
  std::ostream& os, vtkIndent indent, const gmm::FrameSettings& settings);

/**
 * Unit normal at sample (i, j) of the surface z0 + heightScale * h from full-resolution
 * central differences (one-sided next to the border or to nodata; (0, 0, 1) when no
 * neighbour is valid). The mapper's fragment shader computes the same normals.
 */
GEOMIPMAPFILTERS_EXPORT void SampleNormal(
  const gmm::Heightfield& hf, int i, int j, double heightScale, float n[3]);
}


/**
 * Defines the Set/Get methods of the LOD settings the mapper and the filter share
 * (PixelError, TriangleBudget, HeightScale, Geomorphing, GeomorphRange, GeomorphMerges,
 * GeomorphMeasureSamples) for
 * `Class`, whose internals hold them as `Internal->Settings` (a gmm::FrameSettings): each
 * setter applies its rule above and calls `this->Modify()` when the value changed.
 */
#define vtkGeoMipMapFrameSettingsMacro(Class, Modify)                                          \
  void Class::SetPixelError(double tau)                                                        \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptPixelError(this, tau, this->Internal->Settings.pixelError)) \
      this->Modify();                                                                          \
  }                                                                                            \
  double Class::GetPixelError() { return this->Internal->Settings.pixelError; }                \
  void Class::SetTriangleBudget(vtkIdType budget)                                              \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptCount(                                                   \
          this, "TriangleBudget", "no budget", budget, this->Internal->Settings.triangleBudget))   \
      this->Modify();                                                                          \
  }                                                                                            \
  vtkIdType Class::GetTriangleBudget()                                                         \
  {                                                                                            \
    return static_cast<vtkIdType>(this->Internal->Settings.triangleBudget);                    \
  }                                                                                            \
  void Class::SetHeightScale(double scale)                                                     \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptHeightScale(this, scale, this->Internal->Settings.heightScale)) \
      this->Modify();                                                                          \
  }                                                                                            \
  double Class::GetHeightScale() { return this->Internal->Settings.heightScale; }              \
  void Class::SetGeomorphing(bool on)                                                          \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptSetting(on, this->Internal->Settings.geomorphing))       \
      this->Modify();                                                                          \
  }                                                                                            \
  bool Class::GetGeomorphing() { return this->Internal->Settings.geomorphing; }                \
  void Class::SetGeomorphRange(double range)                                                   \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptSetting(range, this->Internal->Settings.geomorphRange))  \
      this->Modify();                                                                          \
  }                                                                                            \
  double Class::GetGeomorphRange() { return this->Internal->Settings.geomorphRange; }          \
  void Class::SetGeomorphMerges(bool on)                                                       \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptSetting(on, this->Internal->Settings.geomorphMerges))    \
      this->Modify();                                                                          \
  }                                                                                            \
  bool Class::GetGeomorphMerges() { return this->Internal->Settings.geomorphMerges; }        \
  void Class::SetGeomorphMeasureSamples(vtkIdType samples)                                     \
  {                                                                                            \
    if (vtkGeoMipMapConversion::AcceptCount(this, "GeomorphMeasureSamples", "no limit", samples, \
          this->Internal->Settings.geomorphMeasureSamples))                                    \
      this->Modify();                                                                          \
  }                                                                                            \
  vtkIdType Class::GetGeomorphMeasureSamples()                                                 \
  {                                                                                            \
    return static_cast<vtkIdType>(this->Internal->Settings.geomorphMeasureSamples);            \
  }

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapConversion.h
