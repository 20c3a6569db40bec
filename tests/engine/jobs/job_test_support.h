// What the tests of the background jobs share: small scenes, a generous timeout for waits that
// only fail when something hangs, and a guard against a call that never returns.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <future>
#include <memory>
#include <thread>

#include "tests/support/scene_builder.h"

namespace strata::test {

// Long enough for a loaded machine under ThreadSanitizer; a wait that runs out means a hang.
constexpr std::chrono::seconds kJobTimeout{120};

// A box minus a sphere: one Boolean, two leaves, closed result. `variant` changes the sphere's
// radius, so each variant is a different scene for the evaluator's cache.
inline std::shared_ptr<const Scene> boxMinusSphere(int resolution, int variant = 0) {
  return std::make_shared<const Scene>(
      makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.1 + 0.01 * variant, {1, 1, 1})}),
                resolution));
}

// Runs `call` on another thread and waits for it. A call that has not returned after
// `timeout` cannot be recovered from (it may hold references into the test): the process
// aborts, saying so.
inline void expectReturnsWithin(std::chrono::seconds timeout, const std::function<void()>& call,
                                const char* what) {
  std::promise<void> returned;
  std::future<void> future = returned.get_future();
  std::thread runner([&] {
    call();
    returned.set_value();
  });
  if (future.wait_for(timeout) != std::future_status::ready) {
    std::fprintf(stderr, "FATAL: %s did not return within %lld s\n", what,
                 static_cast<long long>(timeout.count()));
    std::fflush(stderr);
    std::abort();
  }
  runner.join();
}

}  // namespace strata::test
