/**
 * @class   vtkGeoMipMapTerrain
 * @brief   The engine's terrain (heightfield, quadtree, error tables) of one DEM image,
 *          built once and shared by every consumer of that image.
 *
 * vtkGeoMipMapMapper, vtkGeoMipMapFilter and vtkGeoMipMapPicker all need the same
 * gmm::Terrain for an image. Get() returns the one cached on the image (in its
 * information, key TERRAIN()) while it is current: same geometry (dimensions, extent,
 * origin, spacing, direction), same heights array with the same MTime, same block size.
 * Otherwise it builds a new one (progress reported through the given algorithm's
 * UpdateProgress), caches it on the image and returns it. So a mapper and a filter over
 * one image build the tables once, and a second mapper rendering the same image in
 * another window builds nothing.
 *
 * The error tables are the one pass over every sample a terrain needs before its first
 * frame (seconds at 16385^2). With a table cache (TableCacheOptions(), on by default) they
 * are saved to a file keyed by the heights' content hash and the block size, and read back
 * by the next open of the same DEM, in this process or another; a file that fails any
 * check (corrupt, stale, other version) is rebuilt and replaced, never trusted.
 *
 * Float heights are shared with the image's array (no second copy of a large DEM) when
 * they are one component with nothing to sanitise; other types are converted to a float
 * copy for the engine (the mapper still uploads 16-bit heights as they are).
 *
 * Not wrapped: it exposes gmm:: types. Listed as a NOWRAP header of geomipmap::Filters.
 */
#ifndef vtkGeoMipMapTerrain_h
#define vtkGeoMipMapTerrain_h

#include "geomipmapFiltersModule.h" // For export macro
#include "vtkObject.h"

#include "Frame.h"   // gmm::FrameDriver
#include "Terrain.h" // gmm::Terrain
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <memory> // For std::shared_ptr
#include <string> // For std::string

class vtkAlgorithm;
class vtkDataArray;
class vtkImageData;
class vtkInformationObjectBaseKey;

class GEOMIPMAPFILTERS_EXPORT vtkGeoMipMapTerrain : public vtkObject
{
public:
  static vtkGeoMipMapTerrain* New();
  vtkTypeMacro(vtkGeoMipMapTerrain, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The terrain of `image` (heights: its active point scalars, component 0) at
   * `blockSize`: cached or built now. `progress` (may be null) receives UpdateProgress
   * during a build. Returns null and sets `error` when the image or block size cannot be
   * used.
   */
  static vtkGeoMipMapTerrain* Get(vtkImageData* image, int blockSize, vtkAlgorithm* progress,
    std::string& error, const gmm::TableCacheOptions& cache = gmm::TableCacheOptions());

  /**
   * Get() for a consumer that holds its terrain in `current` and draws it with `driver`
   * (the mapper, the filter): a new terrain replaces both, and `changed` says so; on failure
   * both are forgotten and `self` reports the error. Returns the terrain, or null.
   */
  static vtkGeoMipMapTerrain* Bind(vtkImageData* image, int blockSize, vtkAlgorithm* self,
    const gmm::TableCacheOptions& cache, vtkSmartPointer<vtkGeoMipMapTerrain>& current,
    gmm::FrameDriver& driver, bool& changed);

  /**
   * The table cache settings for a consumer: off when `enabled` is false, else in
   * `directory`, or when that is null or empty in DefaultTableCacheDirectory().
   */
  static gmm::TableCacheOptions TableCacheOptions(bool enabled, const char* directory);

  /**
   * The default cache location, the one rule: $GEOMIPMAP_CACHE_DIR when set (set to ""
   * or "off" it turns the cache off), else $XDG_CACHE_HOME/geomipmap, else
   * $HOME/.cache/geomipmap; "" (off) when none is set.
   */
  static std::string DefaultTableCacheDirectory();

  /**
   * What the table cache did when this terrain was built: whether the tables were read
   * from a file, saved to one, and why a file was not used or not written.
   */
  const gmm::TableCacheReport& GetTableCacheReport() const { return this->CacheReport; }

  /**
   * Key of the cache in the image's information.
   */
  static vtkInformationObjectBaseKey* TERRAIN();

  const std::shared_ptr<const gmm::Terrain>& GetTerrain() const { return this->Terrain; }
  vtkDataArray* GetHeights() const;

  ///@{
  /**
   * Wall time of the build (conversion, quadtree, error tables), in seconds.
   */
  vtkGetMacro(BuildTime, double);
  ///@}

  /**
   * Bytes the terrain holds beyond the image: the quadtree, the error tables, and the
   * heights when they could not be shared.
   */
  size_t GetMemoryBytes() const;

protected:
  vtkGeoMipMapTerrain();
  ~vtkGeoMipMapTerrain() override;

private:
  vtkGeoMipMapTerrain(const vtkGeoMipMapTerrain&) = delete;
  void operator=(const vtkGeoMipMapTerrain&) = delete;

  bool IsCurrentFor(vtkImageData* image, vtkDataArray* heights, int blockSize) const;

  std::shared_ptr<const gmm::Terrain> Terrain;
  struct Signature;
  std::unique_ptr<Signature> Built;
  double BuildTime = 0.0;
  gmm::TableCacheReport CacheReport;
};

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapTerrain.h
