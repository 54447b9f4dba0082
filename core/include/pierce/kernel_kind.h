#pragma once
// The kernel registry: which kernels exist, what each guarantees and what it traces. Every front
// end, test and bench reads this table, so a kernel is added by one row here and one entry in
// kernel.h's type lists. Precision is a parameter of KernelKind, not a kernel of its own: every
// kernel on Pierce's BVH also runs in double precision ("<name>-d", on a double BVH of the double
// input).
#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace pierce {

enum class KernelId : std::uint8_t {
  epsilon,
  embree_restart,
  embree_filter,
  embree_nodecull,
  restart,
  queue,
  nodecull,
  filter,
  buffered,
};

// Whose BVH and traversal a kernel runs on.
enum class KernelStructure : std::uint8_t {
  embree,   // Embree's BVH and rtcIntersect1 (float only)
  own_bvh,  // Pierce's wide BVH and traverse.h, in float or double
};

enum class Precision : std::uint8_t { float32, float64 };

struct KernelInfo {
  KernelId id;
  std::string_view name;
  // Exact: every hit once, in the total order (docs/EXACTNESS.md); only `epsilon` is not.
  bool exact;
  KernelStructure structure;
};

// In the order `pierce hits --kernel all` runs and prints them.
inline constexpr KernelInfo kKernelTable[] = {
    {KernelId::epsilon, "epsilon", false, KernelStructure::embree},
    {KernelId::embree_restart, "embree-restart", true, KernelStructure::embree},
    {KernelId::embree_filter, "embree-filter", true, KernelStructure::embree},
    {KernelId::embree_nodecull, "embree-nodecull", true, KernelStructure::embree},
    {KernelId::restart, "restart", true, KernelStructure::own_bvh},
    {KernelId::queue, "queue", true, KernelStructure::own_bvh},
    {KernelId::nodecull, "nodecull", true, KernelStructure::own_bvh},
    {KernelId::filter, "filter", true, KernelStructure::own_bvh},
    {KernelId::buffered, "buffered", true, KernelStructure::own_bvh},
};

constexpr const KernelInfo& kernel_info(KernelId id) {
  for (const KernelInfo& row : kKernelTable)
    if (row.id == id) return row;
  return kKernelTable[0];  // unreachable while every KernelId has a row (checked below)
}

// A kernel and the precision it runs in. `KernelKind::queue` names the float kernel.
struct KernelKind {
  using enum KernelId;
  KernelId id = KernelId::queue;
  Precision precision = Precision::float32;

  constexpr KernelKind() = default;
  constexpr KernelKind(KernelId kernel, Precision p = Precision::float32) : id(kernel), precision(p) {}
  friend constexpr bool operator==(KernelKind, KernelKind) = default;
  friend constexpr auto operator<=>(KernelKind, KernelKind) = default;
};

// The kernel every front end traces with unless told otherwise.
inline constexpr KernelKind kDefaultKernel = KernelKind::queue;

constexpr bool is_exact(KernelKind k) { return kernel_info(k.id).exact; }
constexpr bool uses_embree(KernelKind k) { return kernel_info(k.id).structure == KernelStructure::embree; }
// Significand bits of the kernel's arithmetic: 24 (float) or 53 (double).
constexpr int kernel_precision_bits(KernelKind k) { return k.precision == Precision::float64 ? 53 : 24; }

namespace detail {
constexpr std::size_t own_bvh_kernel_count() {
  std::size_t n = 0;
  for (const KernelInfo& row : kKernelTable) n += row.structure == KernelStructure::own_bvh;
  return n;
}
constexpr bool every_id_has_one_row() {
  for (std::size_t i = 0; i < std::size(kKernelTable); ++i)
    if (std::size_t(kKernelTable[i].id) != i) return false;
  return true;
}
static_assert(every_id_has_one_row(), "kKernelTable lists the KernelId values once each, in order");
}  // namespace detail

// Every kernel in float, in table order.
inline constexpr auto kAllKernels = [] {
  std::array<KernelKind, std::size(kKernelTable)> out;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = kKernelTable[i].id;
  return out;
}();

// The kernels on Pierce's BVH in double precision. Not in kAllKernels: they answer for the double
// input, which can differ from the float kernels' answers where it is not representable in float.
inline constexpr auto kDoubleKernels = [] {
  std::array<KernelKind, detail::own_bvh_kernel_count()> out;
  std::size_t n = 0;
  for (const KernelInfo& row : kKernelTable)
    if (row.structure == KernelStructure::own_bvh) out[n++] = KernelKind(row.id, Precision::float64);
  return out;
}();

// "queue", or "queue-d" in double precision.
std::string_view kernel_name(KernelKind k);
std::optional<KernelKind> parse_kernel(std::string_view name);

}  // namespace pierce
