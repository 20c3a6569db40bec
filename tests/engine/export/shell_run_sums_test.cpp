// ShellRunSums: each shell's six volumes summed in the one order unfold_shells.h fixes, the same
// bits whether the triangles come whole or in stretches cut anywhere, on one thread or several.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/export/unfold_shells.h"
#include "engine/util/parallel_for.h"

namespace strata::test {
namespace {

struct Terms {
  std::vector<uint32_t> shell;
  std::vector<double> anchored, placed;
};

// Over 3 x kChunk triangles of a few shells in runs of every length (some far longer than a
// chunk, some of one triangle), terms of mixed signs and magnitudes: sums whose bits depend on
// the order of their additions.
Terms randomTerms(uint64_t count, uint32_t shells, uint32_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> term(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  Terms t;
  while (t.shell.size() < count) {
    const uint32_t shell = uint32_t(random() % shells);
    const uint64_t length = random() % 4 == 0 ? 1 + random() % 200000 : 1 + random() % 40;
    for (uint64_t i = 0; i < length && t.shell.size() < count; ++i) {
      t.shell.push_back(shell);
      t.anchored.push_back(std::ldexp(term(random), exponent(random)));
      t.placed.push_back(std::ldexp(term(random), exponent(random)));
    }
  }
  return t;
}

struct Sums {
  std::vector<double> anchored, placed;
};

// The order written out plainly, a triangle at a time (as the streamed export summed it before
// its passes ran on threads): a run ends where the shell or the chunk changes.
Sums referenceSums(const Terms& t, uint32_t shells) {
  Sums sums{std::vector<double>(shells, 0.0), std::vector<double>(shells, 0.0)};
  uint32_t shell = ShellRun::kNone;
  uint64_t chunk = 0;
  double anchored = 0.0, placed = 0.0;
  const auto flush = [&] {
    if (shell == ShellRun::kNone) return;
    sums.anchored[shell] += anchored;
    sums.placed[shell] += placed;
  };
  for (uint64_t i = 0; i < t.shell.size(); ++i) {
    if (t.shell[i] != shell || i / ShellRunSums::kChunk != chunk) {
      flush();
      shell = t.shell[i];
      chunk = i / ShellRunSums::kChunk;
      anchored = placed = 0.0;
    }
    anchored += t.anchored[i];
    placed += t.placed[i];
  }
  flush();
  return sums;
}

// ShellRunSums fed the terms in stretches ending at `cuts` (increasing, the last the count).
Sums stretchedSums(const Terms& t, uint32_t shells, const std::vector<uint64_t>& cuts) {
  Sums sums{std::vector<double>(shells, 0.0), std::vector<double>(shells, 0.0)};
  const auto flush = [&](const ShellRun& run) {
    sums.anchored[run.shell] += run.anchored;
    sums.placed[run.shell] += run.placed;
  };
  ShellRunSums runs;
  uint64_t begin = 0;
  for (uint64_t end : cuts) {
    runs.add(
        end - begin,
        [&](uint64_t i, uint32_t* shell, double* anchored, double* placed) {
          *shell = t.shell[begin + i];
          *anchored = t.anchored[begin + i];
          *placed = t.placed[begin + i];
        },
        flush);
    begin = end;
  }
  runs.finish(flush);
  return sums;
}

bool sameBits(const Sums& a, const Sums& b) {
  return a.anchored == b.anchored && a.placed == b.placed;  // no NaN among them
}

TEST(ShellRunSums, TheSameBitsWhereverTheStretchesAreCutAndOnAnyThreadCount) {
  constexpr uint32_t kShells = 7;
  const uint64_t count = 3 * ShellRunSums::kChunk + 12345;
  const Terms terms = randomTerms(count, kShells, 11);
  const Sums reference = referenceSums(terms, kShells);

  // The test can fail: summed in another order (each shell's terms one after another, no runs)
  // the bits differ.
  Sums plain{std::vector<double>(kShells, 0.0), std::vector<double>(kShells, 0.0)};
  for (uint64_t i = 0; i < count; ++i) {
    plain.anchored[terms.shell[i]] += terms.anchored[i];
    plain.placed[terms.shell[i]] += terms.placed[i];
  }
  EXPECT_FALSE(sameBits(plain, reference));

  std::mt19937_64 random(5);
  std::vector<std::vector<uint64_t>> cutLists = {
      {count},                                                             // whole
      {ShellRunSums::kChunk, 2 * ShellRunSums::kChunk, count},             // on chunk boundaries
      {1, 2, ShellRunSums::kChunk - 1, ShellRunSums::kChunk + 1, count}};  // beside them
  for (int k = 0; k < 6; ++k) {  // anywhere, empty stretches included
    std::vector<uint64_t> cuts;
    for (int c = 0; c < 12; ++c) cuts.push_back(random() % (count + 1));
    cuts.push_back(count);
    std::sort(cuts.begin(), cuts.end());
    cutLists.push_back(cuts);
  }
  for (int threads : {1, 2, 3}) {
    setWorkerCount(threads);
    for (const std::vector<uint64_t>& cuts : cutLists) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", " + std::to_string(cuts.size()) +
                   " stretches, the first " + std::to_string(cuts[0]));
      EXPECT_TRUE(sameBits(stretchedSums(terms, kShells, cuts), reference));
    }
  }
  setWorkerCount(0);
}

}  // namespace
}  // namespace strata::test
