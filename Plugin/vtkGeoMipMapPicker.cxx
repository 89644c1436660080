#include "vtkGeoMipMapPicker.h"

#include "vtkGeoMipMapMapper.h"

#include "vtkActor.h"
#include "vtkDataSet.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkGeoMipMapPicker);

vtkGeoMipMapPicker::vtkGeoMipMapPicker() = default;
vtkGeoMipMapPicker::~vtkGeoMipMapPicker() = default;

//------------------------------------------------------------------------------
double vtkGeoMipMapPicker::IntersectActorWithLine(const double p1[3], const double p2[3],
  double t1, double t2, double tol, vtkProp3D* prop, vtkMapper* mapper)
{
  vtkGeoMipMapMapper* terrain = vtkGeoMipMapMapper::SafeDownCast(mapper);
  if (!terrain)
  {
    return this->Superclass::IntersectActorWithLine(p1, p2, t1, t2, tol, prop, mapper);
  }
  // The part of the ray the clipping planes leave, [t1, t2] of p1 -> p2 (data coordinates).
  double q1[3], q2[3];
  for (int k = 0; k < 3; ++k)
  {
    q1[k] = p1[k] + t1 * (p2[k] - p1[k]);
    q2[k] = p1[k] + t2 * (p2[k] - p1[k]);
  }
  double s = 0.0, x[3], normal[3];
  vtkIdType pointId = -1, cellId = -1;
  if (!terrain->IntersectWithLine(q1, q2, s, x, normal, pointId, cellId))
  {
    return VTK_DOUBLE_MAX;
  }
  const double t = t1 + s * (t2 - t1);
  if (t >= this->GlobalTMin)
  {
    return t; // something nearer was hit already; vtkCellPicker keeps that one
  }
  this->ResetPickInfo();
  vtkImageData* image = vtkImageData::SafeDownCast(terrain->GetInputDataObject(0, 0));
  this->Mapper = terrain;
  this->DataSet = image;
  this->CellId = cellId;
  this->PointId = pointId;
  this->SubId = 0;
  if (image)
  {
    // Position inside the image cell, as vtkImageData's pixel parametric coordinates.
    int ijk[3];
    double pcoords[3];
    if (image->ComputeStructuredCoordinates(x, ijk, pcoords))
    {
      std::copy(pcoords, pcoords + 3, this->PCoords);
    }
  }
  if (vtkActor* actor = vtkActor::SafeDownCast(prop))
  {
    this->Texture = actor->GetTexture();
  }
  std::copy(x, x + 3, this->MapperPosition);
  std::copy(normal, normal + 3, this->MapperNormal);
  return t;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapPicker::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
