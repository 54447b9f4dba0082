#pragma once
// Exact position lookup for welding vertices: positions are equal when their coordinates have the
// same bits (optionally taking -0 and +0 as one).
//  - PositionIndex: an open-addressing table of indices into the caller's position array, so it
//    costs 8 bytes per position at most, not a node per entry as std::unordered_map does; for
//    positions that arrive one at a time (a text file's vertices).
//  - first_equal_keys(): the same answer for n positions known up front, in parallel; welding
//    millions of STL corners is part of loading a model.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "pierce/huge_page_allocator.h"
#include "pierce/vec3.h"

namespace pierce {

enum class PositionZeros { distinct, merged };  // merged: -0 and +0 are the same coordinate

namespace detail {
inline std::uint64_t coordinate_bits(double v, PositionZeros zeros) {
  return std::bit_cast<std::uint64_t>(zeros == PositionZeros::merged && v == 0.0 ? 0.0 : v);
}
}  // namespace detail

// The bits that decide whether two positions are equal (PositionIndex's test, first_equal_keys' key).
inline std::array<std::uint64_t, 3> position_key(const Vec3d& p, PositionZeros zeros) {
  return {detail::coordinate_bits(p.x, zeros), detail::coordinate_bits(p.y, zeros), detail::coordinate_bits(p.z, zeros)};
}

namespace detail {

// A hash of three coordinates' bits.
template <class U>
std::uint64_t key_hash(const std::array<U, 3>& k) {
  std::uint64_t h = std::uint64_t(k[0]) * 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 29) ^ std::uint64_t(k[1])) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 32) ^ std::uint64_t(k[2])) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

inline constexpr std::uint32_t kNoPosition = 0xFFFFFFFFu;

// Linear probing in a power-of-two table of position indices: the index of an equal position
// already there, or `i` after inserting it.
template <class PositionAt>
std::uint32_t find_or_insert_position(std::vector<std::uint32_t>& slots, const PositionAt& at, std::uint32_t i,
                                      PositionZeros zeros) {
  const std::array<std::uint64_t, 3> key = position_key(at(i), zeros);
  const std::size_t mask = slots.size() - 1;
  for (std::size_t s = std::size_t(key_hash(key)) & mask;; s = (s + 1) & mask) {
    const std::uint32_t k = slots[s];
    if (k == kNoPosition) {
      slots[s] = i;
      return i;
    }
    if (position_key(at(k), zeros) == key) return k;
  }
}

}  // namespace detail

class PositionIndex {
 public:
  using Zeros = PositionZeros;

  // `expected`: how many distinct positions will be inserted (the table grows beyond it).
  explicit PositionIndex(std::size_t expected, Zeros zeros = Zeros::distinct) : zeros_(zeros) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, detail::kNoPosition);
  }

  // The index of the first of positions[0 .. i) equal to positions[i], or i if there is none (then
  // i is remembered). positions[i] must not change afterwards while the index is used.
  std::uint32_t find_or_insert(const std::vector<Vec3d>& positions, std::uint32_t i) {
    if (2 * (size_ + 1) > slots_.size()) grow(positions);
    const auto at = [&positions](std::uint32_t k) { return positions[k]; };
    const std::uint32_t found = detail::find_or_insert_position(slots_, at, i, zeros_);
    size_ += found == i;
    return found;
  }

 private:
  void grow(const std::vector<Vec3d>& positions) {
    std::vector<std::uint32_t> old(slots_.size() * 2, detail::kNoPosition);
    old.swap(slots_);
    const std::size_t mask = slots_.size() - 1;
    for (const std::uint32_t k : old) {
      if (k == detail::kNoPosition) continue;
      std::size_t s = std::size_t(detail::key_hash(position_key(positions[k], zeros_))) & mask;
      while (slots_[s] != detail::kNoPosition) s = (s + 1) & mask;
      slots_[s] = k;
    }
  }

  Zeros zeros_;
  std::vector<std::uint32_t> slots_;
  std::size_t size_ = 0;
};

// For every i < n: the first j <= i with key_at(j) == key_at(i), the answer PositionIndex gives for
// i = 0, 1, ... n-1. A key is the three coordinates' bits (std::array<U, 3>: position_key(), or a
// float file's raw bits). In parallel and with the same result on any thread count: a stable
// counting sort by hash copies the keys into partitions of a few thousand, each listing its keys in
// increasing i, and each partition is welded on its own with a table that stays in the cache. One
// table over the 4.9 M corners of a 1.6 M-triangle STL misses the cache on nearly every probe, and
// so would partitions that looked their keys up in the file.
template <class Key, class KeyAt>
std::vector<std::uint32_t> first_equal_keys(std::size_t n, const KeyAt& key_at) {
  if (n >= detail::kNoPosition) throw std::length_error("first_equal_keys: more than 2^32 - 2 positions");
  std::vector<std::uint32_t> first;
  reserve_huge(first, n);
  first.resize(n);
  constexpr std::size_t kChunk = std::size_t(1) << 16;  // keys per task of the counting sort
  constexpr std::size_t kPartition = 4096;              // keys per partition, about
  int part_bits = 0;
  while (part_bits < 16 && (n >> part_bits) > kPartition) ++part_bits;
  const std::size_t parts = std::size_t(1) << part_bits;
  const auto part_of = [part_bits](std::uint64_t hash) {
    return part_bits == 0 ? std::size_t(0) : std::size_t(hash >> (64 - part_bits));
  };
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  // next[c * parts + p]: how many keys of chunk c fall in partition p, then where the first of them
  // goes (partition-major, chunks in order within a partition).
  std::vector<std::uint32_t> next(chunks * parts, 0);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    std::uint32_t* count = next.data() + c * parts;
    for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i)
      ++count[part_of(detail::key_hash(Key(key_at(i))))];
  });
  std::vector<std::uint32_t> start(parts + 1);
  std::uint32_t placed = 0;
  for (std::size_t p = 0; p < parts; ++p) {
    start[p] = placed;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::uint32_t count = next[c * parts + p];
      next[c * parts + p] = placed;
      placed += count;
    }
  }
  start[parts] = placed;
  struct Record {
    Key key;
    std::uint32_t index;
  };
  HugePageVector<Record> sorted(n);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    std::uint32_t* to = next.data() + c * parts;
    for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i) {
      const Key k = key_at(i);
      sorted[to[part_of(detail::key_hash(k))]++] = {k, std::uint32_t(i)};
    }
  });
  // Slots hold record numbers within the partition, first occurrences only.
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> tables;
  tbb::parallel_for(std::size_t(0), parts, [&](std::size_t p) {
    const Record* rec = sorted.data() + start[p];
    const std::size_t m = start[p + 1] - start[p];
    std::size_t cap = 16;
    while (cap < 2 * m) cap *= 2;
    std::vector<std::uint32_t>& slots = tables.local();
    slots.assign(cap, detail::kNoPosition);
    for (std::size_t x = 0; x < m; ++x) {
      for (std::size_t s = std::size_t(detail::key_hash(rec[x].key)) & (cap - 1);; s = (s + 1) & (cap - 1)) {
        const std::uint32_t y = slots[s];
        if (y == detail::kNoPosition) {
          slots[s] = std::uint32_t(x);
          first[rec[x].index] = rec[x].index;
          break;
        }
        if (rec[y].key == rec[x].key) {
          first[rec[x].index] = rec[y].index;
          break;
        }
      }
    }
  });
  return first;
}

}  // namespace pierce
