// The threads' shares of a loop (core/parallel.hpp): contiguous, in order, covering every item once;
// with a block, whole blocks only, so that every particle loop gives a thread the particles the pair
// loop's blocks give it.
#include <gtest/gtest.h>

#include <vector>

#include "core/parallel.hpp"

namespace dem::test::test_parallel_ranges {
namespace {

TEST(ParallelRanges, SharesCoverEveryItemOnceInOrderAndKeepBlocksWhole) {
  for (const int block : {1, 7, kParticleBlock})
    for (const int n : {0, 1, 4095, 4096, 4097, 8192, 10000, 31623, 37500})
      for (const int threads : {1, 2, 3, 8}) {
        int next = 0;
        for (int t = 0; t < threads; ++t) {
          const auto [begin, end] = static_range(n, threads, t, block);
          EXPECT_EQ(begin, next) << "n " << n << ", block " << block << ", thread " << t << " of " << threads;
          EXPECT_LE(begin, end);
          EXPECT_TRUE(begin % block == 0 || begin == n) << "a block split between threads";
          next = end;
        }
        EXPECT_EQ(next, n) << "n " << n << ", block " << block << ", threads " << threads;
      }
}

TEST(ParallelRanges, TheParticlesOfAThreadAreItsShareOfThePairLoopsBlocks) {
  // 37,500 particles: nine whole blocks and one of 644; two threads take five blocks each
  EXPECT_EQ(static_range(37500, 2, 0, kParticleBlock), std::pair(0, 5 * kParticleBlock));
  EXPECT_EQ(static_range(37500, 2, 1, kParticleBlock), std::pair(5 * kParticleBlock, 37500));
  const int blocks = (37500 + kParticleBlock - 1) / kParticleBlock;
  for (int t = 0; t < 2; ++t) {
    const auto [first, last] = static_range(blocks, 2, t);  // the pair loop's blocks of thread t
    const auto [begin, end] = static_range(37500, 2, t, kParticleBlock);
    EXPECT_EQ(begin, first * kParticleBlock);
    EXPECT_EQ(end, std::min(37500, last * kParticleBlock));
  }
  // the default block of one: an even split, as before
  EXPECT_EQ(static_range(10, 3, 0), std::pair(0, 4));
  EXPECT_EQ(static_range(10, 3, 2), std::pair(7, 10));
}

TEST(ParallelRanges, AResultPerRangeIsFoldedInRangeOrder) {
  // on however many threads the machine gives: the sum over [0, n) in blocks, the same every time
  const long long n = 20000;
  auto sum_of = [](int begin, int end) {
    long long s = 0;
    for (int i = begin; i < end; ++i) s += i;
    return s;
  };
  const long long total = reduce_ranges(
      static_cast<int>(n), 4096, 0LL, sum_of, [](long long a, long long b) { return a + b; }, kParticleBlock);
  EXPECT_EQ(total, n * (n - 1) / 2);
}

}  // namespace
}  // namespace dem::test::test_parallel_ranges
