#include "pierce/analysis/gqa.h"

#include "pierce/analysis/tie_distance.h"
#include "pierce/parallel_for_items.h"
#include "partition_walker.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Converged needs the estimated standard error of the volume times this within the tolerance
// (3: a normal error exceeds it with probability 0.3%; the estimate itself errs on the high side).
constexpr double kErrorsPerStdError = 3.0;

std::uint64_t pair_key(std::uint32_t x, std::uint32_t y) {
  if (x > y) std::swap(x, y);
  return (std::uint64_t(x) << 32) | y;
}

struct PairAcc {
  std::uint64_t count = 0;
  double max_depth = 0;
  Vec3d at;
  double depth_sum = 0;  // sum of interval lengths (overlap volume = depth_sum * cell area)
};

void add_interval(PairAcc& p, double depth, Vec3d at) {
  ++p.count;
  p.depth_sum += depth;
  if (depth > p.max_depth) p.max_depth = depth, p.at = at;  // strict: the first ray keeps ties
}

void join_pair(PairAcc& into, const PairAcc& from) {
  into.count += from.count;
  into.depth_sum += from.depth_sum;
  if (from.max_depth > into.max_depth) into.max_depth = from.max_depth, into.at = from.at;
}

// Sums over the rays of one axis. Items are the solids, then the regions.
struct AxisAcc {
  std::vector<double> length;     // total length inside
  std::vector<Vec3d> moment;      // sum of length * interval midpoint
  std::vector<std::uint64_t> crossings;
  // Sum over neighbouring ray pairs of the squared difference of their lengths inside: the
  // collapsed-strata variance estimate of the jittered grid's length sum (see run_gqa).
  std::vector<double> pair_sq;
  std::map<std::uint64_t, PairAcc> overlaps, gaps;
  std::uint64_t unmatched = 0, unclosed = 0;

  explicit AxisAcc(std::size_t items = 0)
      : length(items, 0.0), moment(items), crossings(items, 0), pair_sq(items, 0.0) {}

  void join(const AxisAcc& o) {
    for (std::size_t i = 0; i < length.size(); ++i) {
      length[i] += o.length[i];
      moment[i] = moment[i] + o.moment[i];
      crossings[i] += o.crossings[i];
      pair_sq[i] += o.pair_sq[i];
    }
    for (const auto& [k, p] : o.overlaps) join_pair(overlaps[k], p);
    for (const auto& [k, p] : o.gaps) join_pair(gaps[k], p);
    unmatched += o.unmatched;
    unclosed += o.unclosed;
  }
};

// Length of one ray inside one item (solid or region).
struct ItemLength {
  std::size_t item;
  double length;
};

// Sorts by item and merges entries of the same item.
void merge_lengths(std::vector<ItemLength>& v) {
  std::sort(v.begin(), v.end(), [](const ItemLength& a, const ItemLength& b) { return a.item < b.item; });
  std::size_t out = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (out > 0 && v[out - 1].item == v[k].item) v[out - 1].length += v[k].length;
    else v[out++] = v[k];
  }
  v.resize(out);
}

// Adds (a - b)^2 per item over two merged per-ray length lists.
void add_pair_sq(const std::vector<ItemLength>& a, const std::vector<ItemLength>& b, std::vector<double>& sq) {
  std::size_t x = 0, y = 0;
  while (x < a.size() || y < b.size()) {
    if (y == b.size() || (x < a.size() && a[x].item < b[y].item)) sq[a[x].item] += a[x].length * a[x].length, ++x;
    else if (x == a.size() || b[y].item < a[x].item) sq[b[y].item] += b[y].length * b[y].length, ++y;
    else {
      const double d = a[x].length - b[y].length;
      sq[a[x].item] += d * d, ++x, ++y;
    }
  }
}

struct OpenPair {
  std::uint64_t key;
  double t_in;
};

struct Worker : PartitionWalker {
  std::vector<CsgEvaluator> evals;
  std::vector<OpenPair> open, next_open;
  std::array<std::vector<ItemLength>, 2> lengths;  // of the two rays of a neighbour pair

  Worker(const Accel& accel, const GqaOptions& o) : PartitionWalker(accel, o.kernel) {
    for (const CsgExpr& e : o.regions) evals.emplace_back(e, accel.scene().geometries().size());
  }
};

// splitmix64: a fixed, portable hash (std:: distributions differ between standard libraries).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A 32-bit half of a hash as a position strictly inside (0, 1): never on a cell boundary.
double unit(std::uint64_t bits32) { return (double(bits32 & 0xffffffffu) + 0.5) * 0x1.0p-32; }

struct Grid {
  int axis = 0, n = 0;
  Vec3d lo, ext;
  double margin = 0;
  double cell_area = 0;
  std::uint64_t jitter_key = 0;  // 0: rays through the cell centres; else seeds each ray's position in its cell

  // The ray of cell k; `centre` gets the cell centre's point on the ray's entry plane.
  Ray ray(std::size_t k, Vec3d& centre) const {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const std::size_t i = k % std::size_t(n), j = k / std::size_t(n);
    Ray r;
    r.dir[std::size_t(axis)] = 1.0;
    r.org[std::size_t(axis)] = lo[std::size_t(axis)] - margin;
    double fu = 0.5, fv = 0.5;
    if (jitter_key != 0) {
      const std::uint64_t h = mix(jitter_key ^ k);
      fu = unit(h), fv = unit(h >> 32);
    }
    r.org[std::size_t(u)] = lo[std::size_t(u)] + ext[std::size_t(u)] * ((double(i) + fu) / double(n));
    r.org[std::size_t(v)] = lo[std::size_t(v)] + ext[std::size_t(v)] * ((double(j) + fv) / double(n));
    centre = r.org;
    centre[std::size_t(u)] = lo[std::size_t(u)] + ext[std::size_t(u)] * ((double(i) + 0.5) / double(n));
    centre[std::size_t(v)] = lo[std::size_t(v)] + ext[std::size_t(v)] * ((double(j) + 0.5) / double(n));
    return r;
  }
};

bool contains_sorted(std::span<const std::uint32_t> s, std::uint32_t g) { return std::binary_search(s.begin(), s.end(), g); }

void close_pair(AxisAcc& acc, const OpenPair& p, double t_out, const Ray& ray) {
  add_interval(acc.overlaps[p.key], t_out - p.t_in, ray.org + ray.dir * p.t_in);
}

// Moments take the cross-section coordinates of the cell centre, not of the jittered ray: that is
// exact for every cell the solid fills, where the ray's own position would only add noise.
void measure_ray(Worker& w, const GqaOptions& o, const Ray& ray, Vec3d centre, std::size_t solid_count, double tie,
                 AxisAcc& acc, std::vector<ItemLength>& lengths) {
  lengths.clear();
  w.hits.clear();
  collect_hits(w.it, ray, 0, w.hits);
  w.builder.build(w.hits, w.parts);
  snap_partitions(w.parts, tie);  // unit direction: t is a length
  acc.unmatched += w.parts.unmatched_leaves;
  acc.unclosed += w.parts.unclosed;
  const auto& ps = w.parts.partitions;
  w.open.clear();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const Partition& p = ps[k];
    const auto solids = w.parts.solids_of(p);
    const bool adjacent = k > 0 && ps[k - 1].t_out == p.t_in;
    const auto prev = k > 0 ? w.parts.solids_of(ps[k - 1]) : std::span<const std::uint32_t>{};
    const double len = p.t_out - p.t_in;  // |dir| = 1
    const Vec3d mid = centre + ray.dir * (0.5 * (p.t_in + p.t_out));
    for (std::uint32_t g : solids) {
      acc.length[g] += len;
      acc.moment[g] = acc.moment[g] + mid * len;
      lengths.push_back({g, len});
      if (!adjacent || !contains_sorted(prev, g)) acc.crossings[g] += 2;
    }
    // Overlap runs: a pair's run continues through adjacent partitions that both contain it.
    w.next_open.clear();
    for (std::size_t x = 0; x < solids.size(); ++x)
      for (std::size_t y = x + 1; y < solids.size(); ++y) {
        const std::uint64_t key = pair_key(solids[x], solids[y]);
        double t_in = p.t_in;
        if (adjacent)
          for (const OpenPair& op : w.open)
            if (op.key == key) t_in = op.t_in;
        w.next_open.push_back({key, t_in});
      }
    for (const OpenPair& op : w.open) {
      const bool carried = adjacent && std::any_of(w.next_open.begin(), w.next_open.end(),
                                                   [&](const OpenPair& q) { return q.key == op.key; });
      if (!carried) close_pair(acc, op, ps[k - 1].t_out, ray);
    }
    std::swap(w.open, w.next_open);
    // Gaps: air before this partition, bounded by different solids.
    if (k > 0 && ps[k - 1].t_out < p.t_in) {
      const double size = p.t_in - ps[k - 1].t_out;
      if (size > o.gap_min && size <= o.gap_max)
        for (std::uint32_t x : prev)
          for (std::uint32_t y : solids)
            if (x != y) add_interval(acc.gaps[pair_key(x, y)], size, ray.org + ray.dir * ps[k - 1].t_out);
    }
  }
  for (const OpenPair& op : w.open) close_pair(acc, op, ps.back().t_out, ray);

  for (std::size_t r = 0; r < w.evals.size(); ++r) {
    w.evals[r].evaluate(w.parts, w.intervals);
    const std::size_t item = solid_count + r;
    for (const CsgInterval& iv : w.intervals) {
      const double len = iv.t_out - iv.t_in;
      acc.length[item] += len;
      acc.moment[item] = acc.moment[item] + (centre + ray.dir * (0.5 * (iv.t_in + iv.t_out))) * len;
      acc.crossings[item] += 2;
      lengths.push_back({item, len});
    }
  }
  merge_lengths(lengths);
}

struct PassResult {
  std::array<AxisAcc, 3> axes;
  std::array<double, 3> cell_area{};
  bool completed = true;
};

PassResult run_pass(const Accel& accel, const GqaOptions& o, int n, std::size_t items,
                    tbb::enumerable_thread_specific<Worker>& workers, const GqaProgress& progress) {
  const BBoxd& b = accel.scene().bounds();
  const std::size_t solid_count = accel.scene().geometries().size();
  const std::size_t per_axis = std::size_t(n) * std::size_t(n);
  const double tie = tie_distance(accel.scene(), o.tie_tolerance_rel);
  PassResult res;
  // A reduction (deterministic sums), not parallel_for_items; progress and cancellation the same way.
  const Progress pass_progress = [&](std::size_t d, std::size_t t) { return !progress || progress(n, d, t); };
  ProgressTracker tracker(3 * per_axis, pass_progress);
  for (int axis = 0; axis < 3; ++axis) {
    Grid g;
    g.axis = axis;
    g.n = n;
    g.lo = b.lo;
    g.ext = b.extent();
    g.margin = 0.05 * accel.scene().scale();
    if (o.jitter) g.jitter_key = mix(mix(mix(o.seed) ^ std::uint64_t(n)) ^ std::uint64_t(axis)) | 1;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    g.cell_area = g.ext[std::size_t(u)] * g.ext[std::size_t(v)] / double(per_axis);
    res.cell_area[std::size_t(axis)] = g.cell_area;
    // Work units are pairs of neighbouring cells along u (cells 2a and 2a+1 of a row; with n odd
    // the row's last cell has no partner). Deterministic split and join order: the sums do not
    // depend on the thread count.
    const std::size_t pairs_per_row = (std::size_t(n) + 1) / 2;
    res.axes[std::size_t(axis)] = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, std::size_t(n) * pairs_per_row, std::max<std::size_t>(32, pairs_per_row)),
        AxisAcc(items),
        [&](const tbb::blocked_range<std::size_t>& r, AxisAcc acc) {
          if (tracker.stopped()) return acc;
          Worker& w = workers.local();
          Vec3d centre;
          std::size_t rays = 0;
          for (std::size_t unit = r.begin(); unit != r.end(); ++unit) {
            const std::size_t i = 2 * (unit % pairs_per_row), j = unit / pairs_per_row;
            const std::size_t cells = i + 1 < std::size_t(n) ? 2 : 1;
            for (std::size_t c = 0; c < cells; ++c) {
              const Ray ray = g.ray(j * std::size_t(n) + i + c, centre);
              measure_ray(w, o, ray, centre, solid_count, tie, acc, w.lengths[c]);
            }
            if (cells == 2) add_pair_sq(w.lengths[0], w.lengths[1], acc.pair_sq);
            rays += cells;
          }
          tracker.add(rays);
          return acc;
        },
        [](AxisAcc a, const AxisAcc& c) {
          a.join(c);
          return a;
        },
        tbb::simple_partitioner());
    if (tracker.stopped()) break;
  }
  res.completed = !tracker.stopped();
  return res;
}

// Per-item quantities of one pass.
void quantities(const PassResult& pass, std::size_t item, GqaQuantities& q) {
  double vol = 0, variance = 0;
  Vec3d moment{};
  q.crossings = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    const AxisAcc& acc = pass.axes[a];
    q.axis_volume[a] = acc.length[item] * pass.cell_area[a];
    vol += q.axis_volume[a];
    moment = moment + acc.moment[item] * pass.cell_area[a];
    q.crossings += acc.crossings[item];
    variance += acc.pair_sq[item] * pass.cell_area[a] * pass.cell_area[a];
  }
  q.volume = vol / 3.0;
  q.std_error = std::sqrt(variance) / 3.0;
  q.centroid = vol > 0 ? moment * (1.0 / vol) : Vec3d{kNaN, kNaN, kNaN};
}

std::vector<GqaPair> pairs(const PassResult& pass, bool overlaps) {
  std::map<std::uint64_t, GqaPair> out;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto& m = overlaps ? pass.axes[a].overlaps : pass.axes[a].gaps;
    for (const auto& [key, acc] : m) {
      GqaPair& p = out[key];
      p.a = std::uint32_t(key >> 32);
      p.b = std::uint32_t(key & 0xffffffffu);
      p.count += acc.count;
      if (acc.max_depth > p.max_depth) p.max_depth = acc.max_depth, p.at = acc.at;
      p.axis_max_depth[a] = acc.max_depth;
      if (overlaps) p.volume += acc.depth_sum * pass.cell_area[a] / 3.0;
    }
  }
  std::vector<GqaPair> v;
  for (auto& [key, p] : out) {
    p.penetration = kInf;
    for (double d : p.axis_max_depth)
      if (d > 0) p.penetration = std::min(p.penetration, d);
    if (!std::isfinite(p.penetration)) p.penetration = 0;
    v.push_back(p);
  }
  return v;
}

}  // namespace

int gqa_auto_start_n(const Scene& scene, int max_n) {
  const Vec3d ext = scene.bounds().extent();
  const double scene_ext = scene.bounds().empty() ? 0.0 : std::max({ext.x, ext.y, ext.z});
  double thinnest = kInf;
  for (const Geometry& g : scene.geometries()) {
    BBoxd b;
    for (const Tri& t : g.triangles)
      for (std::uint32_t i : t) b.extend(g.vertices[i]);
    if (b.empty()) continue;
    for (int a = 0; a < 3; ++a)
      if (b.extent()[std::size_t(a)] > 0) thinnest = std::min(thinnest, b.extent()[std::size_t(a)]);
  }
  double n = 16;
  // (The factor below 1 keeps a ratio like 80.00000000001 from rounding up to 81.)
  if (std::isfinite(thinnest) && scene_ext > 0) n = std::max(n, std::ceil(4.0 * scene_ext / thinnest * (1 - 1e-9)));
  // At least two passes fit below max_n, so convergence can be judged.
  return int(std::clamp(n, 1.0, std::max(1.0, double(max_n / 2))));
}

GqaResult run_gqa(const Accel& accel, const GqaOptions& o, const GqaProgress& progress) {
  if (!(o.tolerance > 0)) throw std::invalid_argument("gqa: tolerance must be > 0");
  if (o.max_n < 1) throw std::invalid_argument("gqa: max_n must be >= 1");
  if (o.start_n < 0) throw std::invalid_argument("gqa: start_n must be >= 0");
  if (!is_exact(o.kernel)) throw std::invalid_argument("gqa needs an exact kernel");
  if (!(o.gap_min >= 0) || !(o.gap_max >= o.gap_min)) throw std::invalid_argument("gqa: need 0 <= gap_min <= gap_max");
  if (!(o.tie_tolerance_rel >= 0)) throw std::invalid_argument("gqa: tie tolerance must be >= 0");

  const Scene& scene = accel.scene();
  const std::size_t solid_count = scene.geometries().size();
  const std::size_t items = solid_count + o.regions.size();
  GqaResult result;
  result.tolerance = o.tolerance;
  result.seed = o.jitter ? o.seed : 0;
  result.solids.resize(solid_count);
  for (std::uint32_t g = 0; g < solid_count; ++g) {
    result.solids[g].name = scene.geometry(g).name;
    result.solids[g].geoms = {g};
  }
  result.regions.resize(o.regions.size());
  for (std::size_t r = 0; r < o.regions.size(); ++r) {
    result.regions[r].name = o.regions[r].text;
    result.regions[r].geoms = o.regions[r].solids();
  }
  if (scene.bounds().empty()) {
    result.converged = true;
    return result;
  }
  const Vec3d ext = scene.bounds().extent();
  const double diag = scene.scale();
  const double box_volume = std::max(ext.x, 1e-300) * std::max(ext.y, 1e-300) * std::max(ext.z, 1e-300);
  const double floor = 1e-12 * box_volume;  // volumes below this count as zero

  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker(accel, o); });
  std::vector<GqaQuantities> prev;
  int n = o.start_n > 0 ? std::min(o.start_n, o.max_n) : gqa_auto_start_n(scene, o.max_n);
  for (;; n *= 2) {
    const auto t0 = std::chrono::steady_clock::now();
    PassResult pass = run_pass(accel, o, n, items, workers, progress);
    if (!pass.completed) {
      result.completed = false;
      break;
    }
    std::vector<GqaQuantities> now(items);
    for (std::size_t i = 0; i < items; ++i) {
      now[i] = i < solid_count ? result.solids[i] : result.regions[i - solid_count];
      quantities(pass, i, now[i]);
    }
    GqaPass info;
    info.n = n;
    info.rays = 3 * std::uint64_t(n) * std::uint64_t(n);
    info.worst_change = prev.empty() ? kInf : 0.0;
    for (std::size_t i = 0; i < items && !prev.empty(); ++i) {
      GqaQuantities& q = now[i];
      const double scale = std::max(q.volume, floor);
      double c = std::abs(q.volume - prev[i].volume) / scale;
      q.change = c;
      for (double av : q.axis_volume) c = std::max(c, std::abs(av - q.volume) / scale);
      if (o.jitter) c = std::max(c, kErrorsPerStdError * q.std_error / scale);
      const bool had = std::isfinite(prev[i].centroid.x), has = std::isfinite(q.centroid.x);
      if (had != has) c = kInf;
      else if (has) c = std::max(c, length(q.centroid - prev[i].centroid) / diag);
      if (c > info.worst_change) info.worst_change = c, info.worst = q.name;
    }
    if (prev.empty())
      for (GqaQuantities& q : now) q.change = kInf;
    info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    result.passes.push_back(info);

    for (std::size_t i = 0; i < items; ++i) (i < solid_count ? result.solids[i] : result.regions[i - solid_count]) = now[i];
    result.overlaps = pairs(pass, true);
    result.gaps = pairs(pass, false);
    result.unmatched_leaves = result.unclosed = 0;
    for (const AxisAcc& a : pass.axes) result.unmatched_leaves += a.unmatched, result.unclosed += a.unclosed;
    result.n = n;
    prev = std::move(now);
    if (info.worst_change <= o.tolerance) {
      result.converged = true;
      break;
    }
    if (n > o.max_n / 2) break;
  }
  return result;
}

}  // namespace pierce::analysis
