#include "vtkGeoMipMapFilter.h"

#include "vtkGeoMipMapConversion.h"
#include "vtkGeoMipMapTerrain.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt64Array.h"

#include "Frame.h"
#include "RayCast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

struct vtkGeoMipMapFilter::Internals
{
  // The LOD settings shared with vtkGeoMipMapMapper, and the frame recipe that runs them.
  gmm::FrameSettings Settings;
  gmm::FrameDriver Driver;
  // The terrain the driver uses (shared with every other consumer of the input image).
  vtkSmartPointer<vtkGeoMipMapTerrain> Terrain;
};

vtkStandardNewMacro(vtkGeoMipMapFilter);
vtkCxxSetObjectMacro(vtkGeoMipMapFilter, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkGeoMipMapFilter, ModelMatrix, vtkMatrix4x4);

//------------------------------------------------------------------------------
vtkGeoMipMapFilter::vtkGeoMipMapFilter()
  : BlockSize(gmm::kDefaultBlockQuads)
  , Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkGeoMipMapFilter::~vtkGeoMipMapFilter()
{
  this->SetCamera(nullptr);
  this->SetModelMatrix(nullptr);
  this->SetTableCacheDirectory(nullptr);
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
  if (this->ModelMatrix && this->ModelMatrix->GetMTime() > t)
  {
    t = this->ModelMatrix->GetMTime();
  }
  return t;
}

namespace
{
// The driver's frame as a vtkPolyData: its triangles over the samples they use (compacted, in
// sample order; sorted rather than looked up in a table over all samples, so that the work
// and memory follow the triangles, not the DEM: a table of ids took 2 GiB per update at
// 16385^2), at their drawn heights, with the full-resolution normals and the frame's
// statistics as field data.
void FrameToPolyData(const gmm::FrameDriver& driver, double heightScale, vtkPolyData* output)
{
  const gmm::Frame& frame = driver.frame();
  const gmm::Engine& engine = driver.engine();
  const gmm::Heightfield& hf = engine.heightfield();
  const std::vector<uint32_t>& tris = engine.indices();
  std::vector<uint32_t> used(tris);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  vtkNew<vtkTypeInt64Array> conn;
  conn->SetNumberOfTuples(static_cast<vtkIdType>(tris.size()));
  for (std::size_t k = 0; k < tris.size(); ++k)
  {
    conn->SetValue(static_cast<vtkIdType>(k),
      static_cast<vtkIdType>(std::lower_bound(used.begin(), used.end(), tris[k]) - used.begin()));
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
    // Morphed or not, as the mapper draws it (glided edges' samples on their polylines).
    const double z = gmm::morphedHeight(hf, engine.quadtree(), engine.levels(), driver.morph(), i, j);
    xyz->SetTypedTuple(
      p, std::array<double, 3>{ hf.worldX(i), hf.worldY(j), hf.z0 + heightScale * z }.data());
    elevation->SetValue(p, static_cast<float>(z));
    vtkGeoMipMapConversion::SampleNormal(hf, i, j, heightScale, normals->GetPointer(3 * p));
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
  triCount->InsertNextValue(static_cast<vtkTypeInt64>(frame.stats.triangles));
  output->GetFieldData()->AddArray(triCount);
  addInt("VisibleBlocks", frame.stats.visibleBlocks);
  addInt("CulledBlocks", frame.stats.culledBlocks);
  // The bound of what is output: the morphed surface's when morphing (still <= PixelError, or
  // a budgeted frame's own certified error: gmm::morphErrorBudget).
  addDouble("MaximumScreenSpaceError", frame.stats.maxScreenError);
  addDouble("MaximumGeometricError", frame.stats.maxGeometricError);
}
} // namespace

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
  bool changed = false;
  if (!vtkGeoMipMapTerrain::Bind(image, this->BlockSize, this,
        vtkGeoMipMapTerrain::TableCacheOptions(this->TableCache, this->TableCacheDirectory), in.Terrain,
        in.Driver, changed))
  {
    return 0;
  }

  // The frame (gmm::FrameDriver), as the mapper runs it; view-independent without a camera.
  const gmm::Frame* frame = nullptr;
  if (this->MaximumGeometricError > 0.0 || !this->Camera)
  {
    frame = &in.Driver.updateForError(this->MaximumGeometricError, in.Settings);
  }
  else
  {
    gmm::View view;
    const std::string err = vtkGeoMipMapConversion::CameraToView(
      this->Camera, this->ModelMatrix, this->ViewportSize[0], this->ViewportSize[1], view);
    if (!err.empty())
    {
      vtkErrorMacro("Cannot use the camera: " << err);
      return 0;
    }
    frame = &in.Driver.update(view, in.Settings);
  }
  if (!frame->ok())
  {
    vtkErrorMacro("LOD update failed: " << frame->error);
    return 0;
  }
  FrameToPolyData(in.Driver, in.Settings.heightScale, output);
  return 1;
}

//------------------------------------------------------------------------------
double vtkGeoMipMapFilter::GetHeightAt(double x, double y)
{
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  this->GetInputAlgorithm()->Update();
  std::string err;
  vtkGeoMipMapTerrain* terrain =
    vtkGeoMipMapTerrain::Get(vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0)),
      this->BlockSize, this, err,
      vtkGeoMipMapTerrain::TableCacheOptions(this->TableCache, this->TableCacheDirectory));
  if (!terrain)
  {
    vtkErrorMacro("Cannot use the input image: " << err);
    return std::numeric_limits<double>::quiet_NaN();
  }
  return gmm::heightAt(terrain->GetTerrain()->hf, x, y, this->Internal->Settings.heightScale);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::SetBlockSize(int quads)
{
  if (vtkGeoMipMapConversion::AcceptBlockSize(this, quads, this->BlockSize))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
// The LOD settings: stored in the FrameSettings shared with vtkGeoMipMapMapper, by its rules.
vtkGeoMipMapFrameSettingsMacro(vtkGeoMipMapFilter, Modified);

void vtkGeoMipMapFilter::SetBudgetStartTau(double tau)
{
  if (vtkGeoMipMapConversion::AcceptPixelError(
        this, tau, this->Internal->Settings.budgetStartTau, "BudgetStartTau"))
  {
    this->Modified();
  }
}
double vtkGeoMipMapFilter::GetBudgetStartTau()
{
  return this->Internal->Settings.budgetStartTau;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1]
     << "\n";
  vtkGeoMipMapConversion::PrintFrameSettings(os, indent, this->Internal->Settings);
  os << indent << "BudgetStartTau: " << this->Internal->Settings.budgetStartTau << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "TableCache: " << this->TableCache << "\n";
  os << indent << "TableCacheDirectory: "
     << (this->TableCacheDirectory ? this->TableCacheDirectory : "(default)") << "\n";
  os << indent << "MaximumGeometricError: " << this->MaximumGeometricError << "\n";
  os << indent << "ModelMatrix: " << this->ModelMatrix << "\n";
}
