#include "vtkGeoMipMapTerrainReader.h"

#include "vtkGeoMipMapConversion.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "TerrainFill.h"       // checkFillOptions, fillMemoryBytes
#include "TerrainGeographic.h" // geographicToLocal, localToGeographic
#include "TerrainIO.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkGeoMipMapTerrainReader);

struct vtkGeoMipMapTerrainReader::Internals
{
  gmm::TerrainReadOptions Options(const vtkGeoMipMapTerrainReader* self) const
  {
    gmm::TerrainReadOptions opt;
    opt.heightScale = self->HeightScale;
    opt.heightOffset = self->HeightOffset;
    opt.spacing = self->Spacing;
    opt.terrainRGB = self->TerrainRGB != 0;
    opt.fillNodata = self->FillNodata != 0;
    opt.fillSearchDistance = self->FillSearchDistance;
    opt.fillSmoothingIterations = self->FillSmoothingIterations;
    return opt;
  }
};

//------------------------------------------------------------------------------
vtkGeoMipMapTerrainReader::vtkGeoMipMapTerrainReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkGeoMipMapTerrainReader::~vtkGeoMipMapTerrainReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
int vtkGeoMipMapTerrainReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const std::string name = this->FileName ? this->FileName : "";
  if (!std::isfinite(this->Spacing) || this->Spacing <= 0.0)
  {
    vtkErrorMacro(<< "Cannot read '" << name << "': Spacing " << this->Spacing
                  << " is not finite and positive.");
    return 0;
  }
  if (this->FillNodata)
  {
    const std::string problem =
      gmm::checkFillOptions(this->FillSearchDistance, this->FillSmoothingIterations);
    if (!problem.empty())
    {
      vtkErrorMacro(<< "Cannot read '" << name << "' with FillNodata on: " << problem << ".");
      return 0;
    }
  }
  // Header only: dimensions and georeference, without reading (or allocating) samples.
  gmm::TerrainRaster header;
  const std::string problem =
    gmm::readTerrainHeader(name, this->Internal->Options(this), header);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot read '" << name << "': the file " << problem << ".");
    return 0;
  }
  if (!header.georeferenced)
  {
    // Accepted like an image heightmap, but say so: a GeoTIFF that lost its tags would
    // otherwise silently land at the origin with 1 m (Spacing) samples.
    vtkWarningMacro(<< "Reading '" << name << "': the file has no georeference; using origin "
                    << "(0, 0) and Spacing " << this->Spacing << ".");
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, header.nx - 1, 0, header.ny - 1, 0, 0 };
  double spacing[3] = { header.dx, header.dy, 1.0 };
  double origin[3] = { header.x0, header.y0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGeoMipMapTerrainReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const std::string name = this->FileName ? this->FileName : "";
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro(<< "Cannot read '" << name << "': no output image.");
    return 0;
  }
  output->Initialize(); // a failed read must not leave the previous file's heights behind
  this->UpdateProgress(0.0);
  gmm::TerrainRaster raster;
  {
    // Refuse before allocating what the machine cannot hold (see SetMemoryLimit).
    gmm::TerrainRaster header;
    if (gmm::readTerrainHeader(name, this->Internal->Options(this), header).empty())
    {
      const double samples = static_cast<double>(header.nx) * header.ny;
      // The heights (the output adopts them), as much again for a tiled image's decoded
      // image (OpenImageIO reads tiled files whole), and the source lattice when resampling
      // a geographic raster: conservative for GDAL rasters and scanline images, which are
      // read in chunks of a few MB.
      const double need = samples * sizeof(float) * (header.geographic ? 3.0 : 2.0) +
        (this->FillNodata
            ? gmm::fillMemoryBytes(header.nx, header.ny, this->FillSmoothingIterations)
            : 0.0);
      const double have = this->MemoryLimit > 0 ? static_cast<double>(this->MemoryLimit)
                                                : vtkGeoMipMapConversion::AvailableMemoryBytes();
      if (have > 0 && need > have)
      {
        vtkErrorMacro(<< "Cannot read '" << name << "': its " << header.nx << " x " << header.ny
                      << " samples need about " << need / 1048576.0 << " MiB to read, more than the "
                      << have / 1048576.0 << " MiB "
                      << (this->MemoryLimit > 0 ? "of MemoryLimit" : "available") << ".");
        return 0;
      }
    }
  }
  const std::string problem = gmm::readTerrain(name, this->Internal->Options(this), raster,
    [this](double f) { this->UpdateProgress(0.95 * f); });
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot read '" << name << "': the file " << problem << ".");
    return 0;
  }

  // The whole extent is always produced: the LOD engine needs all of it.
  output->SetExtent(0, raster.nx - 1, 0, raster.ny - 1, 0, 0);
  output->SetSpacing(raster.dx, raster.dy, 1.0);
  output->SetOrigin(raster.x0, raster.y0, 0.0);
  const bool anyValid =
    std::any_of(raster.z.begin(), raster.z.end(), [](float z) { return std::isfinite(z); });
  vtkNew<vtkFloatArray> heights;
  heights->SetName("Elevation");
  // The array adopts the heights' memory (HeightBuffer.h): no second copy of the DEM.
  const vtkIdType count = static_cast<vtkIdType>(raster.z.size());
  heights->SetArray(raster.z.release(), count, 0, vtkFloatArray::VTK_DATA_ARRAY_FREE);
  if (!anyValid)
  {
    // Not an error (a tile of a larger DEM may be all void), but nothing will be drawn.
    vtkWarningMacro(<< "Reading '" << name << "': every sample is nodata; nothing will be drawn.");
  }
  output->GetPointData()->SetScalars(heights);
  if (this->FillNodata)
  {
    vtkNew<vtkUnsignedCharArray> filled;
    filled->SetName("FilledNodata");
    filled->SetNumberOfTuples(heights->GetNumberOfTuples());
    if (raster.filled.size() == static_cast<std::size_t>(heights->GetNumberOfTuples()))
    {
      std::copy(raster.filled.begin(), raster.filled.end(), filled->GetPointer(0));
    }
    else
    {
      filled->FillValue(0); // defensive: a read with FillNodata on always sets the mask
    }
    output->GetPointData()->AddArray(filled);
  }

  vtkFieldData* fd = output->GetFieldData();
  auto addString = [fd](const char* key, const std::string& value) {
    vtkNew<vtkStringArray> a;
    a->SetName(key);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addString("CRS", raster.crs);
  addString("SourceFormat", raster.format);
  addString("HeightUnit", raster.heightUnit);
  if (raster.geographic)
  {
    vtkNew<vtkDoubleArray> lonLat;
    lonLat->SetName("GeographicOrigin");
    lonLat->SetNumberOfComponents(2);
    lonLat->InsertNextTuple2(raster.lon0, raster.lat0);
    fd->AddArray(lonLat);
    vtkNew<vtkDoubleArray> meridian;
    meridian->SetName("CentralMeridian");
    meridian->InsertNextValue(raster.centralMeridian);
    fd->AddArray(meridian);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapTerrainReader::GetGeographicFrame(vtkImageData* image, double frame[3])
{
  vtkFieldData* fd = image ? image->GetFieldData() : nullptr;
  vtkDataArray* origin = fd ? fd->GetArray("GeographicOrigin") : nullptr;
  vtkDataArray* meridian = fd ? fd->GetArray("CentralMeridian") : nullptr;
  if (!origin || !meridian || origin->GetNumberOfTuples() < 1 ||
    origin->GetNumberOfComponents() != 2 || meridian->GetNumberOfTuples() < 1)
  {
    return false;
  }
  frame[0] = origin->GetComponent(0, 0);
  frame[1] = origin->GetComponent(0, 1);
  frame[2] = meridian->GetComponent(0, 0);
  return true;
}

bool vtkGeoMipMapTerrainReader::GeographicToLocal(
  vtkImageData* image, double lon, double lat, double xy[2])
{
  double f[3];
  if (!GetGeographicFrame(image, f))
  {
    return false;
  }
  gmm::geographicToLocal(f[2], f[0], f[1], lon, lat, xy[0], xy[1]);
  return true;
}

bool vtkGeoMipMapTerrainReader::LocalToGeographic(
  vtkImageData* image, double x, double y, double lonLat[2])
{
  double f[3];
  if (!GetGeographicFrame(image, f))
  {
    return false;
  }
  gmm::localToGeographic(f[2], f[0], f[1], x, y, lonLat[0], lonLat[1]);
  return true;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapTerrainReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "HeightOffset: " << this->HeightOffset << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "TerrainRGB: " << (this->TerrainRGB ? "On" : "Off") << "\n";
  os << indent << "FillNodata: " << (this->FillNodata ? "On" : "Off") << "\n";
  os << indent << "FillSearchDistance: " << this->FillSearchDistance << "\n";
  os << indent << "FillSmoothingIterations: " << this->FillSmoothingIterations << "\n";
}
