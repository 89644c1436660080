// Front-to-back drawing order of the selected blocks (NDL's sorted generation): blocks
// nearer the eye are drawn first, so that the depth test rejects the fragments of what they
// hide before those are shaded.
#pragma once

#include "Quadtree.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace gmm
{

// Sorts `blocks` by the distance from `eye` (world) to each block's box, measured in the
// quadtree's frame with each axis weighted by the length of toWorld's column for it
// (heightfieldToWorld: spacing, height scale, actor scale); a shear is ignored, which can
// only swap the order of nearly equidistant blocks. Ties keep block order. An ordering
// heuristic, as every front-to-back sort of overlapping boxes is: nothing depends on it
// but how many fragments the depth test rejects early.
void frontToBack(const Quadtree& qt, const glm::dmat4& toWorld, const glm::dvec3& eye,
  const std::vector<int>& blocks, std::vector<int>& order);

} // namespace gmm
