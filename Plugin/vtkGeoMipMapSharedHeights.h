/**
 * @file   vtkGeoMipMapSharedHeights.h
 * @brief  The heights array read in place by a renderer that runs on the CPU.
 *
 * Mesa's llvmpipe keeps "GPU" textures in the process's own memory: a height texture is a
 * second copy of the DEM, and making it costs the copy plus the first touch of every new
 * page (about 3.9 s per GiB on the VM the benchmarks ran on: 4.6 s for the heights of a
 * 16385^2 DEM). With GL_AMD_pinned_memory the driver can use the array's own memory as
 * buffer storage instead: nothing is copied and nothing is allocated.
 *
 * The array is wrapped as buffer textures read by sample index k = j * nx + i, with the
 * formats the texture path stores (float as R32F, 16-bit integers as R16I / R16UI), so the
 * shaders see the same values. One buffer texture holds at most GL_MAX_TEXTURE_BUFFER_SIZE
 * texels (2^27 on llvmpipe). A DEM that fits takes one sample a texel. A larger one takes
 * four (RGBA32F, RGBA16I / RGBA16UI: sample k is component k % 4 of texel k / 4), so that
 * one band holds 2^29 samples (up to 23170^2: a 16385^2 DEM would take 3 bands of one
 * sample a texel); beyond, bands of 2^BandShift() samples, picked in the shaders by a chain
 * of branches, all of which llvmpipe runs. The last samples that fill no texel (up to 3)
 * reach the shaders as uniforms (GetTail): a texel across the array's end could lie on
 * memory that is not the array's. The array is held (reference counted) while it is
 * shared; a change of it (its MTime) or another array shares again.
 *
 * On a GPU that has its own memory this would make every fetch cross the bus: Usable()
 * answers only for renderers that run on the CPU.
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapSharedHeights_h
#define vtkGeoMipMapSharedHeights_h

#include "vtkGeoMipMapTextures.h" // For vtkGeoMipMapSampleTexture::Format
#include "vtkSmartPointer.h"      // For vtkSmartPointer
#include "vtkType.h"              // For vtkMTimeType

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkDataArray;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class vtkGeoMipMapSharedHeights
{
public:
  /** Most bands a DEM may take (tests ask for small bands; 2^31 samples take 4). */
  static constexpr int kMaxBands = 16;
  /** Samples in one texel of a band, for DEMs larger than one band of one a texel. */
  static constexpr int kMaxPerTexel = 4;

  /**
   * True when `win`'s OpenGL runs on the CPU (Mesa llvmpipe or softpipe) and offers
   * GL_AMD_pinned_memory and buffer textures; the window's context must be current.
   */
  static bool Usable(vtkOpenGLRenderWindow* win);

  /** True for the formats read in place: float, 16-bit integers, one component. */
  static bool SharesFormat(vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format);

  vtkGeoMipMapSharedHeights();
  ~vtkGeoMipMapSharedHeights();

  /**
   * Shares `array` (`samples` values in `format`, SharesFormat) in bands of at most
   * `maxBandTexels` texels (0: GL_MAX_TEXTURE_BUFFER_SIZE) and a power of two samples.
   * Returns "" or why it could not (then nothing is held and the caller uploads a texture
   * instead).
   */
  std::string Share(vtkOpenGLRenderWindow* win, vtkDataArray* array,
    vtkGeoMipMapSampleTexture::Format format, vtkIdType samples, vtkIdType maxBandTexels = 0);

  /** True when the last Share had these arguments (and `array` its MTime then) and succeeded. */
  bool IsCurrent(vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format,
    vtkIdType maxBandTexels = 0) const;
  /**
   * True when the last Share had these arguments and failed: trying again would fail
   * again, until a Release (another context may share them).
   */
  bool Failed(vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format,
    vtkIdType maxBandTexels = 0) const;
  bool HasData() const { return !this->Bands.empty(); }
  int GetBands() const { return static_cast<int>(this->Bands.size()); }
  int GetBandShift() const { return this->BandShift; }
  /** 1, or kMaxPerTexel for a DEM larger than one band of one sample a texel. */
  int GetSamplesPerTexel() const { return this->PerTexel; }
  /** The samples from GetTailStart() on (fewer than a texel's), which no texel holds. */
  vtkIdType GetTailStart() const { return this->TailStart; }
  const float* GetTail() const { return this->Tail; }

  /** Binds every band to a free texture unit; `units` gets them, in band order. */
  void Activate(std::vector<int>& units);
  void Deactivate();

  /** Deletes the buffers and textures; `win`'s context must be current. */
  void Release(vtkWindow* win);
  /** Drops the handles without GL calls: their context is gone. */
  void Forget();

private:
  vtkGeoMipMapSharedHeights(const vtkGeoMipMapSharedHeights&) = delete;
  void operator=(const vtkGeoMipMapSharedHeights&) = delete;

  // Share's work; holds nothing when it fails.
  std::string ShareBands(vtkOpenGLRenderWindow* win, vtkDataArray* array,
    vtkGeoMipMapSampleTexture::Format format, vtkIdType samples, vtkIdType maxBandTexels);

  // The arguments of a Share, with the array's MTime then.
  struct Attempt
  {
    const vtkDataArray* Array = nullptr;
    vtkMTimeType Time = 0;
    vtkGeoMipMapSampleTexture::Format Stored = vtkGeoMipMapSampleTexture::Float32;
    vtkIdType MaxBandTexels = 0;
    bool operator==(const Attempt& o) const
    {
      return Array == o.Array && Time == o.Time && Stored == o.Stored && MaxBandTexels == o.MaxBandTexels;
    }
  };
  static Attempt AttemptOf(vtkDataArray* array, vtkGeoMipMapSampleTexture::Format format,
    vtkIdType maxBandTexels);

  struct Band
  {
    unsigned int Buffer = 0;
    unsigned int Texture = 0;
    vtkSmartPointer<vtkTextureObject> Unit; // texture-unit bookkeeping around Texture
  };
  std::vector<Band> Bands;
  int BandShift = 0;
  vtkIdType TailStart = 0;
  int PerTexel = 1;
  float Tail[kMaxPerTexel - 1] = { 0.0f, 0.0f, 0.0f };
  vtkSmartPointer<vtkDataArray> Source; // held while shared: the driver reads its memory
  Attempt Last; // the last Share's arguments, whether it succeeded or not
};

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapSharedHeights.h
