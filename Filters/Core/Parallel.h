// Spreading a loop over cores: parallelChunks for the scans of the samples (validation,
// block boxes, the heights' hash, synthetic terrain, the mapper's slopes), parallelItems
// for items that need per-worker scratch (geomorphing's part errors), workerCount for
// every thread count (the error table's build, whose caller reports progress instead of
// working, keeps its own two-phase loop).
//
// Work is cut into chunks that threads take from a shared counter, so a core that runs
// slower (or is busy elsewhere) takes fewer of them instead of holding up the others, as a
// fixed share would (on the benchmark VM one core ran 1.6x slower than the other).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace gmm
{

// Threads for `tasks` pieces of work: `threads` (0 = the hardware's), at most `tasks`, at
// least 1.
inline unsigned workerCount(int threads, std::size_t tasks)
{
  const unsigned want = threads > 0 ? static_cast<unsigned>(threads) : std::thread::hardware_concurrency();
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(std::max(want, 1u), tasks)));
}

// Calls fn(worker, item) for every item in [0, count), on up to `threads` threads (0 = the
// hardware's). Items are taken one at a time from a shared counter; `worker` is 0 on the
// calling thread and 1 .. workerCount(threads, count) - 1 on the others, so that fn can keep
// per-worker scratch. fn must be safe to run concurrently on different items.
template <class Fn>
void parallelItems(std::size_t count, int threads, Fn&& fn)
{
  std::atomic<std::size_t> next{ 0 };
  auto work = [&](unsigned worker) {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1))
    {
      fn(worker, i);
    }
  };
  const unsigned workers = workerCount(threads, count);
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < workers; ++w)
  {
    pool.emplace_back(work, w);
  }
  work(0);
  for (std::thread& t : pool)
  {
    t.join();
  }
}

// Calls fn(begin, end) for consecutive ranges of at most `chunk` items covering [0, count),
// on up to `threads` threads (0 = the hardware's; the calling thread is one of them). fn must
// be safe to run concurrently on disjoint ranges; ranges are taken in increasing order.
template <class Fn>
void parallelChunks(std::size_t count, std::size_t chunk, int threads, Fn&& fn)
{
  chunk = std::max<std::size_t>(chunk, 1);
  parallelItems((count + chunk - 1) / chunk, threads, [&](unsigned, std::size_t c) {
    const std::size_t begin = c * chunk;
    fn(begin, std::min(count, begin + chunk));
  });
}

} // namespace gmm
