#include "IndexArena.h"

#include "HugePages.h"

#include <algorithm>

namespace gmm
{

namespace
{
// Room for a block's triangles plus a quarter, so that a block that gains a few triangles
// (a neighbour's level change reshapes its strips) stays in its slot.
std::size_t wholeTriangles(std::size_t n) { return (n + 2) / 3 * 3; }

std::size_t slotCapacity(std::size_t count)
{
  return std::max<std::size_t>(6, wholeTriangles(count + count / 4));
}

// Lists smaller than this are never compacted: rewriting them costs less than the bookkeeping.
constexpr std::size_t kCompactMinimum = std::size_t(1) << 16;
// Dirty ranges closer than this (indices) are merged: one upload instead of two small ones.
constexpr std::size_t kMergeGap = 1024;
} // namespace

void IndexArena::reset(int blocks)
{
  indices_.clear();
  spare_.clear();
  slots_.assign(static_cast<std::size_t>(std::max(0, blocks)), Slot());
  free_.clear();
  end_ = 0;
  live_ = 0;
  rewritten_ = true;
  pendingRewrite_ = true;
  dirty_.clear();
}

void IndexArena::beginFrame()
{
  rewritten_ = pendingRewrite_;
  pendingRewrite_ = false;
  dirty_.clear();
}

void IndexArena::markDirty(std::size_t begin, std::size_t end)
{
  if (!rewritten_ && end > begin)
  {
    dirty_.push_back(Range{ begin, end });
  }
}

void IndexArena::release(Slot& s)
{
  if (s.capacity == 0)
  {
    return;
  }
  std::fill(indices_.begin() + s.offset, indices_.begin() + s.offset + s.count, kRestartIndex);
  markDirty(s.offset, s.offset + s.count);
  live_ -= s.count;
  free_.emplace(s.capacity, s.offset);
  s = Slot();
}

std::size_t IndexArena::allocate(std::size_t capacity)
{
  // Best fit among the unused slots; what is left of it stays unused.
  auto it = free_.lower_bound(capacity);
  if (it != free_.end())
  {
    const std::size_t offset = it->second, rest = it->first - capacity;
    free_.erase(it);
    if (rest >= 3)
    {
      free_.emplace(rest, offset + capacity);
    }
    return offset;
  }
  if (end_ + capacity > indices_.size())
  {
    // Grow by half again, so that appends are amortised; a new size is a rewrite (the
    // renderer's buffer must be reallocated). On huge pages where it is large: a list of
    // 15 MB faulted in 4 KiB pages took 32 ms of a frame over Puget Sound (HugePages.h).
    resizeOnHugePages(indices_,
      wholeTriangles(std::max(end_ + capacity, indices_.size() + indices_.size() / 2)), kRestartIndex);
    rewritten_ = true;
    dirty_.clear();
  }
  const std::size_t offset = end_;
  end_ += capacity;
  return offset;
}

void IndexArena::assign(int block, const uint32_t* tris, std::size_t count)
{
  Slot& s = slots_[static_cast<std::size_t>(block)];
  if (count == 0)
  {
    release(s);
    return;
  }
  if (count > s.capacity)
  {
    release(s);
    s.capacity = slotCapacity(count);
    s.offset = allocate(s.capacity);
  }
  std::copy(tris, tris + count, indices_.begin() + s.offset);
  if (s.count > count)
  {
    std::fill(indices_.begin() + s.offset + count, indices_.begin() + s.offset + s.count, kRestartIndex);
  }
  markDirty(s.offset, s.offset + std::max(count, s.count));
  live_ += count;
  live_ -= s.count;
  s.count = count;
}

void IndexArena::compact()
{
  // Packed into the list the previous compaction left behind: its pages are touched
  // already, where a new list of a few megabytes cost a page fault per 4 KiB (over Rainier,
  // a compaction frame's update took 3x a frame's).
  std::vector<uint32_t>& packed = spare_;
  packed.clear();
  reserveOnHugePages(packed, live_ + live_ / 4 + 6 * slots_.size() / 8);
  for (Slot& s : slots_)
  {
    if (s.count == 0)
    {
      s = Slot();
      continue;
    }
    const std::size_t offset = packed.size();
    packed.insert(packed.end(), indices_.begin() + s.offset, indices_.begin() + s.offset + s.count);
    s.offset = offset;
    s.capacity = slotCapacity(s.count);
    packed.resize(offset + s.capacity, kRestartIndex);
  }
  end_ = packed.size();
  resizeOnHugePages(packed, wholeTriangles(end_ + end_ / 4), kRestartIndex);
  indices_.swap(packed); // the old list is the next compaction's
  if (spare_.capacity() > 4 * indices_.size())
  {
    // Not a list that shrank this much (a full-resolution frame, then a coarse one): the
    // arena holds at most one list beside its own, of at most four times its size. (Budget
    // churn over Rainier compacts lists of 1.6x the packed size, whose capacity the
    // vector's growth made up to twice that.)
    std::vector<uint32_t>().swap(spare_);
  }
  free_.clear();
  rewritten_ = true;
  dirty_.clear();
}

void IndexArena::endFrame()
{
  if (end_ > kCompactMinimum && end_ - live_ > live_)
  {
    compact(); // more than half of the slots' space unused
  }
  if (rewritten_)
  {
    // Being rewritten anyway: leave a quarter in reserve, so that the blocks the next
    // frames move to the end do not force another rewrite.
    resizeOnHugePages(indices_, std::max(indices_.size(), wholeTriangles(end_ + end_ / 4)), kRestartIndex);
    dirty_.clear();
    ++version_;
    return;
  }
  std::sort(dirty_.begin(), dirty_.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
  std::size_t out = 0;
  for (const Range& r : dirty_)
  {
    if (out > 0 && r.begin <= dirty_[out - 1].end + kMergeGap)
    {
      dirty_[out - 1].end = std::max(dirty_[out - 1].end, r.end);
    }
    else
    {
      dirty_[out++] = r;
    }
  }
  dirty_.resize(out);
  if (out > 0)
  {
    ++version_;
  }
}

void IndexArena::appendTriangles(const std::vector<int>& slots, std::vector<uint32_t>& out) const
{
  out.reserve(out.size() + live_);
  for (int k : slots)
  {
    const Slot& s = slots_[static_cast<std::size_t>(k)];
    out.insert(out.end(), indices_.begin() + s.offset, indices_.begin() + s.offset + s.count);
  }
}

} // namespace gmm
