// The engine fuzzer's checks after every frame (used by FuzzEngine.cpp). They are compiled
// without libFuzzer's coverage and comparison tracing (Testing/Fuzz/CMakeLists.txt), still
// with ASan and UBSan: they sort and scan every triangle, and tracing that work cost more
// than the engine itself (measured: 61 % of the target's time, 43 % in comparison tracing
// alone) while guiding nothing; the engine's own coverage is the fuzzer's feedback.
#pragma once

#include "Engine.h"

#include <string>

namespace gmmfuzz
{

// Prints what failed, with the heightfield's size, spacing and block size, and aborts
// (libFuzzer reports it as a crash and keeps the input).
[[noreturn]] void violation(const std::string& what, const gmm::Heightfield& hf, int maxQ);

// The frame e just made: stats match the index count, every index < nx*ny and on a finite
// sample, CoreTestUtil.h's checkMesh (no zero-area or duplicate triangle, no directed edge
// twice, borders only where the drawn region ends, no T-junction, counter-clockwise, exact
// area without nodata), and, with compareFresh, the cached triangles equal a fresh
// tessellate() of the same levels. Linear in the mesh up to the sorts (n log n).
void checkFrame(const gmm::Engine& e, bool hasNodata, int maxQ, bool compareFresh);

} // namespace gmmfuzz
