# geomipmap-bench: frame time against measured screen-space error, ours versus VTK's
# alternatives (package geomipmap_bench, Plugin/Python). Included from
# CMake/geomipmapVTK.cmake after geomipmapFly.cmake (uses GEOMIPMAP_FLY_PYTHON_DIR and the
# geomipmap_fly package, which it reuses for terrain loading, flight paths and the scene).
set(_bench_dir "${CMAKE_CURRENT_LIST_DIR}")
set(_bench_sources __init__.py __main__.py cli.py measure.py meshes.py report.py run.py)

set(GEOMIPMAP_BENCH_EXECUTABLE "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR}/geomipmap-bench"
  CACHE INTERNAL "Build-tree geomipmap-bench command")
configure_file("${_bench_dir}/geomipmap-bench.in" "${GEOMIPMAP_BENCH_EXECUTABLE}" @ONLY
  FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                   WORLD_READ WORLD_EXECUTE)
install(PROGRAMS "${GEOMIPMAP_BENCH_EXECUTABLE}" DESTINATION "${CMAKE_INSTALL_BINDIR}"
  COMPONENT python)
foreach(_f IN LISTS _bench_sources)
  configure_file("${_bench_dir}/geomipmap_bench/${_f}"
    "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_bench/${_f}" COPYONLY)
  install(FILES "${GEOMIPMAP_PYTHON_PACKAGE_PARENT}/geomipmap_bench/${_f}"
    DESTINATION "${GEOMIPMAP_PYTHON_DESTINATION}/geomipmap_bench" COMPONENT python)
endforeach()

# Tests: the quick mode as a smoke test of the harness and its error measure, and the
# error measure against a hand-computed case (CI runs ctest under xvfb-run).
if(GEOMIPMAP_BUILD_TESTING)
  set(_bench_tests "${CMAKE_SOURCE_DIR}/Testing/Benchmarks")
  file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Benchmarks")
  add_test(NAME geomipmapPython.TestBenchQuick
    COMMAND /usr/bin/python3 "${_bench_tests}/TestBenchQuick.py" "${GEOMIPMAP_BENCH_EXECUTABLE}"
            "${CMAKE_BINARY_DIR}/Testing/Benchmarks/TestBenchQuick"
    WORKING_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Benchmarks")
  add_test(NAME geomipmapPython.TestScreenError
    COMMAND /usr/bin/python3 "${_bench_tests}/TestScreenError.py"
    WORKING_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Benchmarks")
  set_tests_properties(geomipmapPython.TestBenchQuick geomipmapPython.TestScreenError
    PROPERTIES
      SKIP_RETURN_CODE 77
      TIMEOUT 300
      LABELS "python;bench"
      ENVIRONMENT "PYTHONPATH=${GEOMIPMAP_PYTHON_PACKAGE_PARENT}")
endif()
