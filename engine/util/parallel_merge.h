// Merging runs that are each sorted by a 64-bit key into one sorted array, on all workers
// (parallelFor): the key space is split at keys sampled from the runs, each part's slice of
// every run is found by binary search, and the parts are merged on their own (a heap over the
// runs) into their place in the output. One pass over the data where appending the runs and
// sorting them took several; what the tiles of an export need (each tile emits its vertices and
// triangles in key order already).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include "engine/util/parallel_for.h"

namespace strata {

template <typename T>
struct SortedRun {
  const T* data = nullptr;  // sorted by key, ascending; not owned
  size_t size = 0;
};

namespace detail {

// Merges the slices [lo[r], hi[r]) of the runs, calling emit(first + k, element) for the k-th
// element of the merge (when emit is given); with `unique`, of equal keys only the first met
// (runs in order) is kept. Returns the number of elements of the merge.
template <typename T, typename Key, typename Emit>
size_t mergeSlices(const std::vector<SortedRun<T>>& runs, const std::vector<size_t>& lo,
                   const std::vector<size_t>& hi, Key key, bool unique, size_t first, Emit* emit) {
  using Head = std::pair<uint64_t, size_t>;  // key, run: ties taken in run order
  std::priority_queue<Head, std::vector<Head>, std::greater<Head>> heads;
  std::vector<size_t> at(lo);
  for (size_t r = 0; r < runs.size(); ++r)
    if (at[r] < hi[r]) heads.push({key(runs[r].data[at[r]]), r});
  size_t written = 0;
  bool any = false;
  uint64_t last = 0;
  while (!heads.empty()) {
    const size_t r = heads.top().second;
    uint64_t k = heads.top().first;
    heads.pop();
    // Run r's elements while they come before every other run's head (ties in run order): the
    // heap's order without its work, for the long stretches one run holds (a tile's row).
    for (;;) {
      if (!unique || !any || k != last) {
        if (emit) (*emit)(first + written, runs[r].data[at[r]]);
        ++written;
        any = true;
        last = k;
      }
      if (++at[r] >= hi[r]) break;
      k = key(runs[r].data[at[r]]);
      if (!heads.empty() && !(Head{k, r} < heads.top())) {
        heads.push({k, r});
        break;
      }
    }
  }
  return written;
}

}  // namespace detail

// The merge of runs sorted by key(element) (a uint64_t) into one order, planned at
// construction (how many elements, which part of every run goes where) and visited by each():
// for consumers that turn the merged elements into something else, without an array of them.
// With `unique`, elements with equal keys are taken as equal and the first met (runs in order)
// is kept. The runs must outlive it.
template <typename T, typename Key>
class RunMerge {
 public:
  RunMerge(const std::vector<SortedRun<T>>& runs, Key key, bool unique)
      : runs_(runs), key_(key), unique_(unique) {
    size_t total = 0;
    for (const SortedRun<T>& r : runs) total += r.size;
    // Parts split at keys sampled evenly from every run, so each holds a similar share.
    const size_t parts = total < (size_t(1) << 16) ? 1 : size_t(workerCount()) * 8;
    std::vector<uint64_t> sample;
    constexpr size_t kSamplesPerRun = 64;
    for (const SortedRun<T>& r : runs)
      for (size_t s = 1; s <= kSamplesPerRun && r.size > 0; ++s)
        sample.push_back(key(r.data[(r.size - 1) * s / kSamplesPerRun]));
    std::sort(sample.begin(), sample.end());
    std::vector<uint64_t> split;  // part p holds keys in [split[p - 1], split[p])
    for (size_t p = 1; p < parts && !sample.empty(); ++p) {
      const uint64_t s = sample[p * sample.size() / parts];
      if (split.empty() || s > split.back()) split.push_back(s);
    }
    const size_t partCount = split.size() + 1;
    // Slice [bounds_[p][r], bounds_[p + 1][r]) of run r belongs to part p.
    bounds_.assign(partCount + 1, std::vector<size_t>(runs.size()));
    for (size_t r = 0; r < runs.size(); ++r) {
      bounds_[partCount][r] = runs[r].size;
      for (size_t p = 0; p < split.size(); ++p)
        bounds_[p + 1][r] =
            size_t(std::lower_bound(runs[r].data, runs[r].data + runs[r].size, split[p],
                                    [&](const T& e, uint64_t k) { return key(e) < k; }) -
                   runs[r].data);
    }
    start_.assign(partCount + 1, 0);
    parallelFor(0, int64_t(partCount), 1, [&](int64_t b, int64_t e) {
      for (int64_t p = b; p < e; ++p) {
        size_t n = 0;
        if (unique) {
          n = detail::mergeSlices<T, Key, void (*)(size_t, const T&)>(
              runs, bounds_[size_t(p)], bounds_[size_t(p) + 1], key, true, 0, nullptr);
        } else {
          for (size_t r = 0; r < runs.size(); ++r)
            n += bounds_[size_t(p) + 1][r] - bounds_[size_t(p)][r];
        }
        start_[size_t(p) + 1] = n;
      }
    });
    for (size_t p = 0; p < partCount; ++p) start_[p + 1] += start_[p];
  }

  // Elements in the merge.
  size_t size() const { return start_.back(); }

  // Calls emit(i, element) for every element of the merge, i its place in it: on all workers,
  // each part's elements in order (emit must be safe to call from several threads at once for
  // distinct i).
  template <typename Emit>
  void each(Emit emit) const {
    struct None {};
    eachWith<None>([&](None&, size_t i, const T& e) { emit(i, e); });
  }

  // The same with a Context of its own for each stretch of the merge a worker visits in order
  // (default-constructed at the stretch's start; a cache of what the stretch met, say):
  // emit(context, i, element).
  template <typename Context, typename Emit>
  void eachWith(Emit emit) const {
    if (runs_.size() == 1 && !unique_) {  // one run: itself, in place
      const SortedRun<T>& run = runs_[0];
      parallelFor(0, int64_t(run.size), 65536, [&](int64_t b, int64_t e) {
        Context context;
        for (int64_t i = b; i < e; ++i) emit(context, size_t(i), run.data[size_t(i)]);
      });
      return;
    }
    const size_t partCount = start_.size() - 1;
    parallelFor(0, int64_t(partCount), 1, [&](int64_t b, int64_t e) {
      for (int64_t p = b; p < e; ++p) {
        Context context;
        auto withContext = [&](size_t i, const T& element) { emit(context, i, element); };
        detail::mergeSlices<T>(runs_, bounds_[size_t(p)], bounds_[size_t(p) + 1], key_, unique_,
                               start_[size_t(p)], &withContext);
      }
    });
  }

 private:
  const std::vector<SortedRun<T>>& runs_;
  Key key_;
  bool unique_;
  std::vector<std::vector<size_t>> bounds_;
  std::vector<size_t> start_;
};

// The runs merged into one array sorted by key(element). T: default-constructible and copyable.
template <typename T, typename Key>
std::vector<T> parallelMergeRuns(const std::vector<SortedRun<T>>& runs, Key key, bool unique) {
  const RunMerge<T, Key> merge(runs, key, unique);
  std::vector<T> out(merge.size());
  merge.each([&](size_t i, const T& e) { out[i] = e; });
  return out;
}

}  // namespace strata
