#pragma once
// Zone and node loops split into fixed blocks that threads share (OpenMP). The blocks do not depend on
// the number of threads, and every sum over blocks is taken in block order, so a run gives the same
// bits on one thread as on several.
#include <algorithm>
#include <vector>

#include "krug/mesh/mesh.hpp"

namespace krug {

// Zones (or nodes) per block, from the loop's length alone (never from the number of threads): the loop
// is cut into an even number of equal blocks (to within one) of at most 4 096, so that two threads get
// equal shares; a loop shorter than 2 x 512 is one block. Large blocks keep the limiter sharing, which
// a block boundary interrupts. The measurements behind the bounds are in docs/performance.md ("Two threads").
inline constexpr Index smallest_block = 512;
inline constexpr Index largest_block = 4096;

inline Index block_count(Index begin, Index end) {
  const Index length = end - begin;
  if (length <= 0) return 0;
  if (length < 2 * smallest_block) return 1;
  return 2 * ((length + 2 * largest_block - 1) / (2 * largest_block));
}

inline Index block_size(Index length) {
  const Index blocks = block_count(0, length);
  return blocks > 0 ? (length + blocks - 1) / blocks : 0;
}

// Fewer blocks than this run on the calling thread alone: starting the other threads and waiting for
// them at the end of the loop costs more than they save on a small loop. Threads pay only on free
// cores, hence the default of one thread (docs/performance.md, "Two threads").
inline constexpr Index min_parallel_blocks = 2;

// Calls body(block, first, last) for every block of [begin, end), on up to `threads` threads.
template <class Body>
void for_each_block(Index begin, Index end, int threads, Body&& body) {
  const Index blocks = block_count(begin, end);
  const Index size = blocks > 0 ? block_size(end - begin) : 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && blocks >= min_parallel_blocks)
  for (Index b = 0; b < blocks; ++b) {
    const Index first = begin + b * size;
    body(b, first, std::min(end, first + size));
  }
}

// Calls body(first, last) for every block of [begin, end) as for_each_block does, and returns what each
// call returned, in block order (so that the caller combines them in an order independent of the threads).
template <class Result, class Body>
std::vector<Result> block_results(Index begin, Index end, int threads, Body&& body) {
  std::vector<Result> results(static_cast<std::size_t>(block_count(begin, end)));
  for_each_block(begin, end, threads, [&](Index block, Index first, Index last) {
    results[static_cast<std::size_t>(block)] = body(first, last);
  });
  return results;
}

}  // namespace krug
