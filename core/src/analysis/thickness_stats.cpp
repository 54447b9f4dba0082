// Thickness, stage 3: welded copies, thin flags and the per-solid statistics over the valid
// samples (tessellation artefacts, no-exits and samples without normal are counted apart).
#include <cmath>

#include "pierce/huge_page_allocator.h"
#include "thickness_internal.h"

namespace pierce::analysis::detail {

void finish_statistics(const Scene& scene, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res) {
  for (auto [to, from] : set.copies) {
    res.thickness[to] = res.thickness[from];
    res.status[to] = res.status[from];
    res.exit_triangle[to] = res.exit_triangle[from];
    if (!res.brep_faces.empty()) {
      res.brep_faces[to] = res.brep_faces[from];
      res.point[to] = res.point[from];
      res.normal[to] = res.normal[from];
    }
  }
  for (std::size_t i = 0; i < res.size(); ++i)
    res.thin[i] = std::isfinite(res.thickness[i]) && res.thickness[i] < opts.min_thickness;

  // Rows per solid: contiguous ranges (compute_thickness) or, for points, wherever they are.
  std::vector<std::vector<std::uint32_t>> rows;
  if (set.ranges.size() != set.solids.size()) {
    std::vector<std::uint32_t> slot(scene.geometries().size(), kInvalidId);
    for (std::size_t k = 0; k < set.solids.size(); ++k) slot[set.solids[k]] = std::uint32_t(k);
    rows.resize(set.solids.size());
    for (std::size_t i = 0; i < res.size(); ++i) rows[slot[res.solid[i]]].push_back(std::uint32_t(i));
  }
  for (std::size_t k = 0; k < set.solids.size(); ++k) {
    SolidThickness st;
    st.geom = set.solids[k];
    st.name = scene.geometry(set.solids[k]).name;
    st.exact = opts.exact && opts.exact->covers(st.geom);
    std::vector<double> values;
    reserve_huge(values, rows.empty() ? set.ranges[k].second - set.ranges[k].first : rows[k].size());
    auto add = [&](std::size_t i) {
      ++st.elements;
      st.no_exit += res.status[i] == ThicknessStatus::no_exit;
      st.no_normal += res.status[i] == ThicknessStatus::no_normal;
      st.tessellation += res.status[i] == ThicknessStatus::tessellation;
      if (!res.brep_faces.empty()) st.edge_samples += res.brep_faces[i] >= 2;
      st.thin += res.thin[i];
      if (std::isfinite(res.thickness[i])) values.push_back(res.thickness[i]);
    };
    if (rows.empty()) {
      const auto [b, e] = set.ranges[k];
      for (std::size_t i = b; i < e; ++i) add(i);
    } else {
      for (std::uint32_t i : rows[k]) add(i);
    }
    st.valid = values.size();
    st.summary = summarize(std::move(values), opts.percentiles, opts.histogram_bins);
    res.solids.push_back(std::move(st));
  }
}

}  // namespace pierce::analysis::detail
