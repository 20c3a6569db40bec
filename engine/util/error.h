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

// Thrown from inside long operations when the caller asked them to stop.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace strata
