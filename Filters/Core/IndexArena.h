// IndexArena: every drawn block's triangles in a slot of its own inside one index list, so
// that a frame rewrites only the slots of blocks whose triangles changed, and a renderer
// that mirrors the list (an OpenGL index buffer) uploads only those ranges.
//
// Slot space a block does not use holds kRestartIndex, the fixed primitive-restart index of
// 32-bit indices: with GL_PRIMITIVE_RESTART_FIXED_INDEX enabled, the whole list can be
// drawn with one glDrawElements and the unused space draws nothing. A block whose
// triangles outgrow its slot moves to a free slot or to the end; when more than half of
// the list is unused it is compacted, which rewrites it whole.
//
//   arena.reset(blocks);
//   arena.beginFrame();  arena.assign(b, tris, n) for each changed block;  arena.endFrame();
//   if (arena.rewritten()) upload(arena.indices()); else for (r : arena.dirtyRanges()) ...
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace gmm
{

constexpr uint32_t kRestartIndex = 0xFFFFFFFFu;

class IndexArena
{
public:
  struct Range
  {
    std::size_t begin, end; // indices [begin, end) of indices()
  };

  // Empties every slot of `blocks` blocks; the next frame rewrites the list.
  void reset(int blocks);
  void beginFrame();
  // Block `block`'s triangles become tris[0 .. count) (3 indices each; count 0 = not drawn).
  void assign(int block, const uint32_t* tris, std::size_t count);
  // Compacts a sparse list and merges this frame's dirty ranges.
  void endFrame();

  // The list: every slot, unused space = kRestartIndex. Its size only changes on a rewrite.
  const std::vector<uint32_t>& indices() const { return indices_; }
  // True when the whole list changed this frame (first frame, growth, compaction).
  bool rewritten() const { return rewritten_; }
  // Frames that changed the list so far: a mirror that missed one (version not its own
  // + 1) must copy the whole list, the ranges only describe the last change.
  uint64_t version() const { return version_; }
  // Otherwise the ranges that changed, sorted and disjoint.
  const std::vector<Range>& dirtyRanges() const { return dirty_; }
  // Indices' worth of memory held: the list's and the spare the next compaction packs into.
  std::size_t heldIndices() const { return indices_.capacity() + spare_.capacity(); }
  // Where block `block`'s triangles are in indices(): [begin, end), empty when not drawn.
  // What a renderer draws to order blocks (glMultiDrawElements) without re-uploading.
  Range slot(int block) const
  {
    const Slot& s = slots_[static_cast<std::size_t>(block)];
    return Range{ s.offset, s.offset + s.count };
  }
  // Indices of drawn triangles (3 per triangle), without unused space.
  std::size_t liveIndices() const { return live_; }
  // The triangles of the listed slots, in the list's order, appended to `out`. The caller
  // lists the slots it drew (Engine: its drawn blocks and merged nodes), so that this costs
  // what is drawn, not the slot count (a 16385^2 DEM at block 32 has 600 000 slots).
  void appendTriangles(const std::vector<int>& slots, std::vector<uint32_t>& out) const;

private:
  struct Slot
  {
    std::size_t offset = 0, capacity = 0, count = 0;
  };
  std::size_t allocate(std::size_t capacity);
  void release(Slot& s);
  void markDirty(std::size_t begin, std::size_t end);
  void compact();

  std::vector<uint32_t> indices_;
  std::vector<uint32_t> spare_; // the list before the last compaction (its capacity reused)
  std::vector<Slot> slots_;
  std::multimap<std::size_t, std::size_t> free_; // capacity -> offset of unused slots
  std::size_t end_ = 0;   // first index after the last slot (the rest is reserve)
  std::size_t live_ = 0;
  bool rewritten_ = true;
  bool pendingRewrite_ = true; // set by reset: the next frame is a rewrite
  uint64_t version_ = 0;
  std::vector<Range> dirty_;
};

} // namespace gmm
