# The command-line tools (geomipmap-fly, geomipmap-bench, geomipmap-view) and their one Python package,
# geomipmap_apps (Plugin/Python/geomipmap_apps): shared terrain loading, scene set-up,
# errors and command-line handling at its top level, one subpackage per tool; the camera
# paths are the geomipmap package's (geomipmap.flight, CMake/geomipmapVTK.cmake). A tool is a subpackage with a cli.main
# and a launcher configured from geomipmap-app.in. Included at the end of
# CMake/geomipmapVTK.cmake (needs GEOMIPMAP_PYTHON_DESTINATION and
# GEOMIPMAP_PYTHON_PACKAGE_PARENT from there). Tests: Testing/Python, Testing/Benchmarks.
set(_apps_dir "${CMAKE_CURRENT_LIST_DIR}")
geomipmap_add_python_files(
  geomipmap_apps/__init__.py
  geomipmap_apps/command.py
  geomipmap_apps/errors.py
  geomipmap_apps/hugeheap.py
  geomipmap_apps/scene.py
  geomipmap_apps/terrain.py
  geomipmap_apps/video.py
  geomipmap_apps/fly/__init__.py
  geomipmap_apps/fly/__main__.py
  geomipmap_apps/fly/cli.py
  geomipmap_apps/fly/report.py
  geomipmap_apps/bench/__init__.py
  geomipmap_apps/bench/__main__.py
  geomipmap_apps/bench/cli.py
  geomipmap_apps/bench/measure.py
  geomipmap_apps/bench/meshes.py
  geomipmap_apps/bench/report.py
  geomipmap_apps/bench/run.py
  geomipmap_apps/view/__init__.py
  geomipmap_apps/view/__main__.py
  geomipmap_apps/view/cli.py
  geomipmap_apps/view/motion_rate.py
  geomipmap_apps/view/progress.py
  geomipmap_apps/view/viewer.py)
# Build trees configured before the tools shared one package hold the old top-level
# packages; a stale copy would let an import of them pass in the tests.
file(REMOVE_RECURSE "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_fly"
  "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_bench")

# The launchers find the packages relative to themselves: same relative path in both trees.
file(RELATIVE_PATH GEOMIPMAP_APPS_PYTHON_DIR "/prefix/${CMAKE_INSTALL_BINDIR}"
  "/prefix/${GEOMIPMAP_PYTHON_DESTINATION}")
foreach(_app IN ITEMS fly bench view)
  string(TOUPPER "${_app}" _APP)
  set(GEOMIPMAP_APP "${_app}")
  set(GEOMIPMAP_${_APP}_EXECUTABLE "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR}/geomipmap-${_app}"
    CACHE INTERNAL "Build-tree geomipmap-${_app} command")
  configure_file("${_apps_dir}/geomipmap-app.in" "${GEOMIPMAP_${_APP}_EXECUTABLE}" @ONLY
    FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                     WORLD_READ WORLD_EXECUTE)
  install(PROGRAMS "${GEOMIPMAP_${_APP}_EXECUTABLE}" DESTINATION "${CMAKE_INSTALL_BINDIR}"
    COMPONENT python)
endforeach()
