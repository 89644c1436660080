#include "Culling.h"

#include <glm/geometric.hpp>

namespace gmm
{

namespace
{

void markSubtree(const Quadtree& qt, int node, std::vector<uint8_t>& visible, std::vector<int>& list)
{
  const QuadtreeNode& n = qt.nodes[node];
  if (n.allNodata)
  {
    return;
  }
  if (n.childCount == 0)
  {
    visible[n.block] = 1;
    list.push_back(n.block);
    return;
  }
  for (int k = 0; k < n.childCount; ++k)
  {
    markSubtree(qt, n.firstChild + k, visible, list);
  }
}

} // namespace

Overlap boxVsFrustum(const Box& box, const Frustum& fr)
{
  bool inside = true;
  for (const glm::dvec4& p : fr)
  {
    // p-vertex: the box corner furthest along the plane normal; n-vertex: the nearest.
    const glm::dvec3 pv(p.x >= 0 ? box.hi.x : box.lo.x, p.y >= 0 ? box.hi.y : box.lo.y,
      p.z >= 0 ? box.hi.z : box.lo.z);
    const glm::dvec3 nv(p.x >= 0 ? box.lo.x : box.hi.x, p.y >= 0 ? box.lo.y : box.hi.y,
      p.z >= 0 ? box.lo.z : box.hi.z);
    if (glm::dot(glm::dvec3(p), pv) + p.w < 0)
    {
      return Overlap::Outside;
    }
    if (glm::dot(glm::dvec3(p), nv) + p.w < 0)
    {
      inside = false;
    }
  }
  return inside ? Overlap::Inside : Overlap::Partial;
}

int cullBlocks(const Quadtree& qt, const Frustum& frustum, std::vector<uint8_t>& visible,
  std::vector<int>& list)
{
  visible.assign(qt.blockCount(), 0);
  list.clear();
  if (!qt.nodes.empty())
  {
    // Fully inside: no more plane tests below.
    forNodesInFrustum(qt, 0, frustum, [&](int node) { markSubtree(qt, node, visible, list); });
  }
  return static_cast<int>(list.size());
}

} // namespace gmm
