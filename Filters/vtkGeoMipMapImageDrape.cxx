#include "vtkGeoMipMapImageDrape.h"

#include "vtkGeoMipMapConversion.h"
#include "vtkGeoMipMapTerrainReader.h"

#include "vtkAbstractArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "TerrainDrape.h"

#include <algorithm>
#include <cstring>

vtkStandardNewMacro(vtkGeoMipMapImageDrape);

namespace
{
// The terrain's frame from its field data; false (with `why`) when it has none.
bool FrameOf(vtkImageData* terrain, gmm::TerrainFrame& frame, std::string& why)
{
  vtkFieldData* fd = terrain ? terrain->GetFieldData() : nullptr;
  vtkStringArray* crs =
    fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray("CRS")) : nullptr;
  if (!terrain)
  {
    why = "no terrain was set (SetTerrain: the terrain reader's output)";
    return false;
  }
  if (!crs || crs->GetNumberOfValues() < 1)
  {
    why = "the terrain has no \"CRS\" field data (is it vtkGeoMipMapTerrainReader's output, "
          "updated?)";
    return false;
  }
  frame.crs = crs->GetValue(0);
  double f[3];
  frame.geographic = vtkGeoMipMapTerrainReader::GetGeographicFrame(terrain, f);
  if (frame.geographic)
  {
    frame.lon0 = f[0];
    frame.lat0 = f[1];
    frame.centralMeridian = f[2];
  }
  return true;
}
}

//------------------------------------------------------------------------------
vtkGeoMipMapImageDrape::vtkGeoMipMapImageDrape()
{
  this->SetNumberOfInputPorts(0);
}

vtkGeoMipMapImageDrape::~vtkGeoMipMapImageDrape()
{
  this->SetFileName(nullptr);
}

void vtkGeoMipMapImageDrape::SetTerrain(vtkImageData* terrain)
{
  if (this->Terrain != terrain)
  {
    this->Terrain = terrain;
    this->Modified();
  }
}

vtkImageData* vtkGeoMipMapImageDrape::GetTerrain()
{
  return this->Terrain;
}

vtkMTimeType vtkGeoMipMapImageDrape::GetMTime()
{
  const vtkMTimeType m = this->Superclass::GetMTime();
  return this->Terrain ? std::max(m, this->Terrain->GetMTime()) : m;
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapImageDrape::Plan(gmm::TerrainFrame& frame, gmm::DrapeRaster& plan)
{
  const std::string name = this->FileName ? this->FileName : "";
  std::string problem;
  if (!FrameOf(this->Terrain, frame, problem))
  {
    vtkErrorMacro(<< "Cannot drape '" << name << "': " << problem << ".");
    return false;
  }
  problem = name.empty() ? std::string("no file name was given")
                         : gmm::planDrape(name, frame, this->Options(), plan);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot drape '" << name << "': " << problem << ".");
    return false;
  }
  return true;
}

gmm::DrapeOptions vtkGeoMipMapImageDrape::Options() const
{
  gmm::DrapeOptions options;
  options.maximumSize = this->MaximumSize;
  return options;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapImageDrape::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  gmm::TerrainFrame frame;
  gmm::DrapeRaster plan;
  if (!this->Plan(frame, plan))
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, plan.nx - 1, 0, plan.ny - 1, 0, 0 };
  double spacing[3] = { plan.dx, plan.dy, 1.0 };
  double origin[3] = { plan.x0, plan.y0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapImageDrape::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const std::string name = this->FileName ? this->FileName : "";
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro(<< "Cannot drape '" << name << "': no output image.");
    return 0;
  }
  output->Initialize();
  gmm::TerrainFrame frame;
  gmm::DrapeRaster drape;
  if (!this->Plan(frame, drape))
  {
    return 0;
  }
  // Refuse before reading what the machine cannot hold (the pixels about three times:
  // GDAL's, ours and the output's).
  const double need = 3.0 * 4.0 * drape.nx * static_cast<double>(drape.ny);
  const double have = vtkGeoMipMapConversion::AvailableMemoryBytes();
  if (have > 0 && need > have)
  {
    vtkErrorMacro(<< "Cannot drape '" << name << "': its " << drape.nx << " x " << drape.ny
                  << " pixels need about " << need / 1048576.0 << " MiB, more than the "
                  << have / 1048576.0 << " MiB available; set MaximumSize.");
    return 0;
  }
  this->UpdateProgress(0.1);
  const std::string problem = gmm::readDrape(name, frame, this->Options(), drape);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot drape '" << name << "': " << problem << ".");
    return 0;
  }
  if (!drape.warning.empty())
  {
    vtkWarningMacro(<< "Draping '" << name << "': " << drape.warning << ".");
  }
  output->SetExtent(0, drape.nx - 1, 0, drape.ny - 1, 0, 0);
  output->SetSpacing(drape.dx, drape.dy, 1.0);
  output->SetOrigin(drape.x0, drape.y0, 0.0);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("DrapeRGBA");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(drape.nx) * drape.ny);
  std::memcpy(rgba->GetPointer(0), drape.rgba.data(), drape.rgba.size());
  output->GetPointData()->SetScalars(rgba);
  vtkNew<vtkStringArray> crs;
  crs->SetName("CRS");
  crs->InsertNextValue(drape.crs);
  output->GetFieldData()->AddArray(crs);
  vtkNew<vtkIntArray> warped;
  warped->SetName("DrapeWarped");
  warped->InsertNextValue(drape.warped ? 1 : 0);
  output->GetFieldData()->AddArray(warped);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapImageDrape::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Terrain: " << this->Terrain.GetPointer() << "\n";
  os << indent << "MaximumSize: " << this->MaximumSize << "\n";
}
