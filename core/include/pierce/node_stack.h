#pragma once
// The containers of a traversal's pending nodes (traverse.h): a depth-first stack, and a heap
// ordered by entry distance.
#include <cstddef>
#include <limits>
#include <vector>

#include "pierce/wide_bvh.h"

namespace pierce {

// Depth-first pending nodes, in a buffer sized once from the BVH's depth (WideBvh::stack_capacity):
// no allocation and no capacity check per push (but for a kAnyOrder policy's, see
// FifoCursor::ensure_room). The traversal works on the raw buffer.
template <typename T>
class NodeStack {
 public:
  static constexpr bool kOrdered = false;
  // Room for n entries, plus a node's worth: the SIMD push writes eight entries whatever passed.
  void reserve(std::size_t n) {
    if (v_.size() < n + kWideArity) v_.resize(n + kWideArity);
  }
  // Entries the buffer holds (what reserve() asked for, plus a node's worth).
  std::size_t capacity() const { return v_.size(); }
  void clear() { size_ = 0; }
  bool empty() const { return size_ == 0; }
  void push(NodeEntry<T> e) { v_[size_++] = e; }
  NodeEntry<T> pop() { return v_[--size_]; }
  T next_tn() const { return v_[size_ - 1].tn; }
  T min_tn() const {
    T m = std::numeric_limits<T>::infinity();
    for (std::size_t i = 0; i < size_; ++i) m = v_[i].tn < m ? v_[i].tn : m;
    return m;
  }
  NodeEntry<T>* data() { return v_.data(); }
  std::size_t size() const { return size_; }
  void set_size(std::size_t n) { size_ = n; }

 private:
  std::vector<NodeEntry<T>> v_;
  std::size_t size_ = 0;
};

// Pending nodes ordered by entry distance (a binary min-heap in a vector that keeps its capacity).
template <typename T>
class NodeHeap {
 public:
  static constexpr bool kOrdered = true;
  void reserve(std::size_t n) { v_.reserve(n); }
  void clear() { v_.clear(); }
  bool empty() const { return v_.empty(); }
  void push(NodeEntry<T> e) {
    std::size_t i = v_.size();
    v_.push_back(e);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!(e.tn < v_[parent].tn)) break;
      v_[i] = v_[parent];
      i = parent;
    }
    v_[i] = e;
  }
  NodeEntry<T> pop() {
    const NodeEntry<T> top = v_.front();
    const NodeEntry<T> last = v_.back();
    v_.pop_back();
    const std::size_t n = v_.size();
    if (n == 0) return top;
    std::size_t i = 0;
    for (;;) {
      std::size_t c = 2 * i + 1;
      if (c >= n) break;
      if (c + 1 < n && v_[c + 1].tn < v_[c].tn) ++c;
      if (!(v_[c].tn < last.tn)) break;
      v_[i] = v_[c];
      i = c;
    }
    v_[i] = last;
    return top;
  }
  T next_tn() const { return v_.front().tn; }
  T min_tn() const { return v_.empty() ? std::numeric_limits<T>::infinity() : v_.front().tn; }
  std::size_t size() const { return v_.size(); }

 private:
  std::vector<NodeEntry<T>> v_;
};

}  // namespace pierce
