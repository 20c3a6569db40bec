#include "engine/util/hash.h"

#include <cstdio>

namespace strata {

std::string formatContentHash(uint64_t digest) {
  char text[32];
  std::snprintf(text, sizeof(text), "fnv1a64:%016llx", static_cast<unsigned long long>(digest));
  return text;
}

}  // namespace strata
