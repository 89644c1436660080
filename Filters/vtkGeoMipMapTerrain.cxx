#include "vtkGeoMipMapTerrain.h"

#include "vtkGeoMipMapConversion.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseKey.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <array>
#include <chrono>
#include <cstdlib>

vtkStandardNewMacro(vtkGeoMipMapTerrain);
vtkInformationKeyMacro(vtkGeoMipMapTerrain, TERRAIN, ObjectBase);

// What the terrain was built from: the geometry by value, the heights by identity and MTime.
struct vtkGeoMipMapTerrain::Signature
{
  std::array<int, 6> Extent;
  std::array<double, 3> Origin, Spacing;
  std::array<double, 9> Direction;
  vtkWeakPointer<vtkDataArray> Heights;
  vtkMTimeType HeightsTime = 0;
  int BlockSize = 0;

  static Signature Of(vtkImageData* image, vtkDataArray* heights, int blockSize)
  {
    Signature s;
    image->GetExtent(s.Extent.data());
    image->GetOrigin(s.Origin.data());
    image->GetSpacing(s.Spacing.data());
    vtkMatrix3x3::DeepCopy(s.Direction.data(), image->GetDirectionMatrix());
    s.Heights = heights;
    s.HeightsTime = heights ? heights->GetMTime() : 0;
    s.BlockSize = blockSize;
    return s;
  }

  bool operator==(const Signature& o) const
  {
    return this->Extent == o.Extent && this->Origin == o.Origin && this->Spacing == o.Spacing &&
      this->Direction == o.Direction && this->Heights && this->Heights == o.Heights &&
      this->HeightsTime == o.HeightsTime && this->BlockSize == o.BlockSize;
  }
};

//------------------------------------------------------------------------------
vtkGeoMipMapTerrain::vtkGeoMipMapTerrain() = default;
vtkGeoMipMapTerrain::~vtkGeoMipMapTerrain() = default;

//------------------------------------------------------------------------------
vtkDataArray* vtkGeoMipMapTerrain::GetHeights() const
{
  return this->Built ? this->Built->Heights.GetPointer() : nullptr;
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapTerrain::IsCurrentFor(vtkImageData* image, vtkDataArray* heights, int blockSize) const
{
  return this->Terrain && this->Built && *this->Built == Signature::Of(image, heights, blockSize);
}

//------------------------------------------------------------------------------
std::string vtkGeoMipMapTerrain::DefaultTableCacheDirectory()
{
  if (const char* dir = std::getenv("GEOMIPMAP_CACHE_DIR"))
  {
    return std::string(dir) == "off" ? std::string() : std::string(dir);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"))
  {
    if (*xdg)
    {
      return std::string(xdg) + "/geomipmap";
    }
  }
  if (const char* home = std::getenv("HOME"))
  {
    if (*home)
    {
      return std::string(home) + "/.cache/geomipmap";
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
gmm::TableCacheOptions vtkGeoMipMapTerrain::TableCacheOptions(bool enabled, const char* directory)
{
  gmm::TableCacheOptions options;
  if (enabled)
  {
    options.directory =
      directory && *directory ? std::string(directory) : DefaultTableCacheDirectory();
  }
  return options;
}

//------------------------------------------------------------------------------
vtkGeoMipMapTerrain* vtkGeoMipMapTerrain::Bind(vtkImageData* image, int blockSize, vtkAlgorithm* self,
  const gmm::TableCacheOptions& cache, vtkSmartPointer<vtkGeoMipMapTerrain>& current,
  gmm::FrameDriver& driver, bool& changed)
{
  std::string err;
  vtkGeoMipMapTerrain* terrain = vtkGeoMipMapTerrain::Get(image, blockSize, self, err, cache);
  changed = terrain != current;
  if (!terrain)
  {
    current = nullptr;
    driver.setTerrain(nullptr);
    vtkErrorWithObjectMacro(self, "Cannot use the input image: " << err);
    return nullptr;
  }
  if (changed)
  {
    current = terrain;
    driver.setTerrain(terrain->GetTerrain());
  }
  return terrain;
}

//------------------------------------------------------------------------------
vtkGeoMipMapTerrain* vtkGeoMipMapTerrain::Get(vtkImageData* image, int blockSize,
  vtkAlgorithm* progress, std::string& error, const gmm::TableCacheOptions& cache)
{
  error.clear();
  if (!image)
  {
    error = "no input image";
    return nullptr;
  }
  vtkDataArray* heights = image->GetPointData()->GetScalars();
  auto* cached = vtkGeoMipMapTerrain::SafeDownCast(image->GetInformation()->Get(TERRAIN()));
  if (cached && cached->IsCurrentFor(image, heights, blockSize))
  {
    return cached;
  }
  const auto start = std::chrono::steady_clock::now();
  gmm::Heightfield hf;
  error = vtkGeoMipMapConversion::ImageToHeightfield(image, hf);
  std::shared_ptr<const gmm::Terrain> terrain;
  gmm::TableCacheReport cacheReport;
  if (error.empty())
  {
    gmm::ProgressFn report;
    if (progress)
    {
      report = [progress](double f) { progress->UpdateProgress(f); };
    }
    error = gmm::buildTerrain(std::move(hf), blockSize, 0, terrain, report, cache, &cacheReport);
  }
  if (!error.empty())
  {
    return nullptr;
  }
  if (!cacheReport.problem.empty())
  {
    // The tables are fine (built); only the cache could not serve or keep them.
    if (progress)
    {
      vtkWarningWithObjectMacro(progress, "Table cache: " << cacheReport.problem);
    }
    else
    {
      vtkGenericWarningMacro("geomipmap table cache: " << cacheReport.problem);
    }
  }
  vtkNew<vtkGeoMipMapTerrain> built;
  built->Terrain = std::move(terrain);
  built->CacheReport = cacheReport;
  built->Built.reset(new Signature(Signature::Of(image, heights, blockSize)));
  built->BuildTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  image->GetInformation()->Set(TERRAIN(), built); // the image holds it; so do the callers
  return built;
}

//------------------------------------------------------------------------------
size_t vtkGeoMipMapTerrain::GetMemoryBytes() const
{
  if (!this->Terrain)
  {
    return 0;
  }
  const gmm::Terrain& t = *this->Terrain;
  size_t bytes = t.hf.z.capacity() * sizeof(float);
  bytes += t.qt.nodes.capacity() * sizeof(gmm::QuadtreeNode) +
    t.qt.blockBox.capacity() * sizeof(gmm::Box) + t.qt.blockHasNodata.capacity() +
    (t.qt.nodataBits.capacity() + t.qt.nodataBitsAt.capacity()) * sizeof(uint64_t) +
    t.qt.nodataDepth.capacity() * sizeof(uint16_t);
  bytes += (t.table.ownError.capacity() + t.table.ownErrorExact.capacity() +
             t.table.stripError.capacity()) * sizeof(float);
  return bytes;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapTerrain::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  if (this->Terrain)
  {
    os << indent << "Samples: " << this->Terrain->hf.nx << " x " << this->Terrain->hf.ny << "\n";
    os << indent << "BlockSize: " << this->Terrain->maxBlockQuads << "\n";
    os << indent << "HeightsShared: " << (this->Terrain->hf.external != nullptr) << "\n";
  }
  os << indent << "BuildTime: " << this->BuildTime << "\n";
  os << indent << "TableCache: "
     << (!this->CacheReport.used ? "not used"
           : this->CacheReport.hit ? "read from " + this->CacheReport.path
           : this->CacheReport.written ? "built and saved to " + this->CacheReport.path
                                       : "built, not saved")
     << "\n";
  os << indent << "MemoryBytes: " << this->GetMemoryBytes() << "\n";
}
