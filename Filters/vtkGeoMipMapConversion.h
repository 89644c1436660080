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

#include "Heightfield.h" // gmm::Heightfield
#include "View.h"        // gmm::View

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
 * type); NaN/Inf are nodata. Sample (i, j) sits at origin + (extent min + (i, j)) * spacing;
 * a direction matrix must be diagonal with entries +-1 (a flip becomes a negative
 * spacing). The image's z origin is ignored: heights are absolute.
 * Returns "" on success, else why the image cannot be used.
 */
GEOMIPMAPFILTERS_EXPORT std::string ImageToHeightfield(
  vtkImageData* image, gmm::Heightfield& hf, vtkDataArray* heights = nullptr);

/**
 * A camera and a viewport of width x height pixels as a gmm::View in the data's own
 * coordinates. `dataToWorld` is the actor's matrix (nullptr = identity): eye, focal
 * point and view-up go through its inverse, and the clipping range and parallel scale are
 * divided by its scale. Exact for rotations, translations and uniform scale; for a
 * non-uniform scale the geometric-mean scale is used, so error bounds are approximate
 * (a vertical exaggeration k magnifies screen errors by up to k).
 * Returns "" on success, else why (no camera, singular matrix, empty viewport).
 */
GEOMIPMAPFILTERS_EXPORT std::string CameraToView(vtkCamera* camera, vtkMatrix4x4* dataToWorld,
  int width, int height, gmm::View& view);

/**
 * The SetPixelError rule of the mapper and the filter: a finite tau >= 0 is stored in
 * `current` and true is returned when it differs (the caller then marks itself modified);
 * anything else is refused with an error reported by `self`, and `current` is kept.
 */
GEOMIPMAPFILTERS_EXPORT bool AcceptPixelError(vtkObject* self, double tau, double& current);

/**
 * Unit normal at sample (i, j) from full-resolution central differences (one-sided next
 * to the border or to nodata; (0, 0, 1) when no neighbour is valid).
 */
GEOMIPMAPFILTERS_EXPORT void SampleNormal(const gmm::Heightfield& hf, int i, int j, float n[3]);
}

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapConversion.h
