// VTK-HeaderTest-Exclude: vtkGeoMipMapSoftwareRenderer.cxx
#include "vtkGeoMipMapSoftwareRenderer.h"

#include "vtk_glew.h"

#include <cstring>
#include <mutex>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

bool vtkGeoMipMapSoftwareRenderer::IsCurrent()
{
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
}

bool vtkGeoMipMapSoftwareRenderer::RetainHeap()
{
#if defined(__GLIBC__)
  static std::once_flag once;
  static bool set = false;
  std::call_once(once, [] {
    // Both values: setting either parameter ends glibc's adaptation of both.
    set = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kTrimThreshold)) == 1 &&
      mallopt(M_MMAP_THRESHOLD, static_cast<int>(kMmapThreshold)) == 1;
  });
  return set;
#else
  return false;
#endif
}
