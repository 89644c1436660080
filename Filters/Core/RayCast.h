// Exact queries on the full-resolution surface, independent of any level of detail: the
// height under a point and the first hit of a segment. The surface is the level-0
// triangulation the tessellation draws (the union jack: quad (i, j) split along its
// (i, j)-(i+1, j+1) diagonal where i + j is even, along (i+1, j)-(i, j+1) where it is odd,
// fullResolutionAntiDiagonal in Levels.h; triangles touching nodata are holes), at
// z = z0 + heightScale * h in the heightfield's data frame.
#pragma once

#include "Terrain.h"

#include <glm/vec3.hpp>

namespace gmm
{

// Surface height at (x, y) in the data frame: linear on the level-0 triangle under it.
// NaN outside the grid or over a hole (a triangle with a nodata vertex).
double heightAt(const Heightfield& hf, double x, double y, double heightScale = 1.0);

struct SurfaceHit
{
  bool hit = false;
  double t = 0.0;        // segment parameter in [0, 1] of the first hit
  glm::dvec3 point{ 0.0 }; // data frame
  int cellI = 0, cellJ = 0; // the grid quad hit (samples cellI..cellI+1, cellJ..cellJ+1)
  glm::dvec3 weights{ 0.0 }; // barycentric weights of the hit triangle's vertices
  uint32_t vertex[3] = { 0, 0, 0 }; // its sample indices (j * nx + i)
  glm::dvec3 normal{ 0.0, 0.0, 1.0 }; // unit normal of the hit triangle, data frame, up
};

// First intersection of the segment p0 -> p1 (data frame) with the surface. Walks the
// quadtree boxes front to back (boxes the segment misses are skipped, and a branch is left
// once a hit is nearer than its box), then the grid quads of each leaf along the
// segment's x, y path. Cost: the depth of the tree plus the quads the segment passes over
// inside the boxes it enters.
SurfaceHit intersectSegment(
  const Terrain& terrain, const glm::dvec3& p0, const glm::dvec3& p1, double heightScale = 1.0);

} // namespace gmm
