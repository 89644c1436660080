#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan, GEOMIPMAP_SANITIZE) into
# ${GEOMIPMAP_FUZZ_BUILD_DIR:-build-fuzz} and runs each for FUZZ_SECONDS (default 60) in
# FUZZ_JOBS processes at once (default: one per core), sharing the corpus directory.
# Usage: Scripts/fuzz.sh [target...]   targets: engine reader (default both)
# The growing corpus lives in <build>/corpus/<target> (kept between runs, so long campaigns
# resume); seeds come from Testing/Fuzz/make_corpus.py and Testing/Fuzz/corpus/<target>.
# A crash, leak, timeout or invariant violation fails the script; the reproducer is written
# to <build>/artifacts/<target>/ and the failing log's tail printed. Full logs:
# <build>/logs/<target>/fuzz-<k>.log, one per process.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${GEOMIPMAP_FUZZ_BUILD_DIR:-$here/build-fuzz}
seconds=${FUZZ_SECONDS:-60}
jobs=${FUZZ_JOBS:-$(nproc)}
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(engine reader)

GEOMIPMAP_EXTRA_PACKAGES="clang-14 libclang-rt-14-dev" GEOMIPMAP_SETUP_ONLY=1 \
  bash "$here/Scripts/setup.sh"

# No VTK in this tree: the targets need only the engine, TerrainIO.cxx, GDAL and OIIO.
CC=clang-14 CXX=clang++-14 cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS_RELEASE="-O1 -g -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g -DNDEBUG" \
  -DGEOMIPMAP_WITH_VTK=OFF -DGEOMIPMAP_BUILD_BENCHMARKS=OFF -DGEOMIPMAP_BUILD_FUZZERS=ON \
  -DGEOMIPMAP_SANITIZE=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target geomipmapFuzzEngine geomipmapFuzzTerrainReader

/usr/bin/python3 "$here/Testing/Fuzz/make_corpus.py" "$build/seed"
status=0
for t in "${targets[@]}"; do
  case $t in
    # 16384: grids up to 4096 samples (FuzzEngine.cpp, kBytesPerSample).
    engine) exe=geomipmapFuzzEngine; args=(-max_len=16384) ;;
    # GDAL may take long on some inputs: bounded input size, time per input and memory.
    reader) exe=geomipmapFuzzTerrainReader
      args=(-max_len=65536 -rss_limit_mb=2048 -malloc_limit_mb=1024) ;;
    *) echo "fuzz.sh: unknown target $t (engine, reader)" >&2; exit 2 ;;
  esac
  corpus="$build/corpus/$t" artifacts="$build/artifacts/$t/" logs="$build/logs/$t"
  mkdir -p "$corpus" "$artifacts"
  rm -rf "$logs" && mkdir -p "$logs"
  seeds=("$build/seed/$t")
  [ ! -d "$here/Testing/Fuzz/corpus/$t" ] || seeds+=("$here/Testing/Fuzz/corpus/$t")
  # Leak checks stay on; the reader's suppressions name only OpenImageIO (see the file).
  # Reader: malloc stacks unwound the slow way (libstdc++ and OpenImageIO have no frame
  # pointers), so that the suppression can see the OpenImageIO frame, but only 8 deep: the
  # slow unwinder's cost grows with the depth (robustness.md has the figures). To see
  # full allocation stacks in a report, rerun the reproducer with malloc_context_size=30.
  supp="$here/Testing/Fuzz/lsan-$t.supp"
  lsan="print_suppressions=0"
  [ ! -f "$supp" ] || lsan="suppressions=$supp:$lsan"
  asan="fast_unwind_on_malloc=1"
  [ "$t" != reader ] || asan="fast_unwind_on_malloc=0:malloc_context_size=8"
  echo "fuzz.sh: $t for ${seconds}s in $jobs process(es) (logs: $logs)"
  # -jobs/-workers: independent processes (each writes fuzz-<k>.log in $logs), not -fork,
  # whose short child jobs re-read the corpus each time (half the inputs, measured).
  # -reload=0: no re-reading of the other processes' finds every second.
  if (cd "$logs" && LSAN_OPTIONS="$lsan" ASAN_OPTIONS="$asan" \
    UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
    "$build/Testing/Fuzz/$exe" -jobs="$jobs" -workers="$jobs" -max_total_time="$seconds" \
    -timeout=25 -print_final_stats=1 -reload=0 -artifact_prefix="$artifacts" "${args[@]}" \
    "$corpus" "${seeds[@]}" >main.log 2>&1); then
    grep -h -E '^#[0-9]+.*DONE' "$logs"/fuzz-*.log || true
    total=$(cat "$logs"/fuzz-*.log | sed -n 's/^stat::number_of_executed_units: //p' |
      awk '{ s += $1 } END { print s + 0 }')
    echo "fuzz.sh: $t: $total inputs in ${seconds}s ($jobs processes), no crash; corpus $(find "$corpus" -type f | wc -l) files"
  else
    status=1
    echo "fuzz.sh: $t FAILED; reproducer(s): $(ls "$artifacts")" >&2
    failed=()
    for log in "$logs"/fuzz-*.log; do
      ! grep -q -E 'ERROR: |SUMMARY: |==[0-9]+==' "$log" || failed+=("$log")
    done
    # libFuzzer's own complaint when no process log says more
    [ ${#failed[@]} -gt 0 ] || failed=("$logs"/main.log)
    for log in "${failed[@]}"; do
      echo "--- $log" >&2
      grep -v -E '^(ERROR|Warning) [0-9]+:|Not a TIFF|^libpng ' "$log" | tail -60 >&2
    done
  fi
done
exit $status
