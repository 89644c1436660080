# VTK modules (geomipmap::Filters, geomipmap::Rendering) and their Python package.
# Included from the top-level CMakeLists.txt when GEOMIPMAP_WITH_VTK is ON.
# Debian 12 pitfalls this file works around: ../shared/notes/vtk-9.1-on-debian.md.

include(GNUInstallDirs)

# The interpreter first on PATH may lack vtkmodules (see notes): default to Debian's python3,
# which VTK's Python component and the wrapping then use. Override with -DPython3_EXECUTABLE.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter with vtkmodules")
endif()

find_package(VTK 9.1 REQUIRED COMPONENTS
  CommonCore
  CommonDataModel
  CommonExecutionModel
  CommonMath
  CommonMisc
  IOImage
  IOGeometry
  FiltersCore
  FiltersGeometry
  RenderingCore
  RenderingOpenGL2
  RenderingFreeType
  InteractionStyle
  TestingRendering
  WrappingPythonCore
  Python
)
find_package(GDAL CONFIG REQUIRED)
# Debian 12's OpenImageIOConfig.cmake (and ImathConfig) reference tool executables that
# the -dev package does not install and stop with a fatal error, so find the library by hand.
find_path(GEOMIPMAP_OIIO_INCLUDE_DIR OpenImageIO/imageio.h REQUIRED)
find_path(GEOMIPMAP_IMATH_INCLUDE_DIR Imath/half.h)
find_library(GEOMIPMAP_OIIO_LIBRARY OpenImageIO REQUIRED)
find_library(GEOMIPMAP_OIIO_UTIL_LIBRARY OpenImageIO_Util REQUIRED)
if(NOT TARGET geomipmap_OpenImageIO)
  add_library(geomipmap_OpenImageIO INTERFACE IMPORTED)
  set_target_properties(geomipmap_OpenImageIO PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GEOMIPMAP_OIIO_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${GEOMIPMAP_OIIO_LIBRARY};${GEOMIPMAP_OIIO_UTIL_LIBRARY}")
  if(GEOMIPMAP_IMATH_INCLUDE_DIR)
    set_property(TARGET geomipmap_OpenImageIO APPEND PROPERTY
      INTERFACE_INCLUDE_DIRECTORIES "${GEOMIPMAP_IMATH_INCLUDE_DIR}/Imath")
  endif()
endif()
# Debian ships FindGeographicLib.cmake outside CMake's own module path.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
find_package(Python3 3.9 REQUIRED COMPONENTS Interpreter Development.Module)

vtk_module_scan(
  MODULE_FILES
    "${CMAKE_CURRENT_SOURCE_DIR}/Filters/vtk.module"
    "${CMAKE_CURRENT_SOURCE_DIR}/Plugin/vtk.module"
  REQUEST_MODULES geomipmap::Filters geomipmap::Rendering
  PROVIDES_MODULES geomipmap_modules
  ENABLE_TESTS OFF # tests live in the top-level Testing/ folder (plain CTest)
)

# Shared modules: the Python extension modules link them, and the engine (static, PIC)
# is linked into each. Restored below so other targets keep CMake's default.
set(_geomipmap_shared "${BUILD_SHARED_LIBS}")
set(BUILD_SHARED_LIBS ON)

# Debian's VTK exports absolute destinations; vtk_module_build rejects them, so every
# destination is given relative to the prefix.
vtk_module_build(
  MODULES ${geomipmap_modules}
  PACKAGE geomipmap
  INSTALL_EXPORT geomipmap
  ENABLE_WRAPPING ON # hierarchy files, needed by the Python wrapping
  ARCHIVE_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  RUNTIME_DESTINATION "${CMAKE_INSTALL_BINDIR}"
  HEADERS_DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/geomipmap"
  CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/geomipmap"
  LICENSE_DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/licenses/geomipmap"
  HIERARCHY_DESTINATION "${CMAKE_INSTALL_LIBDIR}/vtk/hierarchy/geomipmap"
  VERSION "${PROJECT_VERSION}"
  SOVERSION "0"
)

# geomipmapRendering finds geomipmapFilters next to it once installed, even outside the
# loader's default paths (e.g. a /tmp prefix, or /usr/local/lib before ldconfig ran).
foreach(_gmm_module IN LISTS geomipmap_modules)
  vtk_module_set_properties(${_gmm_module} INSTALL_RPATH "$ORIGIN")
endforeach()

# Python package destination, relative to the prefix. Debian's python3 puts
# <prefix>/lib/python3.X/dist-packages on sys.path for the /usr/local prefix (and for /usr);
# Debian's patched VTK default (lib/python3/dist-packages) is not on it under /usr/local.
set(GEOMIPMAP_PYTHON_DESTINATION
  "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages"
  CACHE STRING "Install destination of the geomipmap Python package, relative to the prefix")

vtk_module_wrap_python(
  MODULES ${geomipmap_modules}
  TARGET geomipmap::Python
  PYTHON_PACKAGE geomipmap
  MODULE_DESTINATION "${GEOMIPMAP_PYTHON_DESTINATION}"
  CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/geomipmap"
  # Gives the extension modules an $ORIGIN-relative RPATH to the installed libraries.
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  INSTALL_EXPORT geomipmapPython
  BUILD_STATIC OFF
  INSTALL_HEADERS OFF
)

set(BUILD_SHARED_LIBS "${_geomipmap_shared}")

# Package __init__: re-exports every class of both modules, so both
#   import geomipmap; geomipmap.vtkGeoMipMapTerrainReader
#   from geomipmap.geomipmapFilters import vtkGeoMipMapTerrainReader
# work. The wrapped modules import their VTK dependencies themselves.
set(GEOMIPMAP_PYTHON_PACKAGE_PARENT "${CMAKE_BINARY_DIR}/${GEOMIPMAP_PYTHON_DESTINATION}"
  CACHE INTERNAL "Build-tree folder holding the geomipmap Python package: put it on PYTHONPATH")
configure_file("${CMAKE_CURRENT_LIST_DIR}/geomipmap__init__.py.in"
  "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap/__init__.py" COPYONLY)
install(FILES "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap/__init__.py"
  DESTINATION "${GEOMIPMAP_PYTHON_DESTINATION}/geomipmap" COMPONENT python)
# Tests (Testing/Python) run: PYTHONPATH=${GEOMIPMAP_PYTHON_PACKAGE_PARENT} /usr/bin/python3 ...

# Pure-Python files, given relative to Plugin/Python: copied into the build tree's package
# folder (COPYONLY: re-copied on the next build when a source changes, as CMake re-runs)
# and installed with the same layout under the prefix.
function(geomipmap_add_python_files)
  foreach(_f IN LISTS ARGN)
    configure_file("${PROJECT_SOURCE_DIR}/Plugin/Python/${_f}"
      "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/${_f}" COPYONLY)
    get_filename_component(_sub "${_f}" DIRECTORY)
    install(FILES "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/${_f}"
      DESTINATION "${GEOMIPMAP_PYTHON_DESTINATION}/${_sub}" COMPONENT python)
  endforeach()
endfunction()

# geomipmap.flight: camera paths for any vtkCamera (pure Python, part of the package).
geomipmap_add_python_files(
  geomipmap/flight/__init__.py
  geomipmap/flight/heights.py
  geomipmap/flight/paths.py
  geomipmap/flight/waypoints.py)

# The geomipmap-fly and geomipmap-bench commands and their package geomipmap_apps.
include("${CMAKE_CURRENT_LIST_DIR}/../Plugin/Python/geomipmapApps.cmake")
