// Vertex ids for drawing: sample (i, j) is drawn as vertex j * pitch + i, with a pitch a
// little above the grid's width chosen so that a software renderer shades each vertex about
// once instead of twice or three times.
//
// Why: Mesa's draw module (llvmpipe, softpipe: every frame of this project's CI and of a
// machine without a GPU) shades an indexed draw in segments of up to 1 023 indices, and
// finds a segment's repeated vertices through a direct-mapped cache of 256 entries keyed by
// id % 256 (draw_pt_vsplit.c). With ids j * nx + i, two vertices collide when
// (dj * nx + di) % 256 == 0. Every 2^k + 1 DEM (513, 1025, 4097, 16385: nx % 256 == 1) and
// every 2^k one make the vertices a quad shares collide: (i + 1, j) and (i, j + 1) with
// nx % 256 == 1, so nearly every triangle corner is shaded again (1.76 vertex shader runs
// a triangle on a 2049^2 view at block 32, against 0.70 with the pitch below; the engine's
// triangles, the cache modelled in TestVertexPitch). A hardware GPU's vertex reuse does not
// key on the id's low bits, so the padding costs it nothing: the ids are only decoded (the
// mapper's vertex shader has no vertex buffer to pad).
#pragma once

#include <cstddef>
#include <cstdint>

namespace gmm
{

// The residue of the drawing pitch modulo 256. Measured with the cache model over every
// residue, blocks of 16, 32 and 64 quads: 93 is among the best for all three (0.70 - 0.72
// vertex shader runs a triangle; the worst residues, 0, 1, 127, 128 and 255, take
// 1.36 - 1.94).
constexpr uint32_t kDrawPitchResidue = 93;

// The pitch sample (i, j) is drawn with, for an nx x ny grid: the least pitch >= nx that is
// kDrawPitchResidue modulo 256, or nx where the last sample's id would then reach the
// primitive-restart index (0xFFFFFFFF; such a grid is within 256 columns of the 32-bit
// limit). nx, ny >= 1.
uint32_t drawPitch(int nx, int ny);

// out[k] = the drawing id of sample index in[k] (j * nx + i, as the engine's indices are):
// j * pitch + i; the primitive-restart index stays as it is. Exact for every sample index
// of the grid (a multiply-high division by nx). `in` and `out` may be the same array.
void toDrawIds(const uint32_t* in, std::size_t count, int nx, uint32_t pitch, uint32_t* out);

} // namespace gmm
