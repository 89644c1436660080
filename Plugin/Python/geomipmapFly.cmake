# geomipmap-fly: a Python command (package geomipmap_fly) next to the geomipmap package.
# Included at the end of CMake/geomipmapVTK.cmake (needs GEOMIPMAP_PYTHON_DESTINATION and
# GEOMIPMAP_PYTHON_PACKAGE_PARENT from there). Build tree: <build>/bin/geomipmap-fly and
# <build>/<python destination>/geomipmap_fly; install: the same layout under the prefix.
set(_fly_dir "${CMAKE_CURRENT_LIST_DIR}")
set(_fly_sources __init__.py __main__.py cli.py errors.py paths.py report.py scene.py terrain.py)

# The launcher finds the packages relative to itself: same relative path in both trees.
file(RELATIVE_PATH GEOMIPMAP_FLY_PYTHON_DIR "/prefix/${CMAKE_INSTALL_BINDIR}"
  "/prefix/${GEOMIPMAP_PYTHON_DESTINATION}")
set(GEOMIPMAP_FLY_EXECUTABLE "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR}/geomipmap-fly"
  CACHE INTERNAL "Build-tree geomipmap-fly command")
configure_file("${_fly_dir}/geomipmap-fly.in" "${GEOMIPMAP_FLY_EXECUTABLE}" @ONLY
  FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                   WORLD_READ WORLD_EXECUTE)
install(PROGRAMS "${GEOMIPMAP_FLY_EXECUTABLE}" DESTINATION "${CMAKE_INSTALL_BINDIR}"
  COMPONENT python)

foreach(_f IN LISTS _fly_sources)
  # COPYONLY re-copies on the next build when a source changes (CMake re-runs).
  configure_file("${_fly_dir}/geomipmap_fly/${_f}"
    "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_fly/${_f}" COPYONLY)
  install(FILES "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_fly/${_f}"
    DESTINATION "${GEOMIPMAP_PYTHON_DESTINATION}/geomipmap_fly" COMPONENT python)
endforeach()

# Tests (plain CTest, /usr/bin/python3; CI runs ctest under xvfb-run).
if(GEOMIPMAP_BUILD_TESTING)
  set(_fly_tests "${CMAKE_SOURCE_DIR}/Testing/Python")
  # Real data: GEOMIPMAP_DATA_DIR (top-level CMakeLists.txt, Testing/Python/gmmdata.py).
  set(_fly_env "PYTHONPATH=${GEOMIPMAP_PYTHON_PACKAGE_PARENT}" ${GEOMIPMAP_TEST_DATA_ENV})
  file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Python")
  foreach(_t IN ITEMS TestFlySynthetic TestFlyRealDEM TestFlyBadInput)
    add_test(NAME geomipmapPython.${_t}
      COMMAND /usr/bin/python3 "${_fly_tests}/${_t}.py" "${GEOMIPMAP_FLY_EXECUTABLE}"
              "${CMAKE_BINARY_DIR}/Testing/Python/${_t}"
      WORKING_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Python")
    set_tests_properties(geomipmapPython.${_t} PROPERTIES
      SKIP_RETURN_CODE 77
      TIMEOUT 300
      LABELS "python;fly"
      ENVIRONMENT "${_fly_env}")
  endforeach()
  # Waypoint parsing in-process (no command, no rendering): every case file, then seeded
  # mutation fuzzing (15000 inputs, a few seconds).
  foreach(_t IN ITEMS TestFlyWaypointFiles TestFlyWaypointFuzz)
    add_test(NAME geomipmapPython.${_t}
      COMMAND /usr/bin/python3 "${_fly_tests}/${_t}.py" "${CMAKE_BINARY_DIR}/Testing/Python/${_t}"
      WORKING_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Python")
    set_tests_properties(geomipmapPython.${_t} PROPERTIES
      TIMEOUT 120
      LABELS "python;fly"
      ENVIRONMENT "PYTHONPATH=${GEOMIPMAP_PYTHON_PACKAGE_PARENT}")
  endforeach()
endif()
