/**
 * @file   vtkGeoMipMapSoftwareRenderer.h
 * @brief  What vtkGeoMipMapMapper does differently when OpenGL runs on the CPU.
 *
 * A software OpenGL (Mesa's llvmpipe or softpipe) keeps its "GPU" buffers in this process's
 * memory and shades vertices on the calling thread. Two consequences for the mapper:
 * - heights can be shared with the renderer instead of copied (vtkGeoMipMapSharedHeights);
 * - the renderer's per-draw work buffers come from the C heap, and glibc's default heap
 *   policy hands them back to the system and takes them again, page by page, frame after
 *   frame. RetainHeap stops that (see its comment).
 * Not wrapped, not installed: private to geomipmap::Rendering.
 */
#ifndef vtkGeoMipMapSoftwareRenderer_h
#define vtkGeoMipMapSoftwareRenderer_h

#include <cstddef> // For std::size_t

namespace vtkGeoMipMapSoftwareRenderer
{
/// Whether the current OpenGL context renders on the CPU (llvmpipe, softpipe).
bool IsCurrent();

/// The heap policy RetainHeap sets: allocations below kMmapThreshold come from the heap,
/// and up to kTrimThreshold of free memory stays at its top. These are the values glibc's
/// own adaptive policy reaches after it has freed a 32 MiB mapped block (its largest).
constexpr std::size_t kMmapThreshold = std::size_t(32) << 20;
constexpr std::size_t kTrimThreshold = std::size_t(64) << 20;

/**
 * Once per process, sets glibc's malloc policy to kMmapThreshold and kTrimThreshold
 * (mallopt). Why: llvmpipe allocates and frees its vertex work buffers for every draw. With
 * glibc's initial policy the heap's top is returned to the system after each frame and
 * touched again in the next, one page fault per page; on the benchmark VM that took half
 * of a 100 ms frame (about 4000 faults), until a large enough free raised glibc's
 * thresholds, which in a flight whose triangle count grows slowly took 40 frames or never
 * came. Cost: up to kTrimThreshold of freed memory stays mapped. Returns false where the C
 * library has no mallopt (not glibc) or refuses it (ASan's allocator answers 0): the heap
 * is then left as it is.
 */
bool RetainHeap();
}

#endif
// VTK-HeaderTest-Exclude: vtkGeoMipMapSoftwareRenderer.h
