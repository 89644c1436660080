/**
 * @class   vtkGeoMipMapPicker
 * @brief   A vtkCellPicker that hits the terrain of vtkGeoMipMapMapper actors exactly.
 *
 * vtkCellPicker and vtkPointPicker intersect the pick ray with a mapper's input data set;
 * for vtkGeoMipMapMapper that is the flat 2D image, not the terrain. This picker
 * intersects the ray with the full-resolution surface instead (the level-0 triangulation
 * at origin z + HeightScale * h, nodata as holes; vtkGeoMipMapMapper::IntersectWithLine:
 * a walk of the quadtree boxes and of the grid quads under the ray), whatever level of
 * detail is drawn, under the actor's matrix and the mapper's clipping planes. Every
 * other actor is picked as vtkCellPicker picks it, and the nearest hit wins.
 *
 * For a terrain hit: PickPosition and PickNormal (world) are the exact surface point and
 * its triangle's normal; DataSet is the input image; CellId is the image cell (pixel)
 * under the hit, (j * (nx - 1) + i); PointId is the image sample nearest to the hit among
 * the hit triangle's vertices (what vtkPointPicker would report); SubId is 0 and PCoords
 * the position inside the cell.
 *
 * @sa vtkGeoMipMapMapper vtkCellPicker vtkWorldPointPicker
 */
#ifndef vtkGeoMipMapPicker_h
#define vtkGeoMipMapPicker_h

#include "geomipmapRenderingModule.h" // For export macro
#include "vtkCellPicker.h"

class GEOMIPMAPRENDERING_EXPORT vtkGeoMipMapPicker : public vtkCellPicker
{
public:
  static vtkGeoMipMapPicker* New();
  vtkTypeMacro(vtkGeoMipMapPicker, vtkCellPicker);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkGeoMipMapPicker();
  ~vtkGeoMipMapPicker() override;

  double IntersectActorWithLine(const double p1[3], const double p2[3], double t1, double t2,
    double tol, vtkProp3D* prop, vtkMapper* mapper) override;

private:
  vtkGeoMipMapPicker(const vtkGeoMipMapPicker&) = delete;
  void operator=(const vtkGeoMipMapPicker&) = delete;
};

#endif
