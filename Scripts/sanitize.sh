#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer (GCC, the
# compiler Debian's VTK is built with) into ${GEOMIPMAP_ASAN_BUILD_DIR:-build-asan} and runs
# the whole ctest there (under xvfb-run when there is no DISPLAY). Extra arguments go to ctest.
# Leak detection is on for our C++ test programs; see Documentation/robustness.md for every
# runtime option and suppression used below and why.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_ASAN_BUILD_DIR:-$here/build-asan}

# Packages: setup.sh's list (no build there: GEOMIPMAP_SETUP_ONLY).
GEOMIPMAP_SETUP_ONLY=1 bash "$here/Scripts/setup.sh"

# -O1: ASan's recommended level (fast enough, stacks still exact); -g1: line tables only.
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" \
  -DPython3_EXECUTABLE=/usr/bin/python3 -DGEOMIPMAP_SANITIZE=ON \
  -DGEOMIPMAP_BUILD_BENCHMARKS=OFF -DGEOMIPMAP_BUILD_FUZZERS=OFF \
  -DGEOMIPMAP_TEST_XVFB=OFF >/dev/null # one X server for the run (below), not one per test
cmake --build "$build" -j"$(nproc)"
keep="$build/libgeomipmap_keep_loaded.so"
gcc -shared -fPIC -O1 -o "$keep" "$here/Testing/Sanitizers/keep_loaded.c"

asan_rt=$(gcc -print-file-name=libasan.so)
# python3 does not link libstdc++: preloaded too, or ASan's __cxa_throw interceptor finds no
# real __cxa_throw at start-up and the first C++ exception (GDAL, PROJ) aborts the process.
stdcxx=$(g++ -print-file-name=libstdc++.so.6)
supp="$here/Testing/Sanitizers"
# Shared by every process: UBSan stops at the first error with a stack; ASan reports go to
# stderr (ctest --output-on-failure shows them); LSan uses the Mesa/X suppressions.
common_asan="abort_on_error=0:halt_on_error=1:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="$common_asan:detect_leaks=1"

source "$here/Scripts/display.sh" # run=(): xvfb-run where there is no display
cd "$build"
status=0
# 1) Everything but the Python tests: instrumented executables, leak detection on. The
#    dlclose() no-op (Testing/Sanitizers/keep_loaded.c) stops false leak reports from Mesa's
#    unloaded driver; the ASan runtime must come first in a preload list.
"${run[@]}" env LD_PRELOAD="$asan_rt $keep" \
  ctest --output-on-failure -j2 -LE python "$@" || status=1
# 2) Python tests: /usr/bin/python3 is not instrumented, so the ASan runtime must be loaded
#    first (LD_PRELOAD) for our wrapped modules to load. Leak detection is off for these
#    processes only: CPython (and VTK's Python wrapping) keep interned objects, module
#    state and caches alive until exit by design, which LSan reports as leaks.
#    ctest runs with the runtime preloaded too (it is not instrumented: that only swaps
#    its allocator); xvfb-run and the X server do not.
#    quarantine_size_mb=16 (default 256): ASan keeps freed blocks in quarantine to catch
#    use-after-free; with the default, TestTerrainReaderMalformed's bound on peak RSS over 32
#    bad files (< 64 MB) measured ASan's quarantine (77.6 MB), not the reader.
"${run[@]}" env LD_PRELOAD="$asan_rt $stdcxx" \
  ASAN_OPTIONS="$common_asan:detect_leaks=0:quarantine_size_mb=16" \
  ctest --output-on-failure -j2 -L python "$@" || status=1
exit $status
