// pierce_check_cad_exact: is `pierce thickness` on CAD files true to the B-rep? For
// each STEP/IGES/BREP file given, every valid sample of `pierce thickness --per face` and
// `--per vertex` (default options, exact B-rep) is checked against OpenCASCADE: from the sample's
// B-rep point along its inward normal, the first crossing of the solid's faces
// (IntCurvesFace_ShapeIntersector). Where that disagrees with Pierce by more than 1e-6 of the
// solid's size, the line is cut by the solid with a Boolean common (BRepAlgoAPI_Common of the solid
// and a segment, which keeps the pieces inside and on the boundary) and the end of the piece the
// sample starts is the answer: a ray that runs down a face from its rim first touches it, which
// the first-crossing answer takes for an exit. Where Pierce and the Boolean still differ and the
// ray between the two answers runs in a face (on the boundary within 1e-7 of the size), the
// thickness is ill-posed and the sample is counted apart. Where the Boolean fails, the point
// classifier settles it (in the solid up to Pierce's exit, out beyond). Also counted: unflagged
// no-exits. Only B-rep solids whose mesh is closed are checked (a shell has no inside).
// Prints one row per file and per sampling, and the samples that disagree with both answers;
// exit status 1 when a sample reads less than half its exact wall or a closed solid has an
// unflagged no-exit (a false thin spot). Not a timed bench: a checker for real parts that are not
// in the repository.
#include <BRepAlgoAPI_Common.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Lin.hxx>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "cad_faces.h"
#include "pierce/analysis/mesh_report.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/io/model_io.h"

namespace pierce::bench {
namespace {

using analysis::SampleAt;
using analysis::ThicknessStatus;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double diagonal(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  return box.IsVoid() ? 1.0 : std::sqrt(box.SquareExtent());
}

// The exact answers for one solid.
class Reference {
 public:
  Reference(const TopoDS_Shape& solid, double size) : solid_(solid), size_(size), inside_(solid) {
    first_.Load(solid, 1e-9 * size);
  }

  // Where the Boolean fails: whether the ray is in (or on) the solid at 200 points up to t and out
  // of it just beyond, by the point classifier (slow, for the rare samples neither answer settles).
  bool classifies_as_exit(Vec3d p, Vec3d inward, double t) {
    auto state = [&](double s) {
      const Vec3d q = p + inward * s;
      inside_.Perform(gp_Pnt(q.x, q.y, q.z), 1e-7 * size_);
      return inside_.State();
    };
    constexpr int kPoints = 200;
    for (int k = 1; k <= kPoints; ++k)
      if (state(t * k / (kPoints + 1)) == TopAbs_OUT) return false;
    return state(t + std::max(1e-6 * size_, 1e-3 * t)) == TopAbs_OUT;
  }

  // Whether the point lies on the solid's boundary, within 1e-7 of the size: where two answers
  // differ along a stretch of the ray that runs in a face, the thickness depends on which side of
  // the face an infinitesimal change of the ray takes it, and neither is wrong.
  bool on_boundary(Vec3d q) {
    inside_.Perform(gp_Pnt(q.x, q.y, q.z), 1e-7 * size_);
    return inside_.State() == TopAbs_ON;
  }

  // The first crossing of a face beyond 1e-7 of the size; NaN when none.
  double first_crossing(Vec3d p, Vec3d inward) {
    first_.Perform(line(p, inward), 1e-7 * size_, 1e9 * size_);
    double best = kNaN;
    if (!first_.IsDone()) return best;
    for (Standard_Integer i = 1; i <= first_.NbPnt(); ++i)
      if (!(first_.WParameter(i) >= best)) best = first_.WParameter(i);
    return best;
  }

  // Where the material the ray starts in ends: the pieces of the segment in or on the solid,
  // joined where they touch, and the end of the one that starts at the sample; NaN when the
  // Boolean fails or no piece starts there.
  double common_exit(Vec3d p, Vec3d inward) {
    try {
      const double len = 4 * size_;
      const gp_Pnt a(p.x, p.y, p.z), b(p.x + len * inward.x, p.y + len * inward.y, p.z + len * inward.z);
      BRepAlgoAPI_Common common(solid_, BRepBuilderAPI_MakeEdge(a, b).Edge());
      if (!common.IsDone()) return kNaN;
      std::vector<std::pair<double, double>> pieces;
      for (TopExp_Explorer e(common.Shape(), TopAbs_EDGE); e.More(); e.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
        double t0 = 0, t1 = 0;
        BRep_Tool::Range(edge, t0, t1);
        Standard_Real f, l;
        const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, f, l);
        if (c.IsNull()) continue;
        const gp_Vec d(inward.x, inward.y, inward.z);
        const double s0 = gp_Vec(a, c->Value(t0)).Dot(d), s1 = gp_Vec(a, c->Value(t1)).Dot(d);
        pieces.emplace_back(std::min(s0, s1), std::max(s0, s1));
      }
      std::sort(pieces.begin(), pieces.end());
      const double gap = 1e-7 * size_;
      double end = kNaN;
      for (const auto& [lo, hi] : pieces) {
        if (std::isnan(end)) {
          if (lo > gap) return kNaN;
          end = hi;
        } else if (lo <= end + gap) {
          end = std::max(end, hi);
        } else {
          break;
        }
      }
      return end;
    } catch (const Standard_Failure&) {
      return kNaN;
    }
  }

 private:
  static gp_Lin line(Vec3d p, Vec3d d) { return gp_Lin(gp_Pnt(p.x, p.y, p.z), gp_Dir(d.x, d.y, d.z)); }
  TopoDS_Shape solid_;
  double size_;
  IntCurvesFace_ShapeIntersector first_;
  BRepClass3d_SolidClassifier inside_;
};

struct Tally {
  std::size_t samples = 0, valid = 0, tessellation = 0, agree = 0, settled_by_common = 0, wrong = 0, false_thin = 0,
              unflagged_no_exit = 0, unchecked = 0, in_face = 0, classified = 0;
  double worst = 0;  // of the agreeing ones, relative to the size
};

Tally check(const std::string& path, SampleAt per, int& shown) {
  Scene scene;
  const std::vector<LoadedFile> files = add_any_model(scene, {path}, TessellationOptions{});
  const auto exact = cad_surfaces(files, scene.geometries().size());
  Tally t;
  if (!exact) return t;
  const Accel accel(scene);
  analysis::ThicknessOptions o;
  o.per = per;
  o.exact = exact.get();
  const analysis::ThicknessResult r = analysis::compute_thickness(accel, o);
  const std::vector<analysis::SolidReport> reports = analysis::mesh_report(scene);
  std::vector<std::unique_ptr<Reference>> refs(scene.geometries().size());
  std::vector<double> sizes(scene.geometries().size(), 1.0);
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    if (!exact->covers(g)) continue;
    // Only closed solids: a shell (open, or faces that close without making a solid) has no
    // inside for the Boolean to keep.
    const TopoDS_Shape& shape = exact->link(g).faces->shape;
    const bool solid = shape.ShapeType() == TopAbs_SOLID || shape.ShapeType() == TopAbs_COMPSOLID;
    if (!solid || !reports.at(g).closed) {
      ++t.unchecked;
      continue;
    }
    sizes[g] = diagonal(shape);
    refs[g] = std::make_unique<Reference>(shape, sizes[g]);
  }
  for (std::size_t i = 0; i < r.size(); ++i) {
    const std::uint32_t g = r.solid[i];
    if (!refs[g]) continue;
    ++t.samples;
    if (r.status[i] == ThicknessStatus::tessellation) ++t.tessellation;
    if (r.status[i] == ThicknessStatus::no_exit) ++t.unflagged_no_exit;
    if (r.status[i] != ThicknessStatus::ok) continue;
    ++t.valid;
    const double tol = 1e-6 * sizes[g];
    const Vec3d inward = r.normal[i] * -1.0;
    const double first = refs[g]->first_crossing(r.point[i], inward);
    double exact_t = first;
    bool by_common = false;
    if (!(std::abs(r.thickness[i] - exact_t) <= tol)) {
      exact_t = refs[g]->common_exit(r.point[i], inward);
      by_common = true;
    }
    const double err = std::abs(r.thickness[i] - exact_t);
    if (err <= tol) {
      ++(by_common ? t.settled_by_common : t.agree);
      t.worst = std::max(t.worst, err / sizes[g]);
      continue;
    }
    if (std::isnan(exact_t) && refs[g]->classifies_as_exit(r.point[i], inward, r.thickness[i])) {
      ++t.classified;
      continue;
    }
    if (std::isfinite(exact_t) &&
        refs[g]->on_boundary(r.point[i] + inward * (0.5 * (r.thickness[i] + exact_t)))) {
      ++t.in_face;
      continue;
    }
    ++t.wrong;
    if (r.thickness[i] < 0.5 * exact_t) ++t.false_thin;
    if (shown < 20) {
      ++shown;
      std::printf("  %s per %s: solid %u element %u at (%.9g, %.9g, %.9g) inward (%.6f, %.6f, %.6f): pierce %.9g, "
                  "first crossing %.9g, common %.9g (%u B-rep faces at the element)\n",
                  path.c_str(), std::string(enum_name(per)).c_str(), g, r.element[i], r.point[i].x, r.point[i].y,
                  r.point[i].z, inward.x, inward.y, inward.z, r.thickness[i], first, exact_t,
                  unsigned(r.brep_faces.empty() ? 0 : r.brep_faces[i]));
    }
  }
  return t;
}

int run(int argc, char** argv) {
  CLI::App app("Checks pierce thickness on CAD files against OpenCASCADE's exact B-rep, sample by sample");
  std::vector<std::string> paths;
  std::string per = "both";
  app.add_option("files", paths, "STEP, IGES or BREP files")->required()->check(CLI::ExistingFile);
  app.add_option("--per", per, "face, vertex or both")->check(CLI::IsMember({"face", "vertex", "both"}));
  CLI11_PARSE(app, argc, argv);
  std::vector<SampleAt> pers;
  if (per != "vertex") pers.push_back(SampleAt::face);
  if (per != "face") pers.push_back(SampleAt::vertex);
  std::printf("%-40s %-7s %8s %8s %6s %8s %8s %6s %7s %6s %6s %8s %10s %5s\n", "file", "per", "samples", "valid",
              "tess", "agree", "common", "class", "in-face", "wrong", "thin", "no-exit", "worst", "unchk");
  Tally total;
  int shown = 0;
  for (const std::string& path : paths) {
    for (SampleAt p : pers) {
      Tally t;
      try {
        t = check(path, p, shown);
      } catch (const std::exception& e) {
        std::printf("%s: %s\n", path.c_str(), e.what());
        continue;
      }
      const std::string name = path.size() > 40 ? "..." + path.substr(path.size() - 37) : path;
      std::printf("%-40s %-7s %8zu %8zu %6zu %8zu %8zu %6zu %7zu %6zu %6zu %8zu %10.2e %5zu\n", name.c_str(),
                  std::string(enum_name(p)).c_str(), t.samples, t.valid, t.tessellation, t.agree, t.settled_by_common,
                  t.classified, t.in_face, t.wrong, t.false_thin, t.unflagged_no_exit, t.worst, t.unchecked);
      std::fflush(stdout);
      total.samples += t.samples, total.valid += t.valid, total.tessellation += t.tessellation;
      total.agree += t.agree, total.settled_by_common += t.settled_by_common, total.wrong += t.wrong;
      total.false_thin += t.false_thin, total.unflagged_no_exit += t.unflagged_no_exit;
      total.unchecked += t.unchecked, total.in_face += t.in_face, total.classified += t.classified;
      total.worst = std::max(total.worst, t.worst);
    }
  }
  std::printf("%-40s %-7s %8zu %8zu %6zu %8zu %8zu %6zu %7zu %6zu %6zu %8zu %10.2e %5zu\n", "total", "",
              total.samples, total.valid, total.tessellation, total.agree, total.settled_by_common, total.classified,
              total.in_face, total.wrong, total.false_thin,
              total.unflagged_no_exit, total.worst, total.unchecked);
  std::printf("agree: the first crossing agrees within 1e-6 of the size; common: the Boolean common does; "
              "class: the Boolean failed, the point classifier finds the ray in the solid at 200 points up to Pierce's exit and out 1e-3 of it beyond; "
              "in-face: they differ where the ray runs in a face (ill-posed); wrong: neither; thin: of those, less than half the exact wall; no-exit: unflagged on a closed solid; "
              "unchk: solids not checked (not a B-rep solid, or its mesh is not closed)\n");
  return total.false_thin == 0 && total.unflagged_no_exit == 0 ? 0 : 1;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) {
  try {
    return pierce::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
