#include "vtkGeoMipMapFractalSource.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "HugePages.h" // gmm::adviseHugePages
#include "SyntheticTerrain.h"

#include <cmath>
#include <cstring>
#include <string>

vtkStandardNewMacro(vtkGeoMipMapFractalSource);

//------------------------------------------------------------------------------
vtkGeoMipMapFractalSource::vtkGeoMipMapFractalSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapFractalSource::CheckParameters() const
{
  const int nx = this->Dimensions[0], ny = this->Dimensions[1];
  if (nx < 2 || ny < 2)
  {
    return "Dimensions " + std::to_string(nx) + " x " + std::to_string(ny) +
      " are below the minimum of 2 x 2.";
  }
  // vtkIdType is 64-bit, but the engine indexes samples with uint32 and VTK arrays of more
  // than 2^31 values are impractical here: refuse before allocating.
  if (static_cast<long long>(nx) * ny > 2147483647LL)
  {
    return "Dimensions " + std::to_string(nx) + " x " + std::to_string(ny) +
      " exceed 2^31 - 1 samples.";
  }
  if (!std::isfinite(this->Spacing) || this->Spacing <= 0.0)
  {
    return "Spacing " + std::to_string(this->Spacing) + " is not finite and positive.";
  }
  if (!std::isfinite(this->Amplitude))
  {
    return "Amplitude is not finite.";
  }
  return std::string();
}

//------------------------------------------------------------------------------
int vtkGeoMipMapFractalSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const std::string problem = this->CheckParameters();
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, this->Dimensions[0] - 1, 0, this->Dimensions[1] - 1, 0, 0 };
  double spacing[3] = { this->Spacing, this->Spacing, 1.0 };
  double origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapFractalSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  const std::string problem = this->CheckParameters();
  if (!output || !problem.empty())
  {
    vtkErrorMacro(<< (problem.empty() ? std::string("No output image.") : problem));
    return 0;
  }
  this->UpdateProgress(0.0);
  // Generated straight into the output array: a large DEM is never held twice.
  const int nx = this->Dimensions[0], ny = this->Dimensions[1];
  vtkNew<vtkFloatArray> heights;
  heights->SetName("Elevation");
  heights->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny);
  gmm::adviseHugePages(heights->GetPointer(0), static_cast<std::size_t>(nx) * ny * sizeof(float));
  if (!gmm::fillSyntheticTerrain(
        heights->GetPointer(0), nx, ny, this->Spacing, this->Seed, this->Amplitude))
  {
    vtkErrorMacro(<< "Terrain generation failed.");
    return 0;
  }
  this->UpdateProgress(0.9);

  // The whole extent is produced regardless of the requested piece: the terrain is cheap
  // next to anything downstream and the LOD engine needs all of it.
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetSpacing(this->Spacing, this->Spacing, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  output->GetPointData()->SetScalars(heights);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapFractalSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dimensions: " << this->Dimensions[0] << " x " << this->Dimensions[1] << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Amplitude: " << this->Amplitude << "\n";
}
