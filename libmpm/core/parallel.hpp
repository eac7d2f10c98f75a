// Deterministic OpenMP building blocks: results are bit-identical for any number of threads.
#pragma once
#include <omp.h>
#if defined(__SSE__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>


namespace cleave {

// Threads pay off only above a few thousand items per loop; below that the fork/join costs more
// than the work (and, on a loaded machine, far more).
inline bool worth_parallel(std::size_t n) { return n >= 8192 && omp_get_max_threads() > 1; }

// Flush denormals to zero on every OpenMP thread. A wave front running into a body at rest leaves
// values near 1e-310 behind it, and arithmetic on denormals is ~100x slower on x86.
inline void flush_denormals_on_all_threads() {
#if defined(__SSE__)
#pragma omp parallel
  {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
#endif
}

// Sum of f(i) for i < n, in fixed chunks summed in chunk order, so the rounding does not depend
// on the thread count (an OpenMP reduction would).
template <class F>
double deterministic_sum(std::size_t n, F&& f) {
  constexpr std::size_t kChunk = 4096;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> partial(chunks, 0.0);
#pragma omp parallel for schedule(static) if (chunks > 2 && omp_get_max_threads() > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    double s = 0.0;
    const std::size_t end = std::min(n, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) s += f(i);
    partial[c] = s;
  }
  double s = 0.0;
  for (double v : partial) s += v;
  return s;
}

// K sums at once, f(i, acc) adding item i's terms into acc[0..K): the same fixed chunks and order as
// deterministic_sum, one pass over the data instead of K.
template <std::size_t K, class F>
std::array<double, K> deterministic_sums(std::size_t n, F&& f) {
  constexpr std::size_t kChunk = 4096;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::array<double, K>> partial(chunks);
#pragma omp parallel for schedule(static) if (chunks > 2 && omp_get_max_threads() > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    std::array<double, K> s{};
    const std::size_t end = std::min(n, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) f(i, s.data());
    partial[c] = s;
  }
  std::array<double, K> s{};
  for (const auto& v : partial)
    for (std::size_t k = 0; k < K; ++k) s[k] += v[k];
  return s;
}

}  // namespace cleave
