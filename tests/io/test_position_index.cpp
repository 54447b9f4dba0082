// Welding by exact position: first_equal_keys (parallel, partitioned) gives exactly the answer of
// PositionIndex (one table, one position at a time) on inputs big enough for many partitions and
// several chunks, with -0 and +0 distinct or merged, on one thread and on several; and a binary STL
// is welded into vertices in order of first occurrence, its triangles unchanged.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <bit>
#include <limits>
#include <map>
#include <random>

#include "mesh_writers.h"
#include "pierce/error.h"
#include "pierce/io/mesh_io.h"
#include "pierce/position_index.h"
#include "temp_dir.h"

namespace pierce::test {
namespace {

// 300 000 positions drawn from 40 000 distinct ones (so most repeat, far apart in the input), some
// differing only in the sign of a zero coordinate.
std::vector<Vec3d> repeated_positions() {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-50, 50);
  std::vector<Vec3d> distinct;
  for (int i = 0; i < 40000; ++i) {
    Vec3d p{coord(rng) * 0.25, coord(rng) * 0.5, double(coord(rng))};
    if (i % 7 == 0) p.y = (i % 14 == 0) ? -0.0 : 0.0;
    distinct.push_back(p);
  }
  std::uniform_int_distribution<std::size_t> pick(0, distinct.size() - 1);
  std::vector<Vec3d> out(300000);
  for (Vec3d& p : out) p = distinct[pick(rng)];
  return out;
}

std::vector<std::uint32_t> one_table(const std::vector<Vec3d>& positions, PositionZeros zeros) {
  PositionIndex index(16, zeros);
  std::vector<std::uint32_t> first(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) first[i] = index.find_or_insert(positions, std::uint32_t(i));
  return first;
}

TEST(FirstEqualKeys, SameAsOneTableOnAnyThreadCount) {
  const std::vector<Vec3d> positions = repeated_positions();
  for (const PositionZeros zeros : {PositionZeros::distinct, PositionZeros::merged}) {
    const std::vector<std::uint32_t> expected = one_table(positions, zeros);
    std::size_t repeats = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) repeats += expected[i] != i;
    ASSERT_GT(repeats, positions.size() / 2);  // the input does exercise the lookup
    for (const int threads : {1, 2, 4}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      const auto first = first_equal_keys<std::array<std::uint64_t, 3>>(
          positions.size(), [&](std::size_t i) { return position_key(positions[i], zeros); });
      EXPECT_EQ(first, expected) << "threads " << threads << ", zeros merged " << (zeros == PositionZeros::merged);
    }
  }
}

TEST(FirstEqualKeys, SmallAndEmptyInputs) {
  using Key = std::array<std::uint32_t, 3>;
  const auto key = [](std::size_t i) { return Key{std::uint32_t(i % 3), 0, 0}; };
  EXPECT_TRUE(first_equal_keys<Key>(0, key).empty());
  const std::vector<std::uint32_t> expected{0, 1, 2, 0, 1, 2, 0};
  EXPECT_EQ(first_equal_keys<Key>(7, key), expected);
}

using BinaryStlWeld = TempDirTest;

// Vertices in order of first occurrence by float bits, as the reader promises.
TEST_F(BinaryStlWeld, VerticesInFirstOccurrenceOrder) {
  const std::vector<Vec3d> positions = repeated_positions();
  PolyMesh m;
  m.vertices = positions;
  for (std::uint32_t i = 0; i + 2 < positions.size(); i += 3) m.faces.push_back({i, i + 1, i + 2});
  write_text(file("weld.stl"), stl_binary_data(m));
  const auto loaded = load_mesh_file(file("weld.stl"));
  ASSERT_EQ(loaded.size(), 1u);
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> seen;
  std::vector<Vec3d> vertices;
  std::vector<Tri> triangles;
  for (const auto& f : m.faces) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      const Vec3d& p = positions[f[std::size_t(k)]];
      const std::array<std::uint32_t, 3> bits{std::bit_cast<std::uint32_t>(float(p.x)),
                                              std::bit_cast<std::uint32_t>(float(p.y)),
                                              std::bit_cast<std::uint32_t>(float(p.z))};
      const auto [it, fresh] = seen.emplace(bits, std::uint32_t(vertices.size()));
      if (fresh) vertices.push_back(Vec3d(Vec3f(p)));
      t[std::size_t(k)] = it->second;
    }
    triangles.push_back(t);
  }
  EXPECT_EQ(loaded[0].triangles, triangles);
  ASSERT_EQ(loaded[0].vertices.size(), vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (std::size_t a = 0; a < 3; ++a)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(loaded[0].vertices[i][a]), std::bit_cast<std::uint64_t>(vertices[i][a]))
          << "vertex " << i;  // bits: -0 and +0 stay apart
}

// The binary reader checks the corners in parallel and still names the first bad one in the file.
TEST_F(BinaryStlWeld, NamesTheFirstBadCorner) {
  PolyMesh m;
  for (std::uint32_t i = 0; i < 200000; ++i) {
    m.vertices.push_back({double(i % 97), double(i % 89), double(i % 83)});
    if (i >= 2) m.faces.push_back({i - 2, i - 1, i});
  }
  m.vertices[150001].z = std::numeric_limits<double>::infinity();  // first in triangle 149999, corner 2
  m.vertices[190000].x = std::numeric_limits<double>::quiet_NaN();
  write_text(file("bad.stl"), stl_binary_data(m));
  try {
    load_mesh_file(file("bad.stl"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string offset = std::to_string(84 + 149999 * 50 + 12 + 12 * 2 + 8);
    EXPECT_NE(std::string(e.what()).find("triangle 149999, vertex 2 (byte offset " + offset + "): infinite"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace pierce::test
