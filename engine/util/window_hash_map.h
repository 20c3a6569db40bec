// A hash map for working sets that come and go (the streamed check's window of vertices and
// edges: engine/export/check_streamed.h): open addressing with linear probing in one array of
// slots, erasure by backward shifting (no tombstones, so probes stay short however many entries
// have passed through), no allocation per entry. std::unordered_map, with a node allocated and
// freed per entry, took most of that check's time.
//
// Key: any type with ==; Hash: a callable giving a well-mixed 64-bit value (the slot is its low
// bits). Pointers returned by find and insert stay valid until the next insert or erase. Not
// thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace strata {

template <typename Key, typename Value, typename Hash>
class WindowHashMap {
 public:
  WindowHashMap() { rehash(64); }

  size_t size() const { return size_; }

  Value* find(const Key& key) {
    for (size_t i = slotOf(key);; i = (i + 1) & mask_) {
      if (!used_[i]) return nullptr;
      if (slots_[i].first == key) return &slots_[i].second;
    }
  }

  // The value of `key`, value-initialised when it was not there; *fresh says which.
  Value* insert(const Key& key, bool* fresh) {
    if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
    size_t i = slotOf(key);
    for (; used_[i]; i = (i + 1) & mask_) {
      if (slots_[i].first == key) {
        *fresh = false;
        return &slots_[i].second;
      }
    }
    used_[i] = 1;
    slots_[i] = {key, Value()};
    ++size_;
    *fresh = true;
    return &slots_[i].second;
  }

  // Removes `key` (where present): the entries after it in its run move back into the gap
  // where their probe would otherwise no longer reach them.
  void erase(const Key& key) {
    size_t i = slotOf(key);
    for (;; i = (i + 1) & mask_) {
      if (!used_[i]) return;
      if (slots_[i].first == key) break;
    }
    for (size_t j = (i + 1) & mask_; used_[j]; j = (j + 1) & mask_) {
      const size_t home = slotOf(slots_[j].first);
      // j's entry may move to i when i lies on its probe path (from home to j, cyclically).
      const bool reachable = i <= j ? (home <= i || home > j) : (home <= i && home > j);
      if (reachable) {
        slots_[i] = std::move(slots_[j]);
        i = j;
      }
    }
    used_[i] = 0;
    slots_[i] = {};
    --size_;
  }

 private:
  size_t slotOf(const Key& key) const { return size_t(Hash()(key)) & mask_; }

  void rehash(size_t capacity) {
    std::vector<std::pair<Key, Value>> old = std::move(slots_);
    std::vector<uint8_t> oldUsed = std::move(used_);
    slots_.assign(capacity, {});
    used_.assign(capacity, 0);
    mask_ = capacity - 1;
    size_ = 0;
    for (size_t k = 0; k < old.size(); ++k) {
      if (!oldUsed[k]) continue;
      size_t i = slotOf(old[k].first);
      while (used_[i]) i = (i + 1) & mask_;
      used_[i] = 1;
      slots_[i] = std::move(old[k]);
      ++size_;
    }
  }

  std::vector<std::pair<Key, Value>> slots_;
  std::vector<uint8_t> used_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

}  // namespace strata
