#pragma once
//! \file flat_table.h
//! Internal: a hash table from simplex keys (sorted vertex ids) to values, for the restricted
//! Delaunay records that are looked up, added and dropped at every insertion.
//!
//! The keys live in one flat array with open addressing (linear probing; deletion by backward
//! shift, so no tombstones), each with the index of its value in a pool; the values live in
//! blocks of 1024 whose slots are reused.  A lookup touches one or two cache lines of the key array
//! and then the value, where a node-based std::unordered_map follows a bucket pointer and a list.
//!
//! Contract: references to values stay valid until that key is erased or the table cleared (the
//! pool never moves its elements).  A value whose key was erased keeps its old contents until its
//! slot is reused; try_emplace() of a new key hands it out, and the caller overwrites it.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "meshing/core/detail/key_order.h"

namespace delmesh::detail {

template <std::size_t N, class Value>
class FlatTable {
 public:
  using Key = std::array<int, N>;

  std::size_t size() const { return size_; }

  Value* find(const Key& key) {
    if (size_ == 0) return nullptr;
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      const Entry& e = entries_[i];
      if (e.key[0] < 0) return nullptr;
      if (KeyEqual{}(e.key, key)) return &value(e.index);
    }
  }
  const Value* find(const Key& key) const { return const_cast<FlatTable*>(this)->find(key); }

  //! Asks the processor to load the first slot key's lookup will read (no effect on the
  //! contents).  Prefetching the keys of a batch before looking them up lets their cache misses
  //! overlap instead of coming one after another.
  void prefetch(const Key& key) const {
    if (!entries_.empty()) __builtin_prefetch(&entries_[home(key)]);
  }

  //! The value of key and true if it was added (then its contents are unspecified), or the
  //! existing value and false.
  std::pair<Value*, bool> try_emplace(const Key& key) {
    if (4 * (size_ + 1) > 3 * entries_.size()) grow();
    std::size_t i = home(key);
    for (;; i = (i + 1) & mask_) {
      Entry& e = entries_[i];
      if (e.key[0] < 0) break;
      if (KeyEqual{}(e.key, key)) return {&value(e.index), false};
    }
    std::uint32_t index;
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
    } else {
      if (pool_size_ == blocks_.size() * block_size) blocks_.push_back(std::make_unique<Value[]>(block_size));
      index = static_cast<std::uint32_t>(pool_size_++);
    }
    entries_[i] = Entry{key, index};
    ++size_;
    return {&value(index), true};
  }

  //! Removes key if present; returns whether it was.
  bool erase(const Key& key) { return take(key) != nullptr; }

  //! Removes key if present and returns its former value (its contents stay until the next
  //! try_emplace()), or nullptr.
  Value* take(const Key& key) {
    if (size_ == 0) return nullptr;
    std::size_t i = home(key);
    for (;; i = (i + 1) & mask_) {
      if (entries_[i].key[0] < 0) return nullptr;
      if (KeyEqual{}(entries_[i].key, key)) break;
    }
    Value* taken = &value(entries_[i].index);
    free_.push_back(entries_[i].index);
    --size_;
    // Backward shift: move later entries of the probe run into the hole when their home allows.
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      Entry& e = entries_[j];
      if (e.key[0] < 0) break;
      const std::size_t h = home(e.key);
      // e may fill the hole at i iff its home is not cyclically in (i, j].
      const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
      if (stays) continue;
      entries_[i] = e;
      i = j;
    }
    entries_[i].key[0] = -1;
    return taken;
  }

  void clear() {
    entries_.clear();
    blocks_.clear();
    pool_size_ = 0;
    free_.clear();
    size_ = 0;
    mask_ = 0;
  }

  //! Calls f(key, value) for every entry, in no particular order.
  template <class F>
  void for_each(F&& f) const {
    for (const Entry& e : entries_)
      if (e.key[0] >= 0) f(e.key, value(e.index));
  }

 private:
  struct Entry {
    Key key;
    std::uint32_t index;
  };

  std::size_t home(const Key& key) const {
    std::uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (int v : key) {
      h ^= static_cast<std::uint32_t>(v);
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 32;
    }
    return static_cast<std::size_t>(h) & mask_;
  }

  void grow() {
    const std::size_t capacity = std::max<std::size_t>(64, 2 * entries_.size());
    std::vector<Entry> old(capacity, empty_entry());
    old.swap(entries_);
    mask_ = capacity - 1;
    for (const Entry& e : old) {
      if (e.key[0] < 0) continue;
      std::size_t i = home(e.key);
      while (entries_[i].key[0] >= 0) i = (i + 1) & mask_;
      entries_[i] = e;
    }
  }

  static Entry empty_entry() {
    Entry e{};
    e.key[0] = -1;
    return e;
  }

  std::vector<Entry> entries_;  // size a power of two, at most three quarters full
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
  //! The values, in blocks of block_size allocated one at a time and never moved; value i is
  //! entry i % block_size of block i / block_size.
  static constexpr std::size_t block_size = 1024;
  std::vector<std::unique_ptr<Value[]>> blocks_;
  std::size_t pool_size_ = 0;
  Value& value(std::uint32_t i) { return blocks_[i / block_size][i % block_size]; }
  const Value& value(std::uint32_t i) const { return blocks_[i / block_size][i % block_size]; }
  std::vector<std::uint32_t> free_;
};

}  // namespace delmesh::detail
