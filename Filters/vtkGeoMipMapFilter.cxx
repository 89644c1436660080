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

#include "Engine.h"
#include "Morph.h"
#include "RayCast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

struct vtkGeoMipMapFilter::Internals
{
  gmm::Engine Engine;
  // The terrain the engine uses (shared with every other consumer of the input image).
  vtkSmartPointer<vtkGeoMipMapTerrain> Terrain;
  gmm::MorphFrame Morph; // this frame's geomorph factors (all 0 when not morphing)
  gmm::MorphCache MorphCache;
};

vtkStandardNewMacro(vtkGeoMipMapFilter);
vtkCxxSetObjectMacro(vtkGeoMipMapFilter, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkGeoMipMapFilter, ModelMatrix, vtkMatrix4x4);

//------------------------------------------------------------------------------
vtkGeoMipMapFilter::vtkGeoMipMapFilter()
  : BlockSize(gmm::kDefaultBlockQuads)
  , GeomorphRange(gmm::kDefaultMorphRange)
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
  std::string err;
  vtkGeoMipMapTerrain* terrain = vtkGeoMipMapTerrain::Get(image, this->BlockSize, this, err,
    vtkGeoMipMapTerrain::TableCacheOptions(this->TableCache, this->TableCacheDirectory));
  if (!terrain)
  {
    in.Terrain = nullptr;
    in.Engine.setTerrain(nullptr);
    vtkErrorMacro("Cannot use the input image: " << err);
    return 0;
  }
  if (terrain != in.Terrain)
  {
    in.Terrain = terrain;
    in.Engine.setTerrain(terrain->GetTerrain());
  }
  in.Engine.setHeightScale(this->HeightScale);

  const gmm::FrameStats* stats = nullptr;
  if (this->MaximumGeometricError > 0.0 || !this->Camera)
  {
    stats = &in.Engine.updateForError(this->MaximumGeometricError);
  }
  else
  {
    gmm::View view;
    err = vtkGeoMipMapConversion::CameraToView(
      this->Camera, this->ModelMatrix, this->ViewportSize[0], this->ViewportSize[1], view);
    if (!err.empty())
    {
      vtkErrorMacro("Cannot use the camera: " << err);
      return 0;
    }
    // Geomorphing's level path (MorphRamp.h; none for a range that is not finite and > 1).
    in.Engine.setMorphRange(this->Geomorphing ? this->GeomorphRange : 0.0);
    in.Engine.setMergeOnPath(this->GeomorphMerges);
    stats = &in.Engine.update(
      view, this->PixelError, static_cast<std::size_t>(this->TriangleBudget), this->BudgetStartTau);
  }
  // Geomorphing needs a camera's projection factors: the view-independent mode never morphs.
  const bool morph = this->Geomorphing && !(this->MaximumGeometricError > 0.0 || !this->Camera) &&
    in.Engine.lastError().empty();
  if (morph)
  {
    gmm::computeMorph(in.Engine.heightfield(), in.Engine.quadtree(), in.Engine.levels(),
      in.Engine.pixelFactors(), gmm::morphErrorBudget(*stats, this->PixelError), in.MorphCache, in.Morph,
      in.Engine.morphRamp(), &in.Engine.drawnBlocks(), &in.Engine.drawnConfigs(), &in.Engine.errorTable());
  }
  else if (!in.Engine.empty())
  {
    gmm::clearMorph(in.Engine.quadtree(), in.Morph);
  }
  if (!in.Engine.lastError().empty())
  {
    vtkErrorMacro("LOD update failed: " << in.Engine.lastError());
    return 0;
  }

  // Compact: only the samples the triangles use, in sample order. Sorted rather than
  // looked up in a table over all samples, so that the work and memory follow the
  // triangles, not the DEM (a table of ids took 2 GiB per update at 16385^2).
  const gmm::Heightfield& hf = in.Engine.heightfield();
  const std::vector<uint32_t>& tris = in.Engine.indices();
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
    const double z = morph
      ? gmm::morphedHeight(hf, in.Engine.quadtree(), in.Engine.levels(), in.Morph, i, j)
      : static_cast<double>(hf.heights()[used[p]]);
    xyz->SetTypedTuple(p,
      std::array<double, 3>{ hf.worldX(i), hf.worldY(j), hf.z0 + this->HeightScale * z }.data());
    elevation->SetValue(p, static_cast<float>(z));
    vtkGeoMipMapConversion::SampleNormal(hf, i, j, this->HeightScale, normals->GetPointer(3 * p));
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
  // The bound of what is output: the morphed surface's when morphing (still <= PixelError, or
  // a budgeted frame's own certified error: gmm::morphErrorBudget).
  addDouble("MaximumScreenSpaceError",
    morph ? std::max(stats->maxScreenError, in.Morph.maxBoundPixels) : stats->maxScreenError);
  addDouble("MaximumGeometricError", stats->maxGeometricError);
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
  return gmm::heightAt(terrain->GetTerrain()->hf, x, y, this->HeightScale);
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
void vtkGeoMipMapFilter::SetHeightScale(double scale)
{
  if (vtkGeoMipMapConversion::AcceptHeightScale(this, scale, this->HeightScale))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::SetTriangleBudget(vtkIdType budget)
{
  if (budget < 0)
  {
    vtkErrorMacro("TriangleBudget " << budget << " must be >= 0 (0: no budget); kept " << this->TriangleBudget);
    return;
  }
  if (budget != this->TriangleBudget)
  {
    this->TriangleBudget = budget;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFilter::SetBudgetStartTau(double tau)
{
  if (vtkGeoMipMapConversion::AcceptPixelError(this, tau, this->BudgetStartTau, "BudgetStartTau"))
  {
    this->Modified();
  }
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
  os << indent << "TriangleBudget: " << this->TriangleBudget << "\n";
  os << indent << "BudgetStartTau: " << this->BudgetStartTau << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "TableCache: " << this->TableCache << "\n";
  os << indent << "TableCacheDirectory: "
     << (this->TableCacheDirectory ? this->TableCacheDirectory : "(default)") << "\n";
  os << indent << "MaximumGeometricError: " << this->MaximumGeometricError << "\n";
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "Geomorphing: " << this->Geomorphing << "\n";
  os << indent << "GeomorphRange: " << this->GeomorphRange << "\n";
  os << indent << "GeomorphMerges: " << this->GeomorphMerges << "\n";
  os << indent << "ModelMatrix: " << this->ModelMatrix << "\n";
}
