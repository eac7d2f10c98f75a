// The MPM particle order for parallel scatters without atomics (core/parallel.hpp has the generic
// deterministic building blocks).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/mpm/grid.hpp"
#include "libmpm/mpm/particles.hpp"

namespace cleave {

// Particles grouped into strips of kWidth cells along x. A particle scatters to nodes at most two
// cells from its own cell, so strips of one colour (every other strip) never share a node and run
// in parallel without atomics; each node then sums its contributions in the same order (colour 0
// strips, then colour 1, particles in index order) whatever the thread count.
// Flagged particles (near a crack) are kept apart, per strip: a strip runs its other particles in
// one tight loop, then its flagged ones with their own body, so the flagged particles' scatters
// run in parallel too without a test per particle in the main loop.
template <int Dim>
class StripOrder {
 public:
  static constexpr int kWidth = 4;

  // skip (optional, one flag per particle, with skip_test): particles left out of the main order and
  // kept in the flagged one (the crack module's particles near cracks). The flags are set afresh
  // here, in the same pass over the positions that finds the strips: skip[p] = skip_test(x_p) for
  // a particle with skip_test.in_box(x_p), else 0 (in_box: a cheap test that the compiler
  // vectorises, true for every particle that the full test may flag).
  // Returns true when a skip flag changed.
  template <class SkipTest = std::nullptr_t>
  bool build(const Particles<Dim>& P, const GridGeometry<Dim>& G, double inv_h, uint8_t* skip = nullptr,
             const SkipTest& skip_test = nullptr) {
    constexpr bool kSkip = !std::is_same_v<SkipTest, std::nullptr_t>;
    const int strips = (G.nodes[0] + kWidth - 1) / kWidth;
    const std::size_t np = P.size();
    // Particles rarely change strip from one step to the next: re-sort only when one did.
    int changed = strip_of_.size() != np || far_.size() != static_cast<std::size_t>(strips);
    if (kSkip && dirty_.size() != static_cast<std::size_t>(strips)) dirty_.assign(strips, 0);
    uint8_t* dirty = dirty_.data();
    int skip_changed = 0;
    strip_of_.resize(np);
    const Vec<Dim>* x = P.x.data();
    int* strip_of = strip_of_.data();
    const double origin = G.origin[0];
    // In blocks: first the strips (and the box test) in loops without branches, which vectorise;
    // then the full test for the few particles in the box or flagged before (the test per particle
    // in one loop with the strips cost ~1.6 ns per particle, ~1 % of a step).
    constexpr std::size_t kBlock = 1024;
    const std::size_t blocks = (np + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (worth_parallel(np)) reduction(| : changed, skip_changed) \
    firstprivate(skip_test)
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t p0 = b * kBlock, p1 = std::min(np, p0 + kBlock);
      int diff = 0;
      for (std::size_t p = p0; p < p1; ++p) {
        const int cell = static_cast<int>((x[p][0] - origin) * inv_h);  // x > origin: truncation = floor
        const int strip = std::clamp(cell / kWidth, 0, strips - 1);
        diff |= strip != strip_of[p];
        strip_of[p] = strip;
      }
      changed |= diff;
      if constexpr (kSkip) {
        uint8_t in[kBlock];
        int any = 0;
        for (std::size_t p = p0; p < p1; ++p) {
          in[p - p0] = skip_test.in_box(x[p]);
          any |= in[p - p0] | skip[p];
        }
        if (!any) continue;
        int fdiff = 0;
        for (std::size_t q = p0; q < p1; q += 8) {  // eight flags at a time: most are 0
          const std::size_t qe = std::min(p1, q + 8);
          uint64_t w = 0, v = 0;
          if (qe == q + 8) {
            std::memcpy(&w, &in[q - p0], 8);
            std::memcpy(&v, &skip[q], 8);
            if (!(w | v)) continue;
          }
          for (std::size_t p = q; p < qe; ++p) {
            if (!(in[p - p0] | skip[p])) continue;
            const uint8_t f = in[p - p0] ? skip_test(x[p]) : 0;
            if (f != skip[p]) {  // its strip's lists change (relaxed: only ever set to 1 here)
              fdiff = 1;
              std::atomic_ref<uint8_t>(dirty[strip_of[p]]).store(1, std::memory_order_relaxed);
            }
            skip[p] = f;
          }
        }
        skip_changed |= fdiff;
      }
    }
    parallel_ = worth_parallel(np);
    if (!kSkip) skip = nullptr;
    if (changed) {  // a particle changed strip: every list afresh, in index order
      far_.resize(strips);
      flagged_.resize(strips);
      for (int s = 0; s < strips; ++s) far_[s].clear(), flagged_[s].clear();
      for (std::size_t p = 0; p < np; ++p)
        ((skip && skip[p]) ? flagged_ : far_)[strip_of_[p]].push_back(static_cast<int32_t>(p));
      if (kSkip) std::fill(dirty_.begin(), dirty_.end(), 0);
    } else if (skip_changed) {
      // Only flags changed (the near set follows a moving crack every few steps): the strips that
      // hold such a particle re-split their particles, still in index order, so the lists are the
      // same as a full re-sort would make (a full one cost ~0.3 ms at 230 000 particles).
      for (int s = 0; s < strips; ++s) {
        if (!dirty_[s]) continue;
        dirty_[s] = 0;
        merged_.resize(far_[s].size() + flagged_[s].size());
        std::merge(far_[s].begin(), far_[s].end(), flagged_[s].begin(), flagged_[s].end(), merged_.begin());
        far_[s].clear(), flagged_[s].clear();
        for (int32_t p : merged_) (skip[p] ? flagged_ : far_)[s].push_back(p);
      }
    }
    return skip_changed;
  }

  // Calls body(p) for every particle not flagged; writes made by body to nodes never race.
  template <class F>
  void scatter(F&& body) const {
    scatter(body, [](std::size_t) {});
  }
  // The same, and flagged(p) for every flagged particle (each strip's after its other particles).
  template <class F, class G>
  void scatter(F&& body, G&& flagged) const {
    const int strips = static_cast<int>(far_.size());
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1) if (parallel_)
      for (int s = colour; s < strips; s += 2) {
        for (int32_t p : far_[s]) body(static_cast<std::size_t>(p));
        for (int32_t p : flagged_[s]) flagged(static_cast<std::size_t>(p));
      }
    }
  }

 private:
  std::vector<int> strip_of_;
  std::vector<std::vector<int32_t>> far_, flagged_;  // per strip, in index order
  std::vector<uint8_t> dirty_;                       // per strip: a flag of one of its particles changed
  std::vector<int32_t> merged_;
  bool parallel_ = false;
};

}  // namespace cleave
