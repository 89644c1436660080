// Large fresh buffers backed by huge pages where the system allows it.
//
// The first touch of a new page costs a page fault. With 4 KiB pages a GiB is 262 144
// faults: 3.5 s on the benchmark VM (a paravirtualised guest, where each fault is slow),
// about a quarter second on bare metal. Linux maps 2 MiB pages instead where a range is
// advised MADV_HUGEPAGE (transparent huge pages in "madvise" mode, Debian's default): 512
// faults a GiB, 0.1 s on the same VM once huge pages are free (2.1 s when the kernel has
// to compact memory for them first). So every buffer of the DEM's size that the engine or
// its readers allocate is advised (adviseHugePages, resizeOnHugePages) before its first write.
#pragma once

#include <cstddef>
#include <vector>

namespace gmm
{

// Smallest buffer worth advising: one huge page.
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// Advises the whole huge pages inside [p, p + bytes) to be backed by huge pages; call it
// after allocating and before the first write (pages already touched keep their size).
// A no-op for smaller ranges and on systems without transparent huge pages.
void adviseHugePages(void* p, std::size_t bytes);

// v.reserve(n), with a new allocation (n elements or more) advised before its elements are
// copied into it.
template <class T>
void reserveOnHugePages(std::vector<T>& v, std::size_t n)
{
  if (n > v.capacity() && n * sizeof(T) >= kHugePageBytes)
  {
    std::vector<T> fresh;
    fresh.reserve(n);
    adviseHugePages(fresh.data(), n * sizeof(T));
    fresh.assign(v.begin(), v.end());
    v.swap(fresh);
  }
  v.reserve(n);
}

// v.resize(n, value), with a new allocation of n or more elements advised before it is
// filled.
template <class T>
void resizeOnHugePages(std::vector<T>& v, std::size_t n, const T& value = T())
{
  reserveOnHugePages(v, n);
  v.resize(n, value);
}

} // namespace gmm
