#pragma once
// Zone and node loops split into fixed blocks that threads share (OpenMP). The blocks do not depend on
// the number of threads, and every sum over blocks is taken in block order, so a run gives the same
// bits on one thread as on several.
#include <algorithm>

#include "krug/mesh/mesh.hpp"

namespace krug {

// Zones (or nodes) per block: large enough that a block's limiter sharing and loop set-up are
// amortised, small enough that 40 000 zones give each of two threads several blocks.
inline constexpr Index work_block = 4096;

inline Index block_count(Index begin, Index end) { return end > begin ? (end - begin + work_block - 1) / work_block : 0; }

// Fewer blocks than this run on the calling thread alone: starting the other threads and waiting for
// them at the end of the loop costs more than they save on a small loop, and far more when another
// process holds a core (measured: a paper case whose largest loop had 3 blocks ran 8 times slower on
// two threads while the other core was busy).
inline constexpr Index min_parallel_blocks = 4;

// Calls body(block, first, last) for every block of [begin, end), on up to `threads` threads.
template <class Body>
void for_each_block(Index begin, Index end, int threads, Body&& body) {
  const Index blocks = block_count(begin, end);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && blocks >= min_parallel_blocks)
  for (Index b = 0; b < blocks; ++b) {
    const Index first = begin + b * work_block;
    body(b, first, std::min(end, first + work_block));
  }
}

}  // namespace krug
