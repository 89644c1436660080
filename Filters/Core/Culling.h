// Frustum culling of the quadtree's boxes: which blocks a view can see.
#pragma once

#include "Quadtree.h"
#include "View.h"

#include <cstdint>
#include <vector>

namespace gmm
{

enum class Overlap
{
  Outside,
  Partial,
  Inside
};

// Where a box lies against the frustum (conservative: Partial may be outside).
Overlap boxVsFrustum(const Box& box, const Frustum& fr);

// Calls accept(node) for every node with a valid sample (QuadtreeNode::allNodata) whose box
// the frustum meets and that is wholly inside it or a leaf, descending only through the
// nodes its planes cut (boxVsFrustum), from `node` down: the walk of cullBlocks, so that
// its cost follows the frustum's boundary.
template <class Accept>
void forNodesInFrustum(const Quadtree& qt, int node, const Frustum& fr, Accept&& accept)
{
  const QuadtreeNode& n = qt.nodes[node];
  if (n.allNodata)
  {
    return; // draws nothing: as good as out of view
  }
  const Overlap o = boxVsFrustum(n.box, fr);
  if (o == Overlap::Outside)
  {
    return;
  }
  if (o == Overlap::Inside || n.childCount == 0)
  {
    accept(node);
    return;
  }
  for (int k = 0; k < n.childCount; ++k)
  {
    forNodesInFrustum(qt, n.firstChild + k, fr, accept);
  }
}

// Marks blocks with a valid sample whose box intersects the frustum (1) or not (0), and
// lists those visible ones
// (quadtree order), walking the quadtree with early full-inside accept. The frustum is in
// the quadtree's frame (x, y, stored height): transformPlanes(frustumOf(view),
// heightfieldToWorld(...)). Returns the number of visible blocks. The per-frame steps
// below work on the list, so their cost follows what is in view, not the DEM's size.
int cullBlocks(const Quadtree& qt, const Frustum& frustum, std::vector<uint8_t>& visible,
  std::vector<int>& list);

} // namespace gmm
