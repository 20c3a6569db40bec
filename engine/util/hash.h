// 64-bit content hashing (FNV-1a based, with a final avalanche) for cache keys and file hashes.
// Not cryptographic: it detects changes, it does not resist adversaries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

namespace strata {

// MurmurHash3's 64-bit finaliser: a bijection in which every input bit flips about half the
// output bits.
inline uint64_t avalanche64(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  x ^= x >> 33;
  return x;
}

class Hasher {
 public:
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      state_ ^= p[i];
      state_ *= 0x100000001b3ull;
    }
  }
  template <typename T>
  Hasher& add(const T& value) {
    static_assert(std::is_trivially_copyable<T>::value, "hash plain values only");
    bytes(&value, sizeof(T));
    return *this;
  }
  Hasher& add(const std::string& text) {
    add<uint64_t>(text.size());
    bytes(text.data(), text.size());
    return *this;
  }
  uint64_t digest() const { return avalanche64(state_); }

 private:
  uint64_t state_ = 0xcbf29ce484222325ull;
};

// "fnv1a64:" followed by 16 lowercase hex digits.
std::string formatContentHash(uint64_t digest);

}  // namespace strata
