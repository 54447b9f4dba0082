#pragma once
// The tests' one OpenCASCADE model builder: CAD models with known geometry for the CAD loader
// and reader tests, the CLI tests and the pvbatch tests.
//
// A small STEP assembly (XDE, names kept):
//   plate_assy/plate     box [0,10] x [0,10] x [0,2]
//   plate_assy/block     box [1,3] x [1,3] x [2,4]    touching the plate's top
//   plate_assy/block#2   box [6,8] x [1,3] x [2,4]    the same part placed again
//   plate_assy/clash     box [6,8] x [6,8] x [1.5,3.5] sunk 0.5 into the plate
//
// Solids for thickness maps true to the B-rep (fillets, blends, a toroid):
//   bent_sheet      an L-shaped sheet 0.5 thick: legs along +x and +z (to 12), the bend a quarter
//                   annulus about the axis x = z = 1.5 (inner radius 1, outer 1.5), 8 wide in y;
//   filleted_box    box [0,10] x [0,8] x [0,6], all twelve edges filleted with radius 1 (the
//                   blends meet in spherical corners);
//   hollow_torus    a tube: torus of major radius 5, outer minor radius 1, inner 0.8 (wall 0.2);
//   thin_blended_plate  a 30 x 30 x 0.3 sheet whose edges are filleted with radius 0.01, with a
//                   through hole of radius 3.75 at its centre (sharp edges): on its default
//                   tessellation the bare mesh reads false thin spots at the blends (0.07 for
//                   the 0.3 sheet);
//   lofted_solid    a solid loft (B-spline side, planar caps) through circles of radius 5 at
//                   z = 0, 3 at (1, 0, 10) and 4 at (0, 1, 20): acute rims at both caps;
//   embossed_box    box [0,10] x [0,8] x [0,6] with a marking embossed kEmbossHeight high on its
//                   top, as KiCad packages carry their lettering: a dot of radius 1 centred at
//                   (3, 4) and a bar [6,8] x [3.5,4.5]. Vertex samples on the marking's rims run
//                   down its walls.
//
// Realistic parts for the CAD benchmark (pierce_bench_cad_refine), as STEP files:
//   sheet_heatsink  a TO-263-like sheet heatsink: a 1 mm sheet bent into a U (two bends of inner
//                   radius 1), 40 wide, its base 30 long and its legs 20 high, with kHeatsinkSlots
//                   slots across the legs and the base, every slot's four corners rounded with
//                   radius 0.5 (4 cylindrical blends per slot);
//   connector       an XDE assembly "connector" of a housing (box 42.14 x 8 x 10 with every edge
//                   filleted, radius 0.5, and kConnectorPins cavities 1 x 1 through it, in two
//                   rows 3 apart, 2.54 apart along each row) and kConnectorPins instances of one
//                   pin (0.64 x 0.64 x 14 with every edge filleted, radius 0.1) standing free in
//                   the cavities.
#include <TopoDS_Shape.hxx>

#include <string>

namespace pierce::test_models {

// Throws std::runtime_error when OpenCASCADE cannot write `path`.
void write_step_assembly(const std::string& path);

TopoDS_Shape bent_sheet();
TopoDS_Shape filleted_box();
TopoDS_Shape hollow_torus();
TopoDS_Shape thin_blended_plate();
TopoDS_Shape lofted_solid();
inline constexpr double kEmbossHeight = 0.002;
TopoDS_Shape embossed_box();

inline constexpr int kHeatsinkSlots = 36;
TopoDS_Shape sheet_heatsink();
inline constexpr int kConnectorPins = 32;
// Throws std::runtime_error when OpenCASCADE cannot write `path`.
void write_connector_assembly(const std::string& path);
// Writes `shape` as a one-part STEP file; throws std::runtime_error on failure.
void write_step(const TopoDS_Shape& shape, const std::string& path);

// `shape` meshed with `deflection` and one triangle of its most finely meshed face turned
// upside down (a fold the loader must find); the triangulation is kept in the shape.
TopoDS_Shape with_folded_triangle(const TopoDS_Shape& shape, double deflection);

// A machined part with pocket floors, the report's CAD test model: block [0,60] x [0,40] x [0,12]
// with pockets milled from its top: [5,20] x [5,15] down to a floor 0.6 thick, a round pocket of
// radius 5 centred at (12, 28) down to a floor 0.8 thick, and [25,55] x [5,35] down to a floor
// 1.5 thick.
TopoDS_Shape pocket_part();

// Writes `shape` as a STEP file of one part named `name` (XDE); throws std::runtime_error on failure.
void write_step_part(const TopoDS_Shape& shape, const std::string& name, const std::string& path);

// Writes `shape` (with its triangulation, if any) as BREP; throws std::runtime_error on failure.
void write_brep(const TopoDS_Shape& shape, const std::string& path);

}  // namespace pierce::test_models
