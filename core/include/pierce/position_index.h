#pragma once
// Exact position lookup for welding vertices: positions are equal when their coordinates have the
// same bits (optionally taking -0 and +0 as one). An open-addressing table of indices into the
// caller's position array, so it costs 8 bytes per position at most, not a node per entry as
// std::unordered_map does; welding millions of STL corners is part of loading a model.
#include <bit>
#include <cstdint>
#include <vector>

#include "pierce/vec3.h"

namespace pierce {

class PositionIndex {
 public:
  enum class Zeros { distinct, merged };  // merged: -0 and +0 are the same coordinate

  // `expected`: how many distinct positions will be inserted (the table grows beyond it).
  explicit PositionIndex(std::size_t expected, Zeros zeros = Zeros::distinct) : zeros_(zeros) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, kEmpty);
  }

  // The index of the first of positions[0 .. i) equal to positions[i], or i if there is none (then
  // i is remembered). positions[i] must not change afterwards while the index is used.
  std::uint32_t find_or_insert(const std::vector<Vec3d>& positions, std::uint32_t i) {
    if (2 * (size_ + 1) > slots_.size()) grow(positions);
    const Vec3d& p = positions[i];
    for (std::size_t s = hash(p) & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1)) {
      const std::uint32_t k = slots_[s];
      if (k == kEmpty) {
        slots_[s] = i;
        ++size_;
        return i;
      }
      if (same(positions[k], p)) return k;
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

  std::uint64_t bits(double v) const {
    return std::bit_cast<std::uint64_t>(zeros_ == Zeros::merged && v == 0.0 ? 0.0 : v);
  }
  bool same(const Vec3d& a, const Vec3d& b) const {
    return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z);
  }
  std::size_t hash(const Vec3d& p) const {
    std::uint64_t h = bits(p.x) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ bits(p.y)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 32) ^ bits(p.z)) * 0x94D049BB133111EBull;
    return std::size_t(h ^ (h >> 31));
  }
  void grow(const std::vector<Vec3d>& positions) {
    std::vector<std::uint32_t> old(slots_.size() * 2, kEmpty);
    old.swap(slots_);
    for (const std::uint32_t k : old) {
      if (k == kEmpty) continue;
      std::size_t s = hash(positions[k]) & (slots_.size() - 1);
      while (slots_[s] != kEmpty) s = (s + 1) & (slots_.size() - 1);
      slots_[s] = k;
    }
  }

  Zeros zeros_;
  std::vector<std::uint32_t> slots_;
  std::size_t size_ = 0;
};

}  // namespace pierce
