#pragma once
// A small STEP assembly with known geometry, written with OpenCASCADE (XDE, names kept), for the
// CAD loader and reader tests, the CLI tests and the pvbatch tests (the one OCCT model builder of the
// tests):
//   plate_assy/plate     box [0,10] x [0,10] x [0,2]
//   plate_assy/block     box [1,3] x [1,3] x [2,4]    touching the plate's top
//   plate_assy/block#2   box [6,8] x [1,3] x [2,4]    the same part placed again
//   plate_assy/clash     box [6,8] x [6,8] x [1.5,3.5] sunk 0.5 into the plate
#include <string>

namespace pierce::test_models {

// Throws std::runtime_error when OpenCASCADE cannot write `path`.
void write_step_assembly(const std::string& path);

}  // namespace pierce::test_models
