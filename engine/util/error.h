// Errors as values a person can read: every failure in the engine is a strata::Error whose
// message names the file (or scene location) and what was wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace strata {

// A user-facing failure: bad input, a resource limit, an impossible request.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// A backend ran out of its own memory (device memory for the CUDA backend). The caller may retry
// with smaller tiles or on another backend; see engine/export/fallback.h.
class BackendOutOfMemory : public Error {
 public:
  explicit BackendOutOfMemory(const std::string& message) : Error(message) {}
};

// Thrown from inside long operations when the caller asked them to stop.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace strata
