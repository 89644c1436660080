// Front-to-back drawing order of the selected blocks and merged nodes (NDL's sorted
// generation): what is nearer the eye is drawn first, so that the depth test rejects the fragments of what they
// hide before those are shaded.
#pragma once

#include "Quadtree.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace gmm
{

// Sorts the drawn blocks and merged nodes by the distance from `eye` (world) to each box,
// measured in the quadtree's frame with each axis weighted by the length of toWorld's
// column for it (heightfieldToWorld: spacing, height scale, actor scale); a shear is
// ignored, which can only swap the order of nearly equidistant boxes. `order` receives
// index-arena slots: block b is slot b, merged node n is slot blockCount() + n (Engine).
// Ties keep the input order, blocks first. An ordering heuristic, as every front-to-back
// sort of overlapping boxes is: nothing depends on it but how many fragments the depth
// test rejects early.
void frontToBack(const Quadtree& qt, const glm::dmat4& toWorld, const glm::dvec3& eye,
  const std::vector<int>& blocks, const std::vector<int>& mergedNodes, std::vector<int>& order);

} // namespace gmm
