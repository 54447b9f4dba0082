// Mesh readers: every format returns every face at its file index (duplicates and degenerate faces
// included, polygons fanned in order), OBJ groups become meshes, and bad files give InputError
// messages naming the file and line (or byte offset / element).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "mesh_writers.h"
#include "pierce/error.h"
#include "pierce/generators.h"
#include "pierce/io/mesh_io.h"
#include "temp_dir.h"

namespace pierce::test {
namespace {

using Corners = std::array<Vec3d, 3>;

// Coordinates exact in float, so binary STL keeps them too.
PolyMesh known_mesh(bool polygons) {
  PolyMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1.25}, {2, 0, 0}, {-3.5, 1024.75, 0.125}};
  m.faces = {
      {0, 1, 2},  // 0
      {0, 2, 3},  // 1
      {0, 1, 2},  // 2: exact duplicate of 0
      {0, 1, 5},  // 3: degenerate, collinear corners
      {4, 4, 1},  // 4: degenerate, repeated vertex
      {2, 1, 0},  // 5: duplicate of 0 with the other winding
      {0, 1, 4},  // 6
      {6, 4, 3},  // 7
  };
  if (polygons) {
    m.faces.push_back({0, 1, 2, 3});     // quad -> 2 fan triangles
    m.faces.push_back({0, 5, 2, 4, 3});  // pentagon -> 3
    m.faces.push_back({1, 2, 4});        // after the polygons: index shifted by the fans
  }
  return m;
}

std::vector<Corners> expected_triangles(const PolyMesh& m) {
  std::vector<Corners> out;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) out.push_back({m.vertices[f[0]], m.vertices[f[i]], m.vertices[f[i + 1]]});
  return out;
}

std::vector<Corners> corners(const LoadedMesh& m) {
  std::vector<Corners> out;
  for (const Tri& t : m.triangles) {
    for (std::uint32_t i : t) EXPECT_LT(i, m.vertices.size());
    out.push_back({m.vertices.at(t[0]), m.vertices.at(t[1]), m.vertices.at(t[2])});
  }
  return out;
}

void expect_same_triangles(const std::vector<Corners>& want, const std::vector<Corners>& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(want[i][k].x, got[i][k].x) << "triangle " << i << " corner " << k;
      EXPECT_EQ(want[i][k].y, got[i][k].y) << "triangle " << i << " corner " << k;
      EXPECT_EQ(want[i][k].z, got[i][k].z) << "triangle " << i << " corner " << k;
    }
}

struct FormatCase {
  const char* name;
  const char* file;
  bool polygons;  // STL holds triangles only
  std::function<std::string(const PolyMesh&)> write;
};

class RoundTrip : public TempDirTest, public ::testing::WithParamInterface<FormatCase> {};

TEST_P(RoundTrip, EveryFaceAtItsIndex) {
  const FormatCase& c = GetParam();
  const PolyMesh mesh = known_mesh(c.polygons);
  const std::string path = file(c.file);
  write_text(path, c.write(mesh));
  const std::vector<LoadedMesh> loaded = load_mesh_file(path);
  ASSERT_EQ(loaded.size(), 1u);
  expect_same_triangles(expected_triangles(mesh), corners(loaded[0]));
  if (c.polygons) {
    // Indexed formats keep the vertex list and indices as written (every vertex is used).
    ASSERT_EQ(loaded[0].vertices.size(), mesh.vertices.size());
    EXPECT_EQ(loaded[0].triangles[2], (Tri{0, 1, 2}));
    EXPECT_EQ(loaded[0].triangles[4], (Tri{4, 4, 1}));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Formats, RoundTrip,
    ::testing::Values(FormatCase{"obj", "mesh.obj", true, obj_text}, FormatCase{"off", "mesh.off", true, off_text},
                      FormatCase{"ply_ascii", "mesh.ply", true, [](const PolyMesh& m) { return ply_data(m, PlyFormat::ascii); }},
                      FormatCase{"ply_le", "mesh.ply", true, [](const PolyMesh& m) { return ply_data(m, PlyFormat::little); }},
                      FormatCase{"ply_be", "mesh.PLY", true, [](const PolyMesh& m) { return ply_data(m, PlyFormat::big); }},
                      FormatCase{"stl_ascii", "mesh.stl", false, [](const PolyMesh& m) { return stl_ascii_text(m); }},
                      FormatCase{"stl_binary", "mesh.stl", false, [](const PolyMesh& m) { return stl_binary_data(m); }},
                      // A binary header may begin with "solid": the size decides.
                      FormatCase{"stl_binary_solid_header", "mesh.Stl", false,
                                 [](const PolyMesh& m) { return stl_binary_data(m, "solid but binary"); }}),
    [](const auto& info) { return std::string(info.param.name); });

using MeshIo = TempDirTest;

TEST_F(MeshIo, TextFormatsKeepDoublePrecision) {
  PolyMesh m{{{0.1, 1e-7, -123456.789}, {1.0 / 3.0, 2, 0}, {0, 1, 2.5e-3}}, {{0, 1, 2}}};
  for (const auto& [name, text] : {std::pair{"p.obj", obj_text(m)}, std::pair{"p.off", off_text(m)},
                                   std::pair{"p.ply", ply_data(m, PlyFormat::ascii)},
                                   std::pair{"b.ply", ply_data(m, PlyFormat::big)}}) {
    write_text(file(name), text);
    const auto loaded = load_mesh_file(file(name));
    ASSERT_EQ(loaded.size(), 1u);
    expect_same_triangles(expected_triangles(m), corners(loaded[0]));
  }
}

TEST_F(MeshIo, BinaryStlRoundsToFloat) {
  PolyMesh m{{{0.1, 0.2, 0.3}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
  write_text(file("f.stl"), stl_binary_data(m));
  const auto loaded = load_mesh_file(file("f.stl"));
  EXPECT_EQ(loaded.at(0).vertices.at(0).x, double(0.1f));
  EXPECT_EQ(loaded.at(0).name, "f");
}

TEST_F(MeshIo, ObjGroupsBecomeMeshesInFileOrder) {
  write_text(file("groups.obj"),
             "mtllib groups.mtl\n"
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\n"
             "vt 0 0\nvn 0 0 1\n"
             "f 1 2 3\n"            // before any group: named after the file
             "o first\nusemtl red\ns off\n"
             "f 1 2 4\nf 1 2 4\n"   // a duplicate, kept
             "o ignored_empty\ng second part\n"
             "f 2 3 4\n"
             "g third\n"
             "f -5 -4 -3 -2\n"      // relative indices, quad
             "o first\n"            // the same name again is a new mesh
             "f 1/1 2/1 3/1\n");
  const auto meshes = load_mesh_file(file("groups.obj"));
  ASSERT_EQ(meshes.size(), 5u);
  EXPECT_EQ(meshes[0].name, "groups");
  EXPECT_EQ(meshes[1].name, "first");
  EXPECT_EQ(meshes[2].name, "second part");
  EXPECT_EQ(meshes[3].name, "third");
  EXPECT_EQ(meshes[4].name, "first");
  EXPECT_EQ(meshes[1].triangles.size(), 2u);
  EXPECT_EQ(meshes[3].triangles.size(), 2u);
  // Each mesh keeps only the vertices it uses, in file order.
  EXPECT_EQ(meshes[1].vertices.size(), 3u);
  expect_same_triangles({{Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 0, 1}}, {Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 0, 1}}},
                        corners(meshes[1]));
  expect_same_triangles({{Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}}, {Vec3d{0, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}}},
                        corners(meshes[3]));
  EXPECT_EQ(meshes[4].vertices.size(), 3u);
}

TEST_F(MeshIo, ObjIndexForms) {
  write_text(file("forms.obj"),
             "v 0 0 0\nv 1 0 0\nv 0 1 0 1.0\nv 0 0 1 0.5 0.5 0.5\n"
             "f 1/1 2/2 3/3\nf 1//1 2//2 4//4\nf 1/1/1 3/3/3 4/4/4\nf -4/1/1 -3//2 -1\n  # comment\n\nf 2 3 4 # trailing\n");
  const auto m = load_mesh_file(file("forms.obj"));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].triangles, (std::vector<Tri>{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}}));
}

TEST_F(MeshIo, AsciiStlSolidsBecomeMeshes) {
  PolyMesh a = known_mesh(false), b{{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 2}}};
  write_text(file("two.stl"), stl_ascii_text(a, "alpha") + stl_ascii_text(b, "beta"));
  const auto m = load_mesh_file(file("two.stl"));
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].name, "alpha");
  EXPECT_EQ(m[1].name, "beta");
  expect_same_triangles(expected_triangles(a), corners(m[0]));
  expect_same_triangles(expected_triangles(b), corners(m[1]));
}

TEST_F(MeshIo, PlyVariants) {
  // vertex_index, float coordinates, uint indices, int8 list count, CRLF header.
  write_text(file("v.ply"),
             "ply\r\nformat ascii 1.0\r\nobj_info x\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n"
             "property float z\r\nelement face 2\r\nproperty list char uint vertex_index\r\nend_header\r\n"
             "0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n4 0 1 2 3\r\n3 3 3 3\r\n");
  const auto m = load_mesh_file(file("v.ply"));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {3, 3, 3}}));
}

TEST_F(MeshIo, OffVariants) {
  // Counts on the header line, vertex colours, face colours, comments.
  write_text(file("c.off"), "COFF 4 2 0\n# c\n0 0 0 255 0 0 255\n1 0 0 1 1 1 1\n1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n"
                            "4 0 1 2 3 255 0 0\n3 2 1 0\n");
  const auto m = load_mesh_file(file("c.off"));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {2, 1, 0}}));
}

TEST_F(MeshIo, AddModelFilesKeepsArgumentOrder) {
  write_text(file("a.stl"), stl_binary_data(known_mesh(false)));
  write_text(file("b.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\no one\nf 1 2 3\no two\nf 3 2 1\nf 1 2 3\n");
  write_text(file("c.off"), off_text(known_mesh(true)));
  Scene scene;
  add_model_files(scene, {file("a.stl"), file("b.obj"), file("c.off")});
  ASSERT_EQ(scene.geometries().size(), 4u);
  EXPECT_EQ(scene.geometry(0).source, file("a.stl"));
  EXPECT_EQ(scene.geometry(1).name, "one");
  EXPECT_EQ(scene.geometry(2).name, "two");
  EXPECT_EQ(scene.geometry(2).source, file("b.obj"));
  EXPECT_EQ(scene.geometry(2).triangles.size(), 2u);
  EXPECT_EQ(scene.geometry(3).source, file("c.off"));
  EXPECT_EQ(scene.geometry(3).triangles.size(), expected_triangles(known_mesh(true)).size());
  // Degenerate faces stay at their index (the scene marks them, it does not drop them).
  EXPECT_EQ(scene.geometry(0).degenerate.at(3), 1);
  EXPECT_EQ(scene.geometry(0).degenerate.at(4), 1);
  EXPECT_EQ(scene.geometry(0).degenerate.at(2), 0);
}

// The bundled samples are what the documentation says they are.
TEST(Samples, PlatesObjIsStackedPlates) {
  const auto meshes = load_mesh_file(std::string(PIERCE_SAMPLES_DIR) + "/plates.obj");
  const auto plates = gen::stacked_plates(10);
  ASSERT_EQ(meshes.size(), plates.size());
  for (std::size_t i = 0; i < plates.size(); ++i) {
    EXPECT_EQ(meshes[i].name, plates[i].name);
    EXPECT_EQ(meshes[i].triangles, plates[i].triangles);
    EXPECT_EQ(meshes[i].vertices, plates[i].vertices);
  }
}

TEST(Samples, BlobStlIsBlob) {
  const auto meshes = load_mesh_file(std::string(PIERCE_SAMPLES_DIR) + "/blob.stl");
  const gen::Mesh blob = gen::blob(3);
  ASSERT_EQ(meshes.size(), 1u);
  ASSERT_EQ(meshes[0].triangles.size(), blob.triangles.size());
  for (std::size_t i = 0; i < blob.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      // Compared as floats (binary STL stores floats). Not as Vec3d(Vec3f(v)): GCC 12.2 at -O3
      // vectorizes that round trip away for x and y here.
      EXPECT_EQ(Vec3f(meshes[0].vertices[meshes[0].triangles[i][k]]), Vec3f(blob.vertices[blob.triangles[i][k]]))
          << "triangle " << i;
    }
}

// ---- errors ------------------------------------------------------------------------------------

struct ErrorCase {
  const char* name;
  const char* file;
  std::string content;
  std::string where;  // the place in the message: ":3:" (line 3), ": face 1 (byte offset 40", ...
  const char* what;   // expected somewhere in the message
};

std::string binary_stl_with(std::uint32_t declared, std::size_t facets) {
  std::string s(80, ' ');
  put(s, declared);
  s.append(facets * 50, '\0');
  return s;
}

std::string binary_ply_header(const char* fmt, int nv, int nf) {
  return std::string("ply\nformat ") + fmt + " 1.0\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string binary_ply_vertices(int n, float x = 0.f, bool big = false) {
  std::string s;
  for (int i = 0; i < n; ++i) put(s, x, big), put(s, 1.f, big), put(s, 2.f, big);
  return s;
}

std::string binary_ply_face(std::initializer_list<std::int32_t> idx, bool big = false) {
  std::string s;
  put(s, std::uint8_t(idx.size()));
  for (auto i : idx) put(s, i, big);
  return s;
}

std::vector<ErrorCase> error_cases() {
  const std::string tri3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string off_head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ply_le_3_1 = binary_ply_header("binary_little_endian", 3, 1);
  const std::string ply_be_3_2 = binary_ply_header("binary_big_endian", 3, 2);
  auto offset = [](std::size_t n) { return std::to_string(n) + ")"; };
  std::string nan_stl = binary_stl_with(1, 1);
  {
    std::string nan;
    put(nan, std::numeric_limits<float>::quiet_NaN());
    nan_stl.replace(84 + 12 + 12 + 4, 4, nan);  // triangle 0, vertex 1, y
  }
  return {
      {"obj_bad_number", "bad_number.obj", "v 0 0 0\nv 1 zero 0\n", ":2:", "bad number 'zero'"},
      {"obj_index_out_of_range", "range.obj", tri3 + "f 1 2 3\nf 1 2 4\n", ":5:", "out of range"},
      {"obj_forward_index_out_of_range", "fwd.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\n", ":2:", "out of range"},
      {"obj_relative_out_of_range", "rel.obj", tri3 + "f -1 -2 -4\n", ":4:", "out of range"},
      {"obj_index_zero", "zero.obj", tri3 + "f 0 1 2\n", ":4:", "index 0"},
      {"obj_bad_index", "badidx.obj", tri3 + "f 1 2 x/1\n", ":4:", "bad vertex index"},
      {"obj_two_vertices", "two.obj", tri3 + "f 1 2\n", ":4:", "face with 2 vertices"},
      {"obj_nan", "nan.obj", "v 0 0 0\nv 0 nan 0\nv 0 1 0\nf 1 2 3\n", ":2:", "NaN"},
      {"obj_inf", "inf.obj", "v 0 0 0\nv 0 0 -inf\nv 0 1 0\nf 1 2 3\n", ":2:", "infinite"},
      {"obj_beyond_float", "big.obj", "v 0 0 1e39\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ":1:", "single-precision"},
      {"obj_short_vertex", "short.obj", "v 0 0\n", ":1:", "3 coordinates"},
      {"obj_free_form", "curve.obj", tri3 + "cstype bspline\n", ":4:", "free-form"},
      {"obj_no_faces", "nofaces.obj", tri3, "", "no faces"},
      {"obj_empty", "empty.obj", "", "", "empty"},
      {"obj_blank", "blank.obj", "  \n\n \t\n", "", "empty"},
      {"off_bad_header", "hdr.off", "PFF\n3 1 0\n", ":1:", "expected 'OFF'"},
      {"off_4d", "four.off", "4OFF\n3 1 0\n", ":1:", "unsupported OFF variant"},
      {"off_bad_count", "count.off", "OFF\n3 x 0\n", ":2:", "bad face count"},
      {"off_truncated_vertices", "trunc.off", "OFF\n# c\n3 1 0\n0 0 0\n1 0 0\n", ":5:", "expected 3 vertices"},
      {"off_index_out_of_range", "range.off", off_head + "3 0 1 3\n", ":6:", "out of range"},
      {"off_negative_index", "neg.off", off_head + "3 0 -1 2\n", ":6:", "out of range"},
      {"off_face_two", "two.off", off_head + "2 0 1\n", ":6:", "face with 2 vertices"},
      {"off_face_short", "fshort.off", off_head + "4 0 1 2\n", ":6:", "lists 3"},
      {"off_bad_number", "num.off", "OFF\n3 1 0\n0 0 0\n1 0 0.0.0\n0 1 0\n3 0 1 2\n", ":4:", "bad number"},
      {"off_nan", "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 NaN\n0 1 0\n3 0 1 2\n", ":4:", "NaN"},
      {"ply_not_ply", "not.ply", "plx\n", ":1:", "not a PLY file"},
      {"ply_unknown_format", "fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", ":2:", "unknown PLY format"},
      {"ply_no_end_header", "noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", ":3:", "end_header"},
      {"ply_unknown_type", "type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty quad x\nend_header\n", ":4:",
       "unknown type"},
      {"ply_no_faces_element", "noface.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
       "", "no 'face' element"},
      {"ply_ascii_bad_number", "num.ply", ply_head + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n", ":12:", "bad number"},
      {"ply_ascii_index_out_of_range", "range.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":13:", "face 0"},
      {"ply_ascii_face_two", "two.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ":13:", "face with 2 vertices"},
      {"ply_ascii_truncated", "trunc.ply", ply_head + "0 0 0\n1 0 0\n", ":11:", "unexpected end of file"},
      {"ply_binary_truncated", "btrunc.ply",
       ply_le_3_1 + binary_ply_vertices(2) + "\x01\x02", ": vertex 2 (byte offset " + offset(ply_le_3_1.size() + 24),
       "truncated"},
      {"ply_binary_index_out_of_range", "brange.ply",
       ply_be_3_2 + binary_ply_vertices(3, 0.f, true) + binary_ply_face({0, 1, 2}, true) +
           binary_ply_face({0, 1, 7}, true),
       ": face 1 (byte offset " + offset(ply_be_3_2.size() + 36 + 13), "vertex index 7 out of range"},
      {"ply_binary_nan", "bnan.ply",
       ply_le_3_1 + binary_ply_vertices(1) + binary_ply_vertices(1, std::numeric_limits<float>::quiet_NaN()) +
           binary_ply_vertices(1) + binary_ply_face({0, 1, 2}),
       ": vertex 1 (byte offset " + offset(ply_le_3_1.size() + 12), "NaN"},
      {"stl_binary_truncated", "trunc.stl", binary_stl_with(3, 2) + std::string(20, '\0'), "triangle 2 at byte offset 184",
       "truncated binary STL"},
      {"stl_binary_short_header", "short.stl", std::string(40, 'x'), "", "truncated binary STL"},
      {"stl_binary_nan", "nan.stl", nan_stl, ": triangle 0, vertex 1 (byte offset 112)", "NaN"},
      {"stl_binary_no_faces", "none.stl", binary_stl_with(0, 0), "", "no faces"},
      {"stl_ascii_no_endsolid", "noend.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n",
       ":8:", "unexpected end of file"},
      {"stl_ascii_bad_number", "num.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 O\nendloop\nendfacet\nendsolid\n",
       ":6:", "bad number 'O'"},
      {"stl_ascii_two_vertices", "two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
       ":6:", "facet with 2 vertices"},
      {"stl_ascii_keyword", "kw.stl", "solid x\nfacet normal 0 0 1\nouter lop\n", ":3:", "expected 'loop'"},
      {"unknown_extension", "mesh.xyz", "v 0 0 0\n", "", "unknown model format"},
      {"no_extension", "mesh", "v 0 0 0\n", "", "unknown model format"},
  };
}

class BadFile : public TempDirTest, public ::testing::WithParamInterface<ErrorCase> {};

TEST_P(BadFile, InputErrorNamesFileAndPlace) {
  const ErrorCase& c = GetParam();
  const std::string path = file(c.file);
  write_text(path, c.content);
  try {
    load_mesh_file(path);
    FAIL() << "no error for " << c.name;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;  // starts with the path
    // A place starting with ':' follows the path directly ("path:12: ...", "path: face 3 (byte offset 40): ...").
    const std::string place = c.where.starts_with(':') ? path + c.where : c.where;
    EXPECT_NE(msg.find(place), std::string::npos) << "expected '" << place << "' in: " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << "expected '" << c.what << "' in: " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, BadFile, ::testing::ValuesIn(error_cases()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_F(MeshIo, MissingFileAndDirectory) {
  EXPECT_THROW(
      {
        try {
          load_mesh_file(file("missing.obj"));
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("missing.obj: cannot open"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
  std::filesystem::create_directories(file("dir.obj"));
  EXPECT_THROW(load_mesh_file(file("dir.obj")), InputError);
  Scene scene;
  EXPECT_THROW(add_model_files(scene, {file("missing.stl")}), InputError);
}

}  // namespace
}  // namespace pierce::test
