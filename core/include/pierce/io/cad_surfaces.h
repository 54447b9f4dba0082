#pragma once
// The exact B-rep surfaces behind CAD geometries (analysis::ExactSurfaces through OpenCASCADE),
// for thickness maps true to the CAD model (pierce/analysis/thickness.h, ThicknessOptions::exact).
#include <memory>
#include <vector>

#include "pierce/analysis/exact_surface.h"
#include "pierce/io/model_io.h"

namespace pierce {

class CadSurfaces final : public analysis::ExactSurfaces {
 public:
  // links[g]: the CAD link of geometry g of the scene (empty for meshes). Each link's triangles
  // are those of geometry g, in its order.
  explicit CadSurfaces(std::vector<CadLink> links);

  // True if any geometry is covered.
  bool any() const;
  const CadLink& link(std::uint32_t geom) const { return links_.at(geom); }

  bool covers(std::uint32_t geom) const override;
  std::uint32_t face_of(std::uint32_t geom, std::uint32_t prim) const override;
  std::span<const std::uint8_t> folded(std::uint32_t geom) const override;
  std::optional<analysis::SurfacePoint> project(std::uint32_t geom, std::uint32_t prim, double b1, double b2,
                                                Vec3d p) const override;
  std::optional<analysis::NearestFacePoint> nearest_on_faces(std::uint32_t geom,
                                                             std::span<const analysis::FaceStart> starts,
                                                             Vec3d p) const override;
  std::optional<analysis::SurfaceCrossing> intersect(std::uint32_t geom, std::uint32_t prim, double b1, double b2,
                                                     Vec3d org, Vec3d dir) const override;
  std::optional<double> exact_exit(std::uint32_t geom, Vec3d org, Vec3d dir, double tmin,
                                   const analysis::MeshSide* mesh = nullptr) const override;
  // How far the mesh of geometry `geom` may lie from its B-rep, per face: twice the largest
  // deviation of one of the face's triangles from its exact patch (sampled at its edge midpoints
  // and centre, as the hidden crossings' prisms bound a patch), plus twice the largest tolerance
  // of the face, its edges and vertices. Null where the mesh still folds (its winding number there
  // is not the solid's) or a band cannot be measured.
  const analysis::MeshBands* mesh_bands(std::uint32_t geom) const;
  std::optional<double> hidden_crossing(std::uint32_t geom, Vec3d org, Vec3d dir, double t_end,
                                        std::uint32_t start_face, std::uint32_t end_face) const override;
  ~CadSurfaces() override;

 private:
  struct Intersectors;  // OpenCASCADE shape intersectors, built on first use
  struct Classifiers;   // per face, whether a (u, v) lies inside its trimming wires
  struct HiddenFaces;   // the patches that bulge into the solid, for hidden_crossing
  struct MeshBands;     // mesh_bands() per geometry, measured on first use
  struct Sizes;         // per triangle, how far Newton may go from it, computed on first use
  // project(), also giving the foot's (u, v) on the face.
  std::optional<analysis::SurfacePoint> foot(std::uint32_t geom, std::uint32_t prim, double b1, double b2, Vec3d p,
                                             double& u, double& v) const;
  std::vector<CadLink> links_;
  std::vector<std::vector<std::uint8_t>> folded_;
  std::unique_ptr<Intersectors> intersectors_;
  std::unique_ptr<Classifiers> classifiers_;
  std::unique_ptr<HiddenFaces> hidden_;
  std::unique_ptr<MeshBands> bands_;
  std::unique_ptr<Sizes> sizes_;
};

// The surfaces of every CAD file among `files` (as add_any_model returned them), for a scene of
// `geometries` geometries; nullptr when none of the files is a CAD file.
std::shared_ptr<const CadSurfaces> cad_surfaces(const std::vector<LoadedFile>& files, std::size_t geometries);

}  // namespace pierce
