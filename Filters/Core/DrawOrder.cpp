#include "DrawOrder.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <utility>

namespace gmm
{

void frontToBack(const Quadtree& qt, const glm::dmat4& toWorld, const glm::dvec3& eye,
  const std::vector<int>& blocks, const std::vector<int>& mergedNodes, std::vector<int>& order)
{
  const glm::dvec3 local(glm::inverse(toWorld) * glm::dvec4(eye, 1.0));
  const glm::dvec3 weight(glm::length(glm::dvec3(toWorld[0])), glm::length(glm::dvec3(toWorld[1])),
    glm::length(glm::dvec3(toWorld[2])));
  std::vector<std::pair<double, int>> keyed;
  keyed.reserve(blocks.size() + mergedNodes.size());
  auto key = [&](const Box& box, int slot) {
    const glm::dvec3 nearest = glm::clamp(local, box.lo, box.hi);
    const glm::dvec3 d = (local - nearest) * weight;
    keyed.emplace_back(glm::dot(d, d), slot);
  };
  for (int b : blocks)
  {
    key(qt.blockBox[b], b);
  }
  for (int n : mergedNodes)
  {
    key(qt.nodes[n].box, qt.blockCount() + n);
  }
  std::stable_sort(keyed.begin(), keyed.end(),
    [](const std::pair<double, int>& a, const std::pair<double, int>& b) { return a.first < b.first; });
  order.clear();
  for (const auto& k : keyed)
  {
    order.push_back(k.second);
  }
}

} // namespace gmm
