// Loops shared among the OpenMP threads only when they are long enough to gain from it.
//
// An OpenMP `if (false)` clause does not make a short loop free: libgomp still builds a team of
// one for the region every time (a memalign, a free and futex calls). In a two-sphere scene that
// was 1.1 us of the 1.45 us a step took; a clump scene entered five such regions a step. These
// helpers run a short loop inline, without entering a region at all.
#pragma once

#include <omp.h>

#include <algorithm>
#include <vector>

namespace dem {

// Thread t's share of [0, n) when split as schedule(static) splits it: contiguous, in order. With a
// block, whole blocks of that many (the last may be short) are shared instead of single items.
inline std::pair<int, int> static_range(int n, int threads, int t, int block = 1) {
  const int blocks = (n + block - 1) / block;
  const int chunk = blocks / threads, extra = blocks % threads;
  const int begin = t * chunk + std::min(t, extra), end = begin + chunk + (t < extra ? 1 : 0);
  return {std::min(n, begin * block), std::min(n, end * block)};
}

// The particles' blocks: the pair loop works on blocks of this many consecutive particles (BlockPlan),
// and every particle loop that runs on several threads gives each thread the same whole blocks
// (pass it as the block of for_ranges and reduce_ranges). A particle's lines then stay in one core's
// cache from loop to loop. Split evenly instead, while the pair loop handed the blocks out as the
// threads came free, about half of them were in the other core: on the 2-core VM a 32,000-sphere
// step's drift took 406 us on two threads against 223 us on one, and its kick 692 against 474.
inline constexpr int kParticleBlock = 4096;

// body(begin, end) over [0, n): one contiguous range per thread (whole blocks of `block`) when
// n >= min_parallel, else body(0, n) on this thread.
template <class Body>
void for_ranges(int n, int min_parallel, Body&& body, int block = 1) {
  if (n < min_parallel) {
    body(0, n);
    return;
  }
#pragma omp parallel
  {
    const auto [begin, end] = static_range(n, omp_get_num_threads(), omp_get_thread_num(), block);
    body(begin, end);
  }
}

// The same with a result per range (body returns a T), folded in range order with combine(a, b),
// starting from init: the same result for the same thread count, run after run.
template <class T, class Body, class Combine>
T reduce_ranges(int n, int min_parallel, T init, Body&& body, Combine&& combine, int block = 1) {
  if (n < min_parallel) return combine(init, body(0, n));
  // Each result in its own object: in a std::vector<bool> (T = bool, the kick's non-finite flag)
  // the threads' results were bits of one shared word, each thread's store a read-modify-write of
  // the whole word, so one thread could undo another's `true` (ThreadSanitizer found it).
  struct Part {
    T value;
  };
  std::vector<Part> parts(static_cast<std::size_t>(omp_get_max_threads()), Part{init});
  int used = 1;
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    const auto [begin, end] = static_range(n, threads, t, block);
    parts[t].value = body(begin, end);
#pragma omp single nowait
    used = threads;
  }
  T out = init;
  for (int t = 0; t < used; ++t) out = combine(out, parts[t].value);
  return out;
}

}  // namespace dem
