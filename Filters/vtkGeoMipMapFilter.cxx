#include "vtkGeoMipMapFilter.h"

#include "vtkGeoMipMapConversion.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt64Array.h"

#include "Engine.h"

#include <array>
#include <cmath>
#include <vector>

struct vtkGeoMipMapFilter::Internals
{
  gmm::Engine Engine;
  // The engine (quadtree, error table) is kept while the input and block size stay.
  vtkMTimeType InputTime = 0;
  int BlockSize = 0;
  bool Valid = false;
};

vtkStandardNewMacro(vtkGeoMipMapFilter);
vtkCxxSetObjectMacro(vtkGeoMipMapFilter, Camera, vtkCamera);

//------------------------------------------------------------------------------
vtkGeoMipMapFilter::vtkGeoMipMapFilter()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkGeoMipMapFilter::~vtkGeoMipMapFilter()
{
  this->SetCamera(nullptr);
}

//------------------------------------------------------------------------------
int vtkGeoMipMapFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGeoMipMapFilter::GetMTime()
{
  // A camera move must re-execute the filter.
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Camera && this->Camera->GetMTime() > t)
  {
    t = this->Camera->GetMTime();
  }
  return t;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!image || !output)
  {
    return 0;
  }
  Internals& in = *this->Internal;
  if (!in.Valid || in.InputTime != image->GetMTime() || in.BlockSize != this->BlockSize)
  {
    gmm::Heightfield hf;
    std::string err = vtkGeoMipMapConversion::ImageToHeightfield(image, hf);
    if (err.empty())
    {
      err = in.Engine.setHeightfield(hf, this->BlockSize);
    }
    in.Valid = err.empty();
    in.InputTime = image->GetMTime();
    in.BlockSize = this->BlockSize;
    if (!err.empty())
    {
      vtkErrorMacro("Cannot use the input image: " << err);
      return 0;
    }
  }

  const gmm::FrameStats* stats = nullptr;
  if (this->MaximumGeometricError > 0.0 || !this->Camera)
  {
    stats = &in.Engine.updateForError(this->MaximumGeometricError);
  }
  else
  {
    gmm::View view;
    const std::string err = vtkGeoMipMapConversion::CameraToView(
      this->Camera, nullptr, this->ViewportSize[0], this->ViewportSize[1], view);
    if (!err.empty())
    {
      vtkErrorMacro("Cannot use the camera: " << err);
      return 0;
    }
    stats = &in.Engine.update(view, this->PixelError);
  }
  if (!in.Engine.lastError().empty())
  {
    vtkErrorMacro("LOD update failed: " << in.Engine.lastError());
    return 0;
  }

  // Compact: only the samples the triangles use, numbered in first-use order.
  const gmm::Heightfield& hf = in.Engine.heightfield();
  const std::vector<uint32_t>& tris = in.Engine.indices();
  std::vector<vtkIdType> newId(hf.z.size(), -1);
  std::vector<uint32_t> used;
  vtkNew<vtkTypeInt64Array> conn;
  conn->SetNumberOfTuples(static_cast<vtkIdType>(tris.size()));
  for (std::size_t k = 0; k < tris.size(); ++k)
  {
    vtkIdType& id = newId[tris[k]];
    if (id < 0)
    {
      id = static_cast<vtkIdType>(used.size());
      used.push_back(tris[k]);
    }
    conn->SetValue(static_cast<vtkIdType>(k), id);
  }
  const vtkIdType nTris = static_cast<vtkIdType>(tris.size() / 3);
  vtkNew<vtkTypeInt64Array> offsets;
  offsets->SetNumberOfTuples(nTris + 1);
  for (vtkIdType t = 0; t <= nTris; ++t)
  {
    offsets->SetValue(t, 3 * t);
  }
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, conn);

  const vtkIdType nPts = static_cast<vtkIdType>(used.size());
  vtkNew<vtkDoubleArray> xyz; // double: UTM-size coordinates keep their precision
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(nPts);
  vtkNew<vtkFloatArray> elevation;
  elevation->SetName("Elevation");
  elevation->SetNumberOfTuples(nPts);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(nPts);
  for (vtkIdType p = 0; p < nPts; ++p)
  {
    const int i = static_cast<int>(used[p] % static_cast<uint32_t>(hf.nx));
    const int j = static_cast<int>(used[p] / static_cast<uint32_t>(hf.nx));
    const float z = hf.z[used[p]];
    xyz->SetTypedTuple(p, std::array<double, 3>{ hf.worldX(i), hf.worldY(j), z }.data());
    elevation->SetValue(p, z);
    vtkGeoMipMapConversion::SampleNormal(hf, i, j, normals->GetPointer(3 * p));
  }
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetPointData()->SetScalars(elevation);
  output->GetPointData()->SetNormals(normals);

  auto addInt = [output](const char* name, double v) {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->InsertNextValue(static_cast<int>(v));
    output->GetFieldData()->AddArray(a);
  };
  auto addDouble = [output](const char* name, double v) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(v);
    output->GetFieldData()->AddArray(a);
  };
  vtkNew<vtkTypeInt64Array> triCount;
  triCount->SetName("Triangles");
  triCount->InsertNextValue(static_cast<vtkTypeInt64>(stats->triangles));
  output->GetFieldData()->AddArray(triCount);
  addInt("VisibleBlocks", stats->visibleBlocks);
  addInt("CulledBlocks", stats->culledBlocks);
  addDouble("MaximumScreenSpaceError", stats->maxScreenError);
  addDouble("MaximumGeometricError", stats->maxGeometricError);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::SetPixelError(double tau)
{
  if (vtkGeoMipMapConversion::AcceptPixelError(this, tau, this->PixelError))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1]
     << "\n";
  os << indent << "PixelError: " << this->PixelError << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "MaximumGeometricError: " << this->MaximumGeometricError << "\n";
}
