// pierce_bench_kernels: the table of Wald et al. 2019, Fig. 3, for Pierce's kernels.
// For each scene and kernel, the rays/s of getting the first N hits of every ray
// (N = 1, 5, 15, all), against reference rows of plain Embree code (embree_reference.h) on the
// same rays in the same run: native first hit, first hit with RTC_SCENE_FLAG_ROBUST, the
// all-hits filter (sorted, duplicates removed) and lexicographic restart. Every row also shows
// how many rays it got wrong against the exact kernels. A benchmark, not a test: it reports, it
// never asserts a speed.
#include <embree3/rtcore.h>
#include <oneapi/tbb/version.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <limits>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <numeric>
#include <random>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_scenes.h"
#include "bench_timing.h"
#include "embree_reference.h"
#include "pierce/bvh_builder.h"
#include "pierce/kernel.h"
#include "pierce/prefetch_mode.h"
#include "pierce/render/false_colour.h"

namespace pierce::bench {
namespace {

using nlohmann::json;

// ---------------------------------------------------------------- machine

// ---------------------------------------------------------------- measuring

// What a pass over the rays found: totals that do not depend on the thread schedule, so
// every kernel's result can be compared with every other's.
struct Tally {
  std::uint64_t hits = 0;
  std::uint64_t hash = 0;  // sum over rays of an order-sensitive hash of the ray's hit list
  std::uint64_t rays_hit = 0;
  std::uint64_t max_per_ray = 0;
  Tally& operator+=(const Tally& o) {
    hits += o.hits, hash += o.hash, rays_hit += o.rays_hit;
    max_per_ray = std::max(max_per_ray, o.max_per_ray);
    return *this;
  }
  bool operator==(const Tally&) const = default;
};

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x ^= x >> 30, x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27, x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Adds one ray's hits to `t`; returns the ray's hash (0 for no hits), which identifies its hit list.
template <typename HitRange>
std::uint64_t tally_ray(Tally& t, const HitRange& hits) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (const Hit& hit : hits) h = mix(h ^ ((std::uint64_t(hit.geom) << 32) | hit.prim));
  if (hits.empty()) h = 0;
  t.hits += hits.size();
  t.hash += h;
  t.rays_hit += hits.empty() ? 0 : 1;
  t.max_per_ray = std::max<std::uint64_t>(t.max_per_ray, hits.size());
  return h;
}

struct Cell {
  std::size_t max_hits = 0;  // 0 = all
  std::vector<double> seconds;
  double median_seconds = 0;
  // The cells behind the quoted ratios (chunked_groups()): their repetitions timed again,
  // interleaved by chunk of rays (time_by_chunk()); empty in every other cell.
  std::vector<double> paired_seconds;
  double paired_median_seconds = 0;
  // N = 1 and all, own-BVH kernels and `epsilon`: those repetitions were paired with plain
  // Embree's first hit or all-hits filter, whose times of the same chunks these are.
  std::vector<double> partner_seconds;
  double partner_median_seconds = 0;
  // With more than one thread, N = 1 and all, own-BVH kernels and the two plain Embree rows: the
  // cell on one thread and on all of the run's, chunk by chunk (time_scaling_by_chunk()).
  std::vector<double> one_thread_seconds, all_threads_seconds;
  Tally tally;
  bool deterministic = true;  // every repetition found the same hits
  Counters counters;          // summed over the timed repetitions
  std::vector<std::uint64_t> ray_hash;  // per ray, from the last repetition
  std::vector<std::uint32_t> ray_hits;  // hits per ray, from the last repetition
  std::optional<std::uint64_t> wrong_rays;  // rays whose hit list differs from the exact kernels'
  std::optional<std::uint64_t> odd_rays;    // closed scenes, all hits: rays with an odd number of hits
};

// A cell's work, kept until every row is set up: the repetitions of all cells are then interleaved
// (every cell's first repetition, then every cell's second, ...), so that a change of the machine's
// load during the run falls on every row alike and the ratios of the medians stay fair.
struct CellJob {
  std::function<Tally(Cell&, std::size_t, std::size_t)> pass;  // rays [begin, end); fills the cell's per-ray arrays
  std::function<Counters()> counters;                          // summed over the cell's iterators
  // Gives the cell's iterators and their buffers new addresses (time_by_chunk(), relocator()).
  std::function<void()> relocate;
};

struct Row {
  std::string kernel;
  bool exact = true;
  bool reference = false;
  std::optional<KernelKind> kind;  // empty for the plain Embree reference rows
  std::optional<PrefetchMode> prefetch;  // the own-BVH kernel rows: the prefetch mode they ran in
  bool counted = false;            // the kernel's counting variant ran: its cells hold counters
  std::vector<Cell> cells;
  std::vector<CellJob> jobs;  // one per cell
};

struct Settings {
  std::vector<std::size_t> columns{1, 5, 15, 0};
  int reps = 3;
  int build_reps = 3;  // builds of each scene, Pierce's and Embree's alternating; medians compared
  bool count = false;  // time the kernels' counting variants and print their counters
  std::string heatmap_dir;  // non-empty: write traversal heat maps of each scene there
  bool force = false;       // overwrite existing heat maps
  // The prefetch modes the own-BVH kernel rows run in (--prefetch): one row per kernel and mode,
  // timed in the same interleaved repetitions, so the modes are compared on the same rays in the
  // same run. The Embree-based rows do not traverse Pierce's BVH and run once.
  std::vector<PrefetchMode> prefetch{prefetch_mode()};
};

// The prefetch modes of the run, "auto" or "always,never".
std::string prefetch_list_text(const Settings& st) {
  std::string s;
  for (const PrefetchMode m : st.prefetch) s += (s.empty() ? "" : ",") + std::string(enum_name(m));
  return s;
}

// A row's name: the kernel's, and its prefetch mode where the run compares more than one.
std::string row_name(std::string_view kernel, std::optional<PrefetchMode> mode, const Settings& st) {
  std::string name(kernel);
  if (mode && st.prefetch.size() > 1) name += " [" + std::string(enum_name(*mode)) + "]";
  return name;
}

// Every cell of every row: a warm-up on the first eighth of the rays, then `reps` timed passes
// over all of them, interleaved across cells (see CellJob), each after an untimed pass over the
// first sixteenth.
void time_rows(std::vector<Row>& rows, std::size_t ray_count, int reps) {
  std::vector<Counters> before;
  for (Row& row : rows)
    for (std::size_t c = 0; c < row.cells.size(); ++c) {
      Cell& cell = row.cells[c];
      cell.ray_hash.assign(ray_count, 0);
      cell.ray_hits.assign(ray_count, 0);
      row.jobs[c].pass(cell, 0, std::max<std::size_t>(1, ray_count / 8));
      before.push_back(row.jobs[c].counters());
    }
  // Counts of the untimed passes below, taken out of the cells' counters afterwards.
  std::vector<Counters> untimed(before.size());
  for (int r = 0; r < reps; ++r) {
    std::size_t k = 0;
    for (Row& row : rows)
      for (std::size_t c = 0; c < row.cells.size(); ++c, ++k) {
        Cell& cell = row.cells[c];
        // Every cell starts with its own data in the caches: the rows use different structures
        // (Embree's scenes, Pierce's BVH), and without this the first row of each repetition would
        // run on data the previous row evicted.
        const Counters warm_from = row.jobs[c].counters();
        row.jobs[c].pass(cell, 0, std::max<std::size_t>(1, ray_count / 16));
        untimed[k] += row.jobs[c].counters() - warm_from;
        const auto t0 = Clock::now();
        const Tally t = row.jobs[c].pass(cell, 0, ray_count);
        cell.seconds.push_back(seconds_since(t0));
        if (r == 0) cell.tally = t;
        else if (!(t == cell.tally)) cell.deterministic = false;
      }
  }
  std::size_t k = 0;
  for (Row& row : rows)
    for (std::size_t c = 0; c < row.cells.size(); ++c, ++k) {
      Cell& cell = row.cells[c];
      const Counters after = row.jobs[c].counters() - untimed[k];
      cell.counters = {after.node_tests - before[k].node_tests, after.traversal_steps - before[k].traversal_steps,
                       after.prim_tests - before[k].prim_tests, after.valid_hits - before[k].valid_hits,
                       after.leaf_visits - before[k].leaf_visits};
      cell.median_seconds = median(cell.seconds);
    }
}

// The rays of one chunk (time_by_chunk()): 8192 per thread, so that the end of each parallel
// chunk (one thread finishing before the other) costs little, or 1/32 of the rays where that is more.
std::size_t chunk_rays(std::size_t ray_count) {
  const auto threads =
      std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return std::max<std::size_t>(8192 * threads, (ray_count + 31) / 32);
}

// The ratios the docs quote need finer timing than time_rows() gives: it times the two cells of a
// ratio tens of milliseconds apart, and on a shared machine their ratio moves by tens of per cent
// from repetition to repetition (the "by repetition" ranges of `pierce_bench_kernels --reps 20`
// show it). So the cells behind those ratios are timed again, group by group, chunk by chunk: each
// chunk of rays through every cell of the group, in a new order per chunk (a fixed order would have
// each cell always follow the same one, and start on what that one left in the branch predictors
// and caches). A change of the machine's speed then falls on all of them alike within
// milliseconds. The groups (chunked_groups()):
//  - `restart`, `queue` and `filter` at N = 5 and 15 (queue / min(restart, filter)). Where no ray
//    holds N hits the three do the same work, so the ratio is 1 give or take the timing's noise.
//  - Pairs: at N = 1 every exact own-BVH kernel and `epsilon`, each with plain Embree's first hit;
//    for all hits every exact own-BVH kernel with plain Embree's all-hits filter.
// Pairs, not one group per column: cells that read different structures (Embree's scenes,
// Pierce's BVH) evict each other's data, and in a group of several cells on Pierce's BVH and one on
// Embree's scene, the Embree cell would start nearly every chunk on evicted data and every
// kernel's ratio to it would read low. In a pair, either cell's chunk follows the other's. And
// every timed chunk follows an untimed pass of the same cell over the chunk's first sixteenth, as
// each of time_rows()' passes follows one over the first sixteenth of the rays.
// Each group runs kPairedRepsPerRep times the table's repetitions, every repetition on iterators
// at new addresses (CellJob::relocate): more repetitions narrow what varies between repetitions,
// the new addresses an offset that comes with where a cell's memory sits and would otherwise hold
// for a whole run. The "same-work control filter N = 15 / N = 5" that `pierce_bench_kernels
// --scene blob` prints checks both: the two cells do the same work there, so it reads 1 within
// the resolution of the quoted ratios (0.985-1.014 on blob and on CGAL's meshes via --mesh).
constexpr int kPairedRepsPerRep = 4;
int paired_reps(const Settings& st) { return kPairedRepsPerRep * st.reps; }

// An exact kernel on Pierce's own BVH (restart, queue, nodecull, filter, buffered).
bool exact_own(const Row& row) { return row.exact && !row.reference && row.kind && !uses_embree(*row.kind); }

struct ChunkedCell {
  Row* row;
  std::size_t column;
  bool one_thread = false;  // the cell's passes on the calling thread alone (time_scaling_by_chunk())
  Cell& cell() const { return row->cells[column]; }
};

// A group of time_by_chunk(). With a partner, the group is {partner, cells[0]}, and the partner's
// times go to cells[0]'s partner_seconds.
struct ChunkedGroup {
  std::vector<ChunkedCell> cells;
  std::optional<ChunkedCell> partner;
};

std::optional<ChunkedCell> cell_of(Row& row, std::size_t max_hits) {
  for (std::size_t c = 0; c < row.cells.size(); ++c)
    if (row.cells[c].max_hits == max_hits) return ChunkedCell{&row, c};
  return std::nullopt;
}

// The groups of time_by_chunk().
std::vector<ChunkedGroup> chunked_groups(std::vector<Row>& rows, const Settings& st) {
  std::vector<ChunkedGroup> groups;
  ChunkedGroup culling;
  for (const PrefetchMode mode : st.prefetch)
    for (const char* kernel : {"restart", "queue", "filter"})
      for (Row& row : rows)
        if (row.kernel == row_name(kernel, mode, st))
          for (const std::size_t n : {std::size_t(5), std::size_t(15)})
            if (const auto c = cell_of(row, n)) culling.cells.push_back(*c);
  if (culling.cells.size() > 1) groups.push_back(std::move(culling));
  for (const std::size_t n : {std::size_t(1), std::size_t(0)}) {
    const char* plain = n == 1 ? "embree first hit" : "embree all-hits";
    std::optional<ChunkedCell> partner;
    for (Row& row : rows)
      if (row.kernel == plain) partner = cell_of(row, n);
    if (!partner) continue;
    for (Row& row : rows) {
      if (exact_own(row) || (n == 1 && row.kind == KernelKind::epsilon))
        if (const auto c = cell_of(row, n)) groups.push_back({{*c}, partner});
    }
  }
  return groups;
}

// One repetition of a group: its cells' seconds, summed over the chunks.
std::vector<double> time_group_by_chunk(const std::vector<ChunkedCell>& cells, std::size_t ray_count, std::mt19937& shuffle_rng) {
  const std::size_t chunk = chunk_rays(ray_count);
  std::vector<std::size_t> order(cells.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::vector<double> seconds(cells.size(), 0.0);
  std::vector<Tally> tallies(cells.size());
  tbb::task_arena one_thread(1);
  auto pass = [&one_thread](const ChunkedCell& c, std::size_t begin, std::size_t end) {
    if (c.one_thread) return one_thread.execute([&] { return c.row->jobs[c.column].pass(c.cell(), begin, end); });
    return c.row->jobs[c.column].pass(c.cell(), begin, end);
  };
  // Every repetition on iterators at new addresses: where a cell's memory lands can make it a few
  // per cent slower for as long as it stays there, so the median is taken over as many layouts as
  // repetitions.
  for (const ChunkedCell& c : cells) c.row->jobs[c.column].relocate();
  for (std::size_t begin = 0; begin < ray_count; begin += chunk) {
    const std::size_t end = std::min(ray_count, begin + chunk);
    std::shuffle(order.begin(), order.end(), shuffle_rng);
    for (const std::size_t o : order) {
      pass(cells[o], begin, begin + std::max<std::size_t>(1, (end - begin) / 16));  // untimed: see above
      const auto t0 = Clock::now();
      tallies[o] += pass(cells[o], begin, end);
      seconds[o] += seconds_since(t0);
    }
  }
  // The same hits as the table's repetitions (time_rows()), chunk by chunk.
  for (std::size_t o = 0; o < cells.size(); ++o)
    if (!(tallies[o] == cells[o].cell().tally)) cells[o].cell().deterministic = false;
  return seconds;
}

void time_by_chunk(std::vector<Row>& rows, std::size_t ray_count, const Settings& st) {
  std::mt19937 shuffle_rng(12345);  // fixed: every run shuffles alike
  for (const ChunkedGroup& group : chunked_groups(rows, st)) {
    std::vector<ChunkedCell> cells = group.cells;
    if (group.partner) cells.push_back(*group.partner);
    for (int r = 0; r < paired_reps(st); ++r) {
      const std::vector<double> seconds = time_group_by_chunk(cells, ray_count, shuffle_rng);
      for (std::size_t o = 0; o < group.cells.size(); ++o) group.cells[o].cell().paired_seconds.push_back(seconds[o]);
      if (group.partner) group.cells.front().cell().partner_seconds.push_back(seconds.back());
    }
    for (const ChunkedCell& c : group.cells) {
      c.cell().paired_median_seconds = median(c.cell().paired_seconds);
      if (group.partner) c.cell().partner_median_seconds = median(c.cell().partner_seconds);
    }
  }
}

// Speed-up on all threads over one, from one run: runs at --threads 1 and 2 taken minutes apart
// differ by more than the speed-up's resolution (set against two 1-thread runs, the same 2-thread
// run reads speed-ups up to a quarter apart), and plain Embree's rows move as far. So a run with more than
// one thread also times each cell of interest on one thread (a task_arena of one) and on all, as a
// pair chunk by chunk, like the pairs above: the own-BVH kernels and plain Embree's first hit at
// N = 1, and the own-BVH kernels and plain Embree's all-hits filter at "all". The pairs take turns
// repetition by repetition, in a new order each time, not each pair's repetitions back to back:
// the second thread gives more in some stretches of a run than in others, and taking turns
// spreads such a stretch over every cell, Pierce's and plain Embree's alike. The "by repetition"
// ranges of `pierce_bench_kernels --threads 2` show how far the stretches reach.
void time_scaling_by_chunk(std::vector<Row>& rows, std::size_t ray_count, const Settings& st) {
  if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) < 2) return;
  std::vector<std::vector<ChunkedCell>> pairs;  // {on one thread, on all}
  for (Row& row : rows)
    for (const std::size_t n : {std::size_t(1), std::size_t(0)}) {
      if (!exact_own(row) && row.kernel != (n == 1 ? "embree first hit" : "embree all-hits")) continue;
      const auto c = cell_of(row, n);
      if (!c) continue;
      ChunkedCell one = *c;
      one.one_thread = true;
      pairs.push_back({one, *c});
    }
  std::mt19937 shuffle_rng(54321);  // fixed: every run shuffles alike
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  for (int r = 0; r < paired_reps(st); ++r) {
    std::shuffle(order.begin(), order.end(), shuffle_rng);
    for (const std::size_t o : order) {
      const std::vector<double> seconds = time_group_by_chunk(pairs[o], ray_count, shuffle_rng);
      Cell& cell = pairs[o][1].cell();
      cell.one_thread_seconds.push_back(seconds[0]);
      cell.all_threads_seconds.push_back(seconds[1]);
    }
  }
}

// Gives a cell's per-thread state new addresses (CellJob::relocate): `state` made anew by `make`
// while the old one still exists, behind a block of a random size that stays allocated, so that
// it lands at new addresses, never at the ones just freed. The calling thread's part is made now;
// other threads make theirs on their next pass.
template <class State, class Make>
std::function<void()> relocator(std::shared_ptr<std::unique_ptr<State>> state, Make make, std::uint32_t seed) {
  auto pads = std::make_shared<std::vector<std::unique_ptr<char[]>>>();
  auto rng = std::make_shared<std::mt19937>(seed);
  return [state, make, pads, rng] {
    pads->push_back(std::make_unique<char[]>(64 * std::uniform_int_distribution<std::size_t>(1, 1024)(*rng)));
    auto fresh = make();
    fresh->local();
    state->swap(fresh);
  };
}

constexpr std::size_t kGrain = 256;

// One reference row of plain Embree code; `query(ray, n, hits)` appends the first n hits (0 = all).
template <typename Query>
Row run_reference(const std::string& name, const std::vector<std::size_t>& columns, const std::vector<Ray>& rays,
                  Query query) {
  Row row{name, false, true, std::nullopt, std::nullopt, false, {}, {}};
  using Buffers = tbb::enumerable_thread_specific<std::vector<Hit>>;
  auto make_buffers = [] { return std::make_unique<Buffers>(); };
  for (const std::size_t n : columns) {
    // The cell's hit buffers, behind one more pointer so that relocate() can replace them.
    auto buffers = std::make_shared<std::unique_ptr<Buffers>>(make_buffers());
    auto pass = [buffers, query, &rays, n](Cell& cell, std::size_t begin, std::size_t end) {
      tbb::enumerable_thread_specific<Tally> local;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, kGrain), [&](const auto& range) {
        Tally& t = local.local();
        std::vector<Hit>& hits = (*buffers)->local();
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          hits.clear();
          query(rays[i], n, hits);
          cell.ray_hash[i] = tally_ray(t, hits);
          cell.ray_hits[i] = std::uint32_t(hits.size());
        }
      });
      return local.combine([](Tally a, const Tally& b) { return a += b; });
    };
    Cell cell;
    cell.max_hits = n;
    row.cells.push_back(std::move(cell));
    row.jobs.push_back({pass, [] { return Counters{}; }, relocator(buffers, make_buffers, std::uint32_t(n) * 7919u + 104729u)});
  }
  return row;
}

std::vector<Row> run_references(const EmbreeReference& plain, const EmbreeReference& robust,
                                const EmbreeReference& filters, const std::vector<Ray>& rays, const Settings& st) {
  if (filters.use() != ReferenceUse::filters)
    throw std::logic_error("run_references: the all-hits and restart rows need a scene made for filters");
  // Copied into each cell's job: the references outlive the timing (they live in run_scene).
  std::vector<Row> rows;
  auto first = [](const EmbreeReference& e) {
    return [&e](const Ray& r, std::size_t, std::vector<Hit>& hits) {
      Hit h;
      if (e.first_hit(r, h)) hits.push_back(h);
    };
  };
  const EmbreeReference* p = &filters;
  rows.push_back(run_reference("embree first hit", {1}, rays, first(plain)));
  rows.push_back(run_reference("embree robust 1st", {1}, rays, first(robust)));
  rows.push_back(run_reference("embree all-hits", st.columns, rays,
                               [p](const Ray& r, std::size_t n, std::vector<Hit>& hits) { p->all_hits(r, n, hits); }));
  rows.push_back(run_reference("embree lex-restart", st.columns, rays,
                               [p](const Ray& r, std::size_t n, std::vector<Hit>& hits) { p->restart_hits(r, n, hits); }));
  return rows;
}

// `mode`: the prefetch mode of an own-BVH kernel's passes (empty for the Embree-based kernels).
Row run_kernel(const Accel& accel, KernelKind kind, std::optional<PrefetchMode> mode, const std::vector<Ray>& rays,
               const Settings& st) {
  Row row{row_name(kernel_name(kind), mode, st), is_exact(kind), false, kind, mode, false, {}, {}};
  struct Worker {
    HitIterator it;
    std::vector<Hit> hits;
  };
  using Workers = tbb::enumerable_thread_specific<Worker>;
  for (const std::size_t n : st.columns) {
    // Fresh iterators per cell so the counters of one cell never mix with another's.
    KernelOptions opts;
    opts.count = row.counted = st.count;
    auto make_workers = [&accel, kind, opts] {
      return std::make_unique<Workers>([&accel, kind, opts] { return Worker{HitIterator(accel, kind, opts), {}}; });
    };
    // The cell's iterators, behind one more pointer so that relocate() can replace them.
    auto workers = std::make_shared<std::unique_ptr<Workers>>(make_workers());
    auto pass = [workers, &rays, n, mode](Cell& cell, std::size_t begin, std::size_t end) {
      // The mode holds for every traversal of this pass, on every thread; the previous one comes
      // back after it.
      const PrefetchMode before = prefetch_mode();
      if (mode) set_prefetch_mode(*mode);
      tbb::enumerable_thread_specific<Tally> local;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, kGrain), [&](const auto& range) {
        Worker& w = (*workers)->local();
        Tally& t = local.local();
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          w.hits.clear();
          collect_hits(w.it, rays[i], n, w.hits);
          cell.ray_hash[i] = tally_ray(t, w.hits);
          cell.ray_hits[i] = std::uint32_t(w.hits.size());
        }
      });
      set_prefetch_mode(before);
      return local.combine([](Tally a, const Tally& b) { return a += b; });
    };
    auto counter_sum = [workers] {
      Counters c;
      for (const Worker& w : **workers) c += w.it.counters();
      return c;
    };
    Cell cell;
    cell.max_hits = n;
    row.cells.push_back(std::move(cell));
    // (Counters of the old iterators are gone after a relocation: time_rows() has taken them already.)
    row.jobs.push_back({pass, counter_sum, relocator(workers, make_workers, std::uint32_t(n) * 7919u + 2 * std::uint32_t(kind.id) + std::uint32_t(kind.precision))});
  }
  return row;
}

// ---------------------------------------------------------------- printing

std::string column_title(std::size_t n) { return n == 0 ? "all" : std::to_string(n) + (n == 1 ? " hit" : " hits"); }

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

constexpr std::size_t kNameWidth = 22;

// `t` left-aligned in `w` columns (at least one space after it).
std::string pad(const std::string& t, std::size_t w) { return t.size() < w ? t + std::string(w - t.size(), ' ') : t + " "; }

double mrays_per_s(const Cell& c, std::size_t rays) { return double(rays) / c.median_seconds * 1e-6; }

struct SceneResult {
  const BenchScene* scene;
  double pierce_build_s = 0;  // what Accel builds for the own-BVH kernels: the 8-wide BVH
  std::size_t pierce_bytes = 0, wide_nodes = 0, leaf_blocks = 0, triangles_in_bvh = 0;
  double embree_build_s = 0, embree_robust_build_s = 0;
  std::size_t embree_bytes = 0;
  std::vector<Row> rows;
  double reference_mrays = 0;
  std::optional<Tally> exact_all;  // the exact kernels' consensus for "all"
  std::vector<std::string> problems;
};

// The exact kernels must agree on every column; the first exact row is the consensus.
void check_agreement(SceneResult& r, const Settings& st) {
  for (std::size_t c = 0; c < st.columns.size(); ++c) {
    const Row* ref = nullptr;
    for (const Row& row : r.rows) {
      if (row.reference) continue;
      const Cell& cell = row.cells[c];
      if (!cell.deterministic)
        r.problems.push_back(row.kernel + " (" + column_title(st.columns[c]) + "): repetitions found different hits");
      if (!row.exact) continue;
      if (!ref) {
        ref = &row;
        if (st.columns[c] == 0) r.exact_all = cell.tally;
      } else if (!(cell.tally == ref->cells[c].tally)) {
        r.problems.push_back(row.kernel + " (" + column_title(st.columns[c]) + ") disagrees with " + ref->kernel + ": " +
                             std::to_string(cell.tally.hits) + " vs " + std::to_string(ref->cells[c].tally.hits) +
                             " hits");
      }
    }
  }
  const long expected = r.scene->expected_hits_per_ray;
  if (expected >= 0 && r.exact_all &&
      r.exact_all->hits != std::uint64_t(expected) * r.scene->rays.size())
    r.problems.push_back("exact kernels found " + std::to_string(r.exact_all->hits) + " hits, the construction has " +
                         std::to_string(std::uint64_t(expected) * r.scene->rays.size()));
}

// Wrong rays of the inexact rows (reference rows and epsilon): hit lists that differ from the first
// exact row's in the same column. On closed scenes, rays with an odd number of hits ("all").
void count_wrong_rays(SceneResult& r) {
  const Row* exact = nullptr;
  for (const Row& row : r.rows)
    if (row.exact && !row.reference) {
      exact = &row;
      break;
    }
  for (Row& row : r.rows) {
    for (Cell& cell : row.cells) {
      if (r.scene->closed && cell.max_hits == 0) {
        std::uint64_t odd = 0;
        for (const std::uint32_t n : cell.ray_hits) odd += n % 2;
        cell.odd_rays = odd;
      }
      if (exact == nullptr || row.exact) continue;
      const auto it = std::find_if(exact->cells.begin(), exact->cells.end(),
                                   [&](const Cell& e) { return e.max_hits == cell.max_hits; });
      if (it == exact->cells.end()) continue;
      std::uint64_t wrong = 0;
      for (std::size_t i = 0; i < cell.ray_hash.size(); ++i) wrong += cell.ray_hash[i] != it->ray_hash[i];
      cell.wrong_rays = wrong;
    }
  }
}

const Cell* find_cell(const SceneResult& r, const std::string& kernel, std::size_t max_hits) {
  for (const Row& row : r.rows)
    if (row.kernel == kernel)
      for (const Cell& c : row.cells)
        if (c.max_hits == max_hits) return &c;
  return nullptr;
}

// A cell's time over its plain Embree partner's, from time_by_chunk() (0 where it had none).
double partner_ratio(const Cell& c) {
  return c.partner_seconds.empty() ? 0.0 : c.paired_median_seconds / c.partner_median_seconds;
}

// Fastest exact own-BVH kernel (restart, queue, nodecull, filter, buffered) in a column, among the
// rows of one prefetch mode: by the table's medians, or (paired) by partner_ratio().
const Row* best_exact_own(const SceneResult& r, std::size_t column, PrefetchMode mode, bool paired = false) {
  const Row* best = nullptr;
  auto cost = [&](const Row& row) {
    return paired ? partner_ratio(row.cells[column]) : row.cells[column].median_seconds;
  };
  for (const Row& row : r.rows) {
    if (!exact_own(row) || row.prefetch != mode) continue;
    if (paired && row.cells[column].partner_seconds.empty()) continue;
    if (best == nullptr || cost(row) < cost(*best)) best = &row;
  }
  return best;
}

// The range of a / b taken repetition by repetition (the two cells of one repetition ran moments
// apart): on a shared machine this shows how far one run's median can be trusted.
std::string by_repetition(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() < 2 || a.size() != b.size()) return {};
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (std::size_t k = 0; k < a.size(); ++k) lo = std::min(lo, a[k] / b[k]), hi = std::max(hi, a[k] / b[k]);
  return " [" + fmt("%.2f", lo) + "-" + fmt("%.2f", hi) + " by repetition]";
}

// time_scaling_by_chunk()'s speed-ups: median time on one thread over median time on all.
void print_scaling(const SceneResult& r, const Settings& st) {
  auto speedup = [](const Cell& c) { return median(c.one_thread_seconds) / median(c.all_threads_seconds); };
  bool any = false;
  for (const Row& row : r.rows)
    for (const Cell& c : row.cells) any = any || !c.one_thread_seconds.empty();
  if (!any) return;
  std::cout << "\nspeed-up on all threads over one (the same cells on one thread and on all, paired by chunk, "
            << paired_reps(st) << " repetitions, the cells taking turns):\n";
  for (const std::size_t n : {std::size_t(1), std::size_t(0)}) {
    const Row* best = nullptr;  // the own-BVH kernel fastest on all threads
    const Cell* b = nullptr;    // its cell
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (const Row& row : r.rows) {
      const Cell* c = exact_own(row) ? find_cell(r, row.kernel, n) : nullptr;
      if (c == nullptr || c->one_thread_seconds.empty()) continue;
      lo = std::min(lo, speedup(*c)), hi = std::max(hi, speedup(*c));
      if (!b || median(c->all_threads_seconds) < median(b->all_threads_seconds)) best = &row, b = c;
    }
    if (!b) continue;
    std::cout << "  " << pad(column_title(n), 8) << "fastest own-BVH kernel " << pad(best->kernel, 9) << fmt("%.2f", speedup(*b))
              << "x" << by_repetition(b->one_thread_seconds, b->all_threads_seconds) << "; every own-BVH kernel "
              << fmt("%.2f", lo) << "-" << fmt("%.2f", hi) << "x";
    const char* plain = n == 1 ? "embree first hit" : "embree all-hits";
    if (const Cell* e = find_cell(r, plain, n); e && !e->one_thread_seconds.empty())
      std::cout << "; " << plain << " " << fmt("%.2f", speedup(*e)) << "x"
                << by_repetition(e->one_thread_seconds, e->all_threads_seconds);
    std::cout << "\n";
  }
}

void print_scene(const SceneResult& r, const Settings& st) {
  const BenchScene& s = *r.scene;
  const std::size_t rays = s.rays.size();
  std::cout << "\n== " << s.name << ": " << s.description << "\n";
  std::cout << "triangles " << s.scene.triangle_count() << " in " << s.scene.geometries().size()
            << " geometries; rays " << rays << "\n";
  const double tris = double(s.scene.triangle_count());
  std::cout << "build: Pierce (8-wide binned SAH, float) " << fmt("%.3f", r.pierce_build_s) << " s, "
            << r.wide_nodes << " wide nodes, " << r.leaf_blocks << " leaf blocks ("
            << fmt("%.2f", double(r.triangles_in_bvh) / double(std::max<std::size_t>(1, r.leaf_blocks)))
            << " of 8 lanes used), " << fmt("%.0f", double(r.pierce_bytes) / tris) << " bytes/triangle; "
            << "Embree (plain) " << fmt("%.3f", r.embree_build_s) << " s, "
            << fmt("%.0f", double(r.embree_bytes) / tris) << " bytes/triangle (robust: "
            << fmt("%.3f", r.embree_robust_build_s) << " s); build ratio "
            << fmt("%.2f", r.pierce_build_s / r.embree_build_s) << "x ("
            << (st.build_reps == 1 ? std::string("one build each") : "medians of " + std::to_string(st.build_reps) + " builds each, alternating")
            << ")\n";
  if (r.exact_all) {
    std::cout << "hits per ray (exact kernels, all): mean " << fmt("%.2f", double(r.exact_all->hits) / double(rays))
              << ", max " << r.exact_all->max_per_ray << ", rays with a hit " << r.exact_all->rays_hit;
    if (s.expected_hits_per_ray >= 0) std::cout << " (construction: " << s.expected_hits_per_ray << " per ray)";
    std::cout << "\n";
  }
  std::cout << "cells: M rays/s (median of " << st.reps << ") getting the first N hits of every ray; x ref = "
            << "ratio to Embree first hit (" << fmt("%.3f", r.reference_mrays) << " M rays/s)\n\n";

  std::cout << std::string(kNameWidth, ' ');
  for (const std::size_t n : st.columns) std::cout << "  " << pad(column_title(n), 15);
  std::cout << "  hits/ray\n" << std::string(kNameWidth, ' ');
  for (std::size_t i = 0; i < st.columns.size(); ++i) std::cout << "  Mrays/s  x ref ";
  std::cout << "  (all)\n";
  for (const Row& row : r.rows) {
    std::string name = row.kernel;
    if (!row.exact && !row.reference) name += " *";
    if (row.kind == KernelKind::nodecull || row.kind == KernelKind::embree_nodecull) name += " (N)";
    std::cout << pad(name, kNameWidth);
    for (std::size_t c = 0; c < st.columns.size(); ++c) {
      const auto it = std::find_if(row.cells.begin(), row.cells.end(),
                                   [&](const Cell& cell) { return cell.max_hits == st.columns[c]; });
      if (it == row.cells.end()) {
        std::cout << "        -        ";
        continue;
      }
      const double m = mrays_per_s(*it, rays);
      std::cout << "  " << fmt("%7.3f", m) << "  " << fmt("%5.2f", m / r.reference_mrays) << " ";
    }
    if (row.reference) std::cout << "\n";
    else std::cout << "  " << fmt("%7.2f", double(row.cells.back().tally.hits) / double(rays)) << "\n";
  }
  std::cout << "\n(N) node culling gets max_hits = N as a hint; in \"all\" it has none.\n"
            << "*   inexact (epsilon relaunch): misses or repeats hits, shown only for its cost.\n";
  for (const Row& row : r.rows)
    if (!row.exact && !row.reference && r.exact_all)
      std::cout << "    " << row.kernel << " found " << row.cells.back().tally.hits << " hits in \"all\", the exact "
                << "kernels " << r.exact_all->hits << ".\n";
  for (const Row& row : r.rows)
    if (row.reference && row.cells[0].max_hits == 1) {
      std::cout << "    " << row.kernel << " hit " << row.cells[0].tally.rays_hit << " rays";
      for (const Row& e : r.rows)
        if (e.exact && !e.cells.empty() && e.cells[0].max_hits == 1) {
          std::cout << ", the exact kernels " << e.cells[0].tally.rays_hit;
          break;
        }
      std::cout << ".\n";
    }
  if (st.count) {
    std::cout << "\ncounters per ray (timed repetitions): node tests / traversal steps / primitive tests\n"
              << "(embree-* and epsilon: Embree's node visits are not visible, their steps are rtcIntersect1 calls)\n"
              << std::string(kNameWidth, ' ');
    for (const std::size_t n : st.columns) {
      std::cout << "  " << pad(column_title(n), 24);
    }
    std::cout << "\n";
    for (const Row& row : r.rows) {
      if (row.reference) continue;
      std::cout << pad(row.kernel, kNameWidth);
      for (const Cell& c : row.cells) {
        const double per = 1.0 / (double(rays) * double(c.seconds.size()));
        std::string t = fmt("%.1f", double(c.counters.node_tests) * per) + " / " +
                        fmt("%.1f", double(c.counters.traversal_steps) * per) + " / " +
                        fmt("%.1f", double(c.counters.prim_tests) * per);
        std::cout << "  " << pad(t, 24);
      }
      std::cout << "\n";
    }
  }
  std::cout << "\nwrong rays (hit list differs from the exact kernels'; all: + rays with an odd hit count on a "
               "closed scene)\n"
            << std::string(kNameWidth, ' ');
  for (const std::size_t n : st.columns) std::cout << "  " << pad(column_title(n), 15);
  std::cout << "\n";
  for (const Row& row : r.rows) {
    if (row.exact) continue;
    std::cout << pad(row.kernel, kNameWidth);
    for (const std::size_t n : st.columns) {
      const Cell* c = find_cell(r, row.kernel, n);
      std::string t = c && c->wrong_rays ? std::to_string(*c->wrong_rays) : "-";
      if (c && c->odd_rays) t += " +" + std::to_string(*c->odd_rays) + " odd";
      std::cout << "  " << pad(t, 15);
    }
    std::cout << "\n";
  }
  // What exactness costs: time ratios (>1 = slower than the plain Embree row), same rays, same run.
  std::cout << "\ncost of exactness (time of the exact kernel / time of plain Embree code):\n";
  auto ratio = [&](const Cell* a, const Cell* b) { return a && b ? fmt("%.2f", a->median_seconds / b->median_seconds) : std::string("-"); };
  auto spread = [&](const Cell* a, const Cell* b) { return a && b ? by_repetition(a->seconds, b->seconds) : std::string(); };
  for (const PrefetchMode mode : st.prefetch) {
    if (st.prefetch.size() > 1) std::cout << " prefetch " << enum_name(mode) << ":\n";
    const auto own = [&](const char* kernel) { return row_name(kernel, mode, st); };
    for (std::size_t c = 0; c < st.columns.size(); ++c) {
      const Row* best = best_exact_own(r, c, mode);
      if (!best) continue;
      const std::size_t n = st.columns[c];
      std::cout << "  " << pad(column_title(n), 8) << "best exact own-BVH kernel " << pad(best->kernel, 9);
      const Cell* first = find_cell(r, "embree first hit", 1);
      const Cell* filter = find_cell(r, "embree all-hits", n);
      if (n == 1) std::cout << ratio(&best->cells[c], first) << "x first hit" << spread(&best->cells[c], first) << ", "
                            << ratio(&best->cells[c], find_cell(r, "embree robust 1st", 1)) << "x robust first hit";
      std::cout << (n == 1 ? ", " : "") << ratio(&best->cells[c], filter) << "x all-hits filter"
                << (n == 0 ? spread(&best->cells[c], filter) : std::string()) << ", "
                << ratio(&best->cells[c], find_cell(r, "embree lex-restart", n)) << "x lex-restart";
      if (const Row* paired = n == 1 || n == 0 ? best_exact_own(r, c, mode, true) : nullptr) {
        // From time_by_chunk(): the kernel with the lowest ratio there, which can differ from the table's best.
        const Cell& cell = paired->cells[c];
        std::cout << "; paired by chunk " << paired->kernel << " " << fmt("%.2f", partner_ratio(cell)) << "x "
                  << (n == 1 ? "first hit" : "all-hits filter") << by_repetition(cell.paired_seconds, cell.partner_seconds);
      }
      if (n == 5 || n == 15) {
        const Cell* q = find_cell(r, own("queue"), n);
        const Cell* a = find_cell(r, own("restart"), n);
        const Cell* f = find_cell(r, own("filter"), n);
        if (q && a && f && !q->paired_seconds.empty()) {
          // From time_by_chunk(): the three rows' cells timed again, interleaved by chunk.
          const Cell* better = a->paired_median_seconds < f->paired_median_seconds ? a : f;
          std::cout << "; queue / min(restart, filter) " << fmt("%.2f", q->paired_median_seconds / better->paired_median_seconds)
                    << by_repetition(q->paired_seconds, better->paired_seconds) << " (" << (better == a ? "restart" : "filter") << ", interleaved by chunk)";
          // How finely this run resolves that ratio: `filter` ignores the hint, so its cells at
          // N = 15 and N = 5 do the same traversal; only the bench's hashing of the hits beyond
          // the fifth differs (none on a scene where no ray holds more than 5).
          const Cell* f5 = find_cell(r, own("filter"), 5);
          if (n == 15 && f5 && !f5->paired_seconds.empty() && !f->paired_seconds.empty())
            std::cout << "; same-work control filter N = 15 / N = 5 "
                      << fmt("%.3f", f->paired_median_seconds / f5->paired_median_seconds);
        }
      }
      std::cout << "\n";
    }
  }
  if (const Cell* e = find_cell(r, "epsilon", 1)) {
    const Cell* first = find_cell(r, "embree first hit", 1);
    std::cout << "  epsilon (1 hit) " << ratio(e, first) << "x plain first hit" << spread(e, first);
    if (!e->partner_seconds.empty())
      std::cout << "; paired by chunk " << fmt("%.2f", partner_ratio(*e)) << "x"
                << by_repetition(e->paired_seconds, e->partner_seconds);
    std::cout << "\n";
  }
  print_scaling(r, st);
  for (const std::string& p : r.problems) std::cout << "WARNING: " << p << "\n";
  std::cout.flush();
}

json scene_json(const SceneResult& r) {
  const BenchScene& s = *r.scene;
  const std::size_t rays = s.rays.size();
  json j;
  j["name"] = s.name;
  j["description"] = s.description;
  j["triangles"] = s.scene.triangle_count();
  j["geometries"] = s.scene.geometries().size();
  j["rays"] = rays;
  j["build_seconds"] = {{"pierce", r.pierce_build_s},
                        {"embree", r.embree_build_s},
                        {"embree_robust", r.embree_robust_build_s}};
  j["bytes_per_triangle"] = {{"pierce", double(r.pierce_bytes) / double(s.scene.triangle_count())},
                             {"embree", double(r.embree_bytes) / double(s.scene.triangle_count())}};
  j["pierce_wide_nodes"] = r.wide_nodes;
  j["pierce_leaf_blocks"] = r.leaf_blocks;
  if (s.expected_hits_per_ray >= 0) j["expected_hits_per_ray"] = s.expected_hits_per_ray;
  if (r.exact_all) {
    j["hits_per_ray_all"] = {{"mean", double(r.exact_all->hits) / double(rays)},
                             {"max", r.exact_all->max_per_ray},
                             {"rays_with_a_hit", r.exact_all->rays_hit}};
  }
  j["reference_mrays_per_s"] = r.reference_mrays;
  j["problems"] = r.problems;
  json rows = json::array();
  for (const Row& row : r.rows) {
    json jr;
    jr["kernel"] = row.kernel;
    jr["exact"] = row.exact;
    jr["reference"] = row.reference;
    if (row.prefetch) jr["prefetch"] = enum_name(*row.prefetch);
    jr["gets_max_hits_hint"] = row.kind == KernelKind::nodecull || row.kind == KernelKind::embree_nodecull;
    json cells = json::array();
    for (const Cell& c : row.cells) {
      const double m = mrays_per_s(c, rays);
      json jc = {{"max_hits", c.max_hits == 0 ? json("all") : json(c.max_hits)},
                 {"seconds", c.seconds},
                 {"median_seconds", c.median_seconds},
                 {"paired_seconds", c.paired_seconds},
                 {"paired_median_seconds", c.paired_median_seconds},
                 {"partner_seconds", c.partner_seconds},
                 {"partner_median_seconds", c.partner_median_seconds},
                 {"one_thread_seconds", c.one_thread_seconds},
                 {"all_threads_seconds", c.all_threads_seconds},
                 {"mrays_per_s", m},
                 {"ratio_to_embree_first_hit", m / r.reference_mrays},
                 {"hits", c.tally.hits},
                 {"hits_per_ray", double(c.tally.hits) / double(rays)},
                 {"max_hits_per_ray", c.tally.max_per_ray},
                 {"rays_with_a_hit", c.tally.rays_hit},
                 {"hit_hash", c.tally.hash},
                 {"deterministic", c.deterministic}};
      if (c.wrong_rays) jc["wrong_rays"] = *c.wrong_rays;
      if (c.odd_rays) jc["odd_hit_count_rays"] = *c.odd_rays;
      if (row.counted) {
        const double per = 1.0 / (double(rays) * double(c.seconds.size()));
        jc["counters_per_ray"] = {{"node_tests", double(c.counters.node_tests) * per},
                                  {"traversal_steps", double(c.counters.traversal_steps) * per},
                                  {"prim_tests", double(c.counters.prim_tests) * per},
                                  {"valid_hits", double(c.counters.valid_hits) * per}};
      }
      cells.push_back(jc);
    }
    jr["cells"] = cells;
    rows.push_back(jr);
  }
  j["rows"] = rows;
  return j;
}

// ---------------------------------------------------------------- main

constexpr KernelKind kRowOrder[] = {KernelKind::restart,  KernelKind::embree_restart, KernelKind::filter,
                                    KernelKind::embree_filter, KernelKind::queue,   KernelKind::buffered,
                                    KernelKind::nodecull, KernelKind::embree_nodecull, KernelKind::epsilon};

// Gribble's heat maps of traversal steps for the scene: `queue` for the first hit and `filter` for
// all hits (the best exact kernels there), 480x360, the default view of `pierce thickness --png`.
void write_heatmaps(const BenchScene& s, const Accel& accel, const Settings& st) {
  FalseColourOptions fo;
  fo.width = 480;
  fo.height = 360;
  for (const auto& [kind, n] : {std::pair{KernelKind::queue, std::size_t(1)}, std::pair{KernelKind::filter, std::size_t(0)}}) {
    const std::filesystem::path path = std::filesystem::path(st.heatmap_dir) /
                                       ("heat_" + s.name + "_" + std::string(kernel_name(kind)) + "_" +
                                        (n == 0 ? std::string("all") : std::to_string(n)) + ".png");
    if (std::filesystem::exists(path) && !st.force)
      throw std::runtime_error("--heatmaps: " + path.string() + " exists; pass --force to overwrite it");
    HeatmapStats stats;
    const FalseColourImage img = render_cost_heatmap(accel, kind, n, CostMetric::traversal_steps, fo, stats);
    const std::string png = false_colour_png(img);
    std::ofstream out(path, std::ios::binary);
    out.write(png.data(), std::streamsize(png.size()));
    if (!out) throw std::runtime_error("--heatmaps: cannot write " + path.string());
    std::cout << "heat map " << path.string() << ": " << kernel_name(kind) << ", " << column_title(n)
              << ", traversal steps per pixel: mean " << fmt("%.2f", stats.mean) << " (" << fmt("%.2f", stats.mean_over_scene)
              << " where the ray does work), max " << fmt("%.0f", stats.max) << "\n";
  }
}

SceneResult run_scene(const BenchScene& s, const std::vector<KernelKind>& kernels, const Settings& st) {
  SceneResult r;
  r.scene = &s;
  std::cerr << "[" << s.name << "] building\n";
  // Each build is timed st.build_reps times, Pierce's and Embree's alternating, and the medians
  // compared: a single build favours whichever comes second (the scene's pages and the builders'
  // thread pools are warm by then) and moves with the machine's load.
  std::optional<Accel> built;
  std::optional<EmbreeReference> plain_built, robust_built;
  std::vector<double> pierce_s, embree_s, robust_s;
  for (int i = 0; i < st.build_reps; ++i) {
    built.reset();
    const auto t0 = Clock::now();
    built.emplace(s.scene);
    pierce_s.push_back(seconds_since(t0));
    plain_built.reset();
    plain_built.emplace(s.scene, ReferenceUse::first_hit);
    embree_s.push_back(plain_built->build_seconds());
    robust_built.reset();
    robust_built.emplace(s.scene, ReferenceUse::robust_first_hit);
    robust_s.push_back(robust_built->build_seconds());
  }
  const Accel& accel = *built;
  const EmbreeReference &plain = *plain_built, &robust = *robust_built;
  r.pierce_build_s = median(pierce_s);
  r.embree_build_s = median(embree_s);
  r.embree_robust_build_s = median(robust_s);
  r.pierce_bytes = accel.wide().memory_bytes();
  r.wide_nodes = accel.wide().nodes.size();
  r.leaf_blocks = accel.wide().blocks.size();
  r.triangles_in_bvh = accel.wide().triangles;
  r.embree_bytes = plain.bytes();

  // The all-hits and restart rows' scene: the plain one with the flag their filters need (an
  // Embree user sets it only where a context filter is used; it is not part of the build timing).
  const EmbreeReference filters(s.scene, ReferenceUse::filters);
  r.rows = run_references(plain, robust, filters, s.rays, st);
  for (const KernelKind k : kernels) {
    if (uses_embree(k)) {
      r.rows.push_back(run_kernel(accel, k, std::nullopt, s.rays, st));
      continue;
    }
    for (const PrefetchMode mode : st.prefetch) r.rows.push_back(run_kernel(accel, k, mode, s.rays, st));
  }
  std::cerr << "[" << s.name << "] timing " << r.rows.size() << " rows, repetitions interleaved\n";
  time_rows(r.rows, s.rays.size(), st.reps);
  time_by_chunk(r.rows, s.rays.size(), st);
  time_scaling_by_chunk(r.rows, s.rays.size(), st);
  r.reference_mrays = mrays_per_s(r.rows.front().cells[0], s.rays.size());
  check_agreement(r, st);
  count_wrong_rays(r);
  if (!st.heatmap_dir.empty()) write_heatmaps(s, accel, st);
  return r;
}

int run(int argc, char** argv) {
  CLI::App app{"pierce_bench_kernels: rays/s of getting the first N hits per ray for every kernel "
               "(the table of Wald et al. 2019, Fig. 3)"};
  std::size_t ray_count = 200000;
  std::string scene_choice = "all";
  int threads = 0;
  bool quick = false, force = false;
  std::string json_path, kernel_list;
  Settings st;
  std::uint64_t seed = 1;
  auto* rays_opt = app.add_option("--rays", ray_count, "rays per scene (default 200000; 2000 with --quick)")
                       ->check(CLI::Range(std::size_t(1), std::size_t(100000000)));
  std::vector<std::string> mesh_paths;
  app.add_option("--scene", scene_choice,
                 "plates | hairball | blob | shell (1.64 M triangles) | all (the first three) | none (only --mesh)")
      ->check(CLI::IsMember({"plates", "hairball", "blob", "shell", "all", "none"}));
  app.add_option("--mesh", mesh_paths, "also bench these model files (STL, OBJ, OFF, PLY), e.g. your own CAD meshes")
      ->check(CLI::ExistingFile);
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  app.add_flag("--quick", quick, "tiny scenes and rays, one repetition (smoke run)");
  app.add_flag("--counters", st.count,
               "time the kernels' counting variants and print node tests, traversal steps and primitive tests per ray");
  app.add_option("--json", json_path, "also write every number to this JSON file");
  app.add_flag("--force", force, "overwrite the --json file (and --heatmaps pictures) if they exist");
  app.add_option("--heatmaps", st.heatmap_dir,
                 "write Gribble's traversal heat maps of each scene into this directory (queue, first hit; filter, all)");
  auto* reps_opt = app.add_option("--reps", st.reps, "timed repetitions per cell, median reported (default 3)")
                       ->check(CLI::Range(1, 100));
  auto* build_reps_opt =
      app.add_option("--build-reps", st.build_reps, "builds of each scene by Pierce and by Embree, alternating, median reported (default 3)")
          ->check(CLI::Range(1, 20));
  app.add_option("--kernels", kernel_list, "comma-separated kernel rows to run (default: all)");
  app.add_option("--seed", seed, "seed of the scenes and rays (default 1)");
  std::string column_list;
  app.add_option("--columns", column_list, "comma-separated N of the columns, 0 or all = all hits (default 1,5,15,all)");
  int blob_subdivisions = 0;
  app.add_option("--blob-subdivisions", blob_subdivisions,
                 "subdivisions of the blob scene (default 6: 82k triangles; each one more is 4x the triangles, 8: 1.3 M)")
      ->check(CLI::Range(1, 9));
  std::vector<std::string> prefetch_names;
  app.add_option("--prefetch", prefetch_names,
                 "comma-separated prefetch modes of the own-BVH kernel rows, each a row of its own: auto, always, "
                 "never (default: PIERCE_PREFETCH, else auto)")
      ->delimiter(',')
      ->check(CLI::IsMember(enum_names<PrefetchMode>()));
  CLI11_PARSE(app, argc, argv);
  st.force = force;
  if (!st.heatmap_dir.empty() && !std::filesystem::is_directory(st.heatmap_dir)) {
    std::cerr << "error: --heatmaps " << st.heatmap_dir << ": not a directory\n";
    return 2;
  }

  if (!column_list.empty()) {
    st.columns.clear();
    std::stringstream ss(column_list);
    for (std::string c; std::getline(ss, c, ',');) {
      if (c == "all" || c == "0") {
        st.columns.push_back(0);
        continue;
      }
      try {
        st.columns.push_back(std::stoul(c));
      } catch (const std::exception&) {
        std::cerr << "error: --columns: '" << c << "' is not a number or 'all'\n";
        return 2;
      }
    }
  }
  if (!prefetch_names.empty()) {
    st.prefetch.clear();
    for (const std::string& name : prefetch_names) {
      const PrefetchMode mode = parse_enum_or_throw<PrefetchMode>(name);  // checked by CLI11 already
      if (std::find(st.prefetch.begin(), st.prefetch.end(), mode) == st.prefetch.end()) st.prefetch.push_back(mode);
    }
  }
  std::vector<KernelKind> kernels;
  if (kernel_list.empty()) {
    kernels.assign(std::begin(kRowOrder), std::end(kRowOrder));
  } else {
    std::stringstream ss(kernel_list);
    for (std::string name; std::getline(ss, name, ',');) {
      const auto k = parse_kernel(name);
      if (!k) {
        std::cerr << "error: --kernels: unknown kernel '" << name << "' (known:";
        for (const KernelKind kk : kRowOrder) std::cerr << " " << kernel_name(kk);
        std::cerr << ")\n";
        return 2;
      }
      if (std::find(kernels.begin(), kernels.end(), *k) == kernels.end()) kernels.push_back(*k);
    }
  }

  // Open the JSON file before the long run so a bad path fails at once.
  std::ofstream json_out;
  if (!json_path.empty()) {
    if (std::filesystem::exists(json_path) && !force) {
      std::cerr << "error: --json " << json_path << " exists; pass --force to overwrite it\n";
      return 2;
    }
    json_out.open(json_path, std::ios::trunc);
    if (!json_out) {
      std::cerr << "error: --json " << json_path << ": cannot open for writing\n";
      return 2;
    }
  }

  SceneSize size;
  if (quick) {
    size = {8, 5000, 0.05, 3};
    if (rays_opt->count() == 0) ray_count = 2000;
    if (reps_opt->count() == 0) st.reps = 1;
    if (build_reps_opt->count() == 0) st.build_reps = 1;
  }
  if (blob_subdivisions > 0) size.blob_subdivisions = blob_subdivisions;
  const int hw = int(std::thread::hardware_concurrency());
  if (threads == 0) threads = tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const int threads_used = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

  const std::string load_before = load_average();
  const StealMeter steal;
  std::cout << "pierce_bench_kernels — Wald et al. 2019 Fig. 3 style table\n"
            << "machine: " << cpu_model() << ", " << hw << " hardware threads, " << threads_used << " used\n"
            << "load average at start: " << load_before << "\n"
            << "Embree " << RTC_VERSION_STRING << ", oneTBB " << TBB_VERSION_STRING << ", counters "
            << (st.count ? "on (the kernels' counting variants are timed)" : "off") << (quick ? ", --quick" : "")
            << ", prefetch " << prefetch_list_text(st) << "\n"
            << "rays per scene " << ray_count << ", seed " << seed << ", " << st.reps
            << " timed repetitions per cell (median) after a warm-up on 1/8 of the rays, each after an untimed pass over 1/16;"
               " the quoted ratios (N = 1 and all against plain Embree, epsilon, queue / min(restart, filter)) also from a further "
            << paired_reps(st) << " repetitions of their cells alone, interleaved by chunk of " << chunk_rays(ray_count)
            << " rays, each chunk after an untimed pass over its first 1/16\n";

  const auto start = Clock::now();
  std::vector<std::unique_ptr<BenchScene>> scenes;
  auto want = [&](const char* n) { return scene_choice == "all" || scene_choice == n; };
  if (want("plates")) scenes.push_back(std::make_unique<BenchScene>(plates_scene(size.plate_layers, ray_count, seed)));
  if (want("hairball"))
    scenes.push_back(std::make_unique<BenchScene>(
        hairball_scene(size.soup_triangles, size.soup_triangle_size, ray_count, seed)));
  if (want("blob")) scenes.push_back(std::make_unique<BenchScene>(blob_scene(size.blob_subdivisions, ray_count, seed)));
  if (scene_choice == "shell")
    scenes.push_back(std::make_unique<BenchScene>(quick ? shell_scene(4, 3, ray_count, seed) : shell_scene(8, 7, ray_count, seed)));
  for (const std::string& path : mesh_paths) scenes.push_back(std::make_unique<BenchScene>(mesh_scene(path, ray_count, seed)));

  json j;
  j["machine"] = {{"cpu", cpu_model()},
                  {"hardware_threads", hw},
                  {"threads_used", threads_used},
                  {"load_average_start", load_before}};
  j["versions"] = {{"embree", RTC_VERSION_STRING}, {"tbb", TBB_VERSION_STRING}};
  j["config"] = {{"rays", ray_count}, {"seed", seed},         {"reps", st.reps}, {"build_reps", st.build_reps},
                 {"quick", quick},    {"counters", st.count}, {"warmup_fraction", 0.125},
                 {"prefetch", prefetch_list_text(st)}};
  j["scenes"] = json::array();
  for (const auto& s : scenes) {
    const SceneResult r = run_scene(*s, kernels, st);
    print_scene(r, st);
    j["scenes"].push_back(scene_json(r));
  }
  const double total = seconds_since(start);
  const std::string load_after = load_average();
  j["machine"]["load_average_end"] = load_after;
  j["machine"]["cpu_stolen"] = steal.percent();
  j["total_seconds"] = total;
  std::cout << "\ntotal " << fmt("%.1f", total) << " s; load average at end: " << load_after
            << "; CPU time stolen by the hypervisor during the run: " << steal.percent() << "\n";

  if (json_out.is_open()) {
    json_out << j.dump(2) << "\n";
    if (!json_out) {
      std::cerr << "error: --json " << json_path << ": write failed\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
