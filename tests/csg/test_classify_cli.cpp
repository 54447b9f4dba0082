// `pierce classify` end to end: inside / outside / on of points for solids and CSG expressions, with
// expected classes that follow from the boxes' coordinates; output formats; errors for bad input.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "pierce/generators.h"

namespace pierce {
namespace {


using csgtest::Outcome;

class ClassifyCli : public csgtest::CliTest {
 protected:
  ClassifyCli() : CliTest("pierce_classify_cli") {}

  void SetUp() override {
    CliTest::SetUp();
    std::ofstream(path("boxes.obj")) << gen::to_obj({gen::box(kA.lo, kA.hi, "a"), gen::box(kB.lo, kB.hi, "b"),
                                                     gen::box(kC.lo, kC.hi, "c")});
  }

  struct Box {
    Vec3d lo, hi;
  };
  // a and b touch along x = 1; c lies strictly inside a.
  static constexpr Box kA{{0, 0, 0}, {1, 1, 1}};
  static constexpr Box kB{{1, 0, 0}, {2, 1, 1}};
  static constexpr Box kC{{0.25, 0.25, 0.25}, {0.75, 0.75, 0.75}};

  // The class of p for an axis-aligned box, from its coordinates alone.
  static std::string box_class(Vec3d p, const Box& b) {
    bool on = false;
    for (std::size_t i = 0; i < 3; ++i) {
      if (p[i] < b.lo[i] || p[i] > b.hi[i]) return "outside";
      on = on || p[i] == b.lo[i] || p[i] == b.hi[i];
    }
    return on ? "on" : "inside";
  }

  // {point index: {target: class}} from the CSV output.
  static std::map<std::size_t, std::map<std::string, std::string>> parse_csv(const std::string& text) {
    std::map<std::size_t, std::map<std::string, std::string>> m;
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "point,x,y,z,target,class");
    while (std::getline(in, line)) {
      // Fields, with "..." quoting ("" inside for a quote) as the command writes names.
      std::vector<std::string> f(1);
      bool quoted = false;
      for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') f.back() += line[++i];
        else if (c == '"') quoted = !quoted;
        else if (c == ',' && !quoted) f.emplace_back();
        else f.back() += c;
      }
      if (f.size() != 6) {
        ADD_FAILURE() << "bad CSV row: " << line;
        continue;
      }
      m[std::stoul(f[0])][f[4]] = f[5];
    }
    return m;
  }
};

// Inside, outside, on a face, an edge and a vertex, on the face two boxes share, inside the second.
const std::vector<Vec3d> kPoints = {
    {0.1, 0.5, 0.1},  // inside a only
    {3, 3, 3},        // outside everything
    {0, 0.5, 0.5},    // on a's face x = 0
    {0, 0, 0.5},      // on a's edge
    {0, 0, 0},        // on a's vertex
    {1, 0.5, 0.5},    // on the face a and b share
    {1, 1, 1},        // a vertex of both a and b
    {1.5, 0.5, 0.5},  // inside the touching box b
    {0.5, 0.5, 0.5},  // inside a and inside c
    {0.25, 0.5, 0.5}, // on c's face, inside a
    {2, 0.5, 1e-3},   // on b's far face
};

std::string points_csv() {
  std::ostringstream s;
  s << "x,y,z\n# a comment line\n\n";
  s.precision(17);
  for (const Vec3d& p : kPoints) s << p.x << ", " << p.y << "," << p.z << "\n";
  return s.str();
}

TEST_F(ClassifyCli, EverySolidFollowsFromTheBoxCoordinates) {
  write("pts.csv", points_csv());
  const Outcome r = pierce("classify boxes.obj --points pts.csv -o out.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto m = parse_csv(read(path("out.csv")));
  ASSERT_EQ(m.size(), kPoints.size());
  for (std::size_t i = 0; i < kPoints.size(); ++i) {
    const auto& row = m.at(i);
    ASSERT_EQ(row.size(), 3u);
    EXPECT_EQ(row.at("a"), box_class(kPoints[i], kA)) << "point " << i;
    EXPECT_EQ(row.at("b"), box_class(kPoints[i], kB)) << "point " << i;
    EXPECT_EQ(row.at("c"), box_class(kPoints[i], kC)) << "point " << i;
  }
  // The geometry really exercises every class.
  EXPECT_EQ(box_class(kPoints[0], kA), "inside");
  EXPECT_EQ(box_class(kPoints[3], kA), "on");
  EXPECT_EQ(box_class(kPoints[1], kA), "outside");
}

TEST_F(ClassifyCli, CsgUnionOfTouchingBoxesAndDifference) {
  write("pts.csv", points_csv());
  const Outcome r = pierce("classify boxes.obj --points pts.csv --csg 'union(a, b)' --csg 'difference(a, c)' "
                           "--format csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto m = parse_csv(r.out);
  ASSERT_EQ(m.size(), kPoints.size());
  auto cls = [&](std::size_t i, const std::string& e) { return m.at(i).at(e); };
  const std::string u = "union(a, b)", d = "difference(a, c)";
  // union(a, b) is the box [0, 2] x [0, 1] x [0, 1]: the shared face is inside it, no seam.
  const Box ab{{0, 0, 0}, {2, 1, 1}};
  for (std::size_t i = 0; i < kPoints.size(); ++i) EXPECT_EQ(cls(i, u), box_class(kPoints[i], ab)) << "point " << i;
  EXPECT_EQ(cls(5, u), "inside");
  // difference(a, c): a with the hole c.
  EXPECT_EQ(cls(0, d), "inside");
  EXPECT_EQ(cls(1, d), "outside");
  EXPECT_EQ(cls(2, d), "on");
  EXPECT_EQ(cls(8, d), "outside");  // inside the hole
  EXPECT_EQ(cls(9, d), "on");       // on the hole's face
  EXPECT_EQ(cls(7, d), "outside");  // in b only
}

TEST_F(ClassifyCli, PointOptionsTableAndJson) {
  Outcome r = pierce("classify boxes.obj --point 0.5,0.5,0.1 --point=-1,0.5,0.5 --point 1,0.5,0.5");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("point 0 (0.5 0.5 0.1): a inside, b outside, c outside"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("point 1 (-1 0.5 0.5): a outside, b outside, c outside"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("point 2 (1 0.5 0.5): a on, b on, c outside"), std::string::npos) << r.out;

  r = pierce("classify boxes.obj --point 1.5,0.5,0.5 --csg 'union(a,b)' -o out.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(read(path("out.json")));
  EXPECT_EQ(j["target_kind"], "csg");
  ASSERT_EQ(j["targets"].size(), 1u);
  EXPECT_EQ(j["targets"][0], "union(a,b)");
  ASSERT_EQ(j["points"].size(), 1u);
  EXPECT_EQ(j["points"][0]["at"][0], 1.5);
  EXPECT_EQ(j["points"][0]["classes"][0], "inside");
  EXPECT_GT(j["tolerance"].get<double>(), 0);

  // No overwrite without --force.
  expect_input_error("classify boxes.obj --point 0,0,0 -o out.json", "--force");
  EXPECT_EQ(nlohmann::json::parse(read(path("out.json")))["points"][0]["at"][0], 1.5);
  r = pierce("classify boxes.obj --point 0,0,0 -o out.json --force");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(ClassifyCli, BadPointsAreReportedWithFileAndLine) {
  struct Case {
    std::string csv, message;
  };
  const std::vector<Case> cases = {
      {"x,y,z\n0,0,0\n1,2\n", "pts.csv, line 3: expected three comma-separated numbers x,y,z, found 2 fields"},
      {"0,0,0\n0,abc,0\n", "pts.csv, line 2: field 2 ('abc') is not a number"},
      {"0,0,0,4\n", "pts.csv, line 1: expected three comma-separated numbers x,y,z, found 4 fields"},
      {"0,0,inf\n", "pts.csv, line 1: field 3 ('inf') is not finite"},
      {"1,2,3x\n", "pts.csv, line 1: field 3 ('3x') is not a number"},
      {"0,,0\n", "pts.csv, line 1: field 2 ('') is not a number"},
      {"x,y,z\n# nothing\n", "pts.csv: no points"},
  };
  for (const Case& c : cases) {
    write("pts.csv", c.csv);
    const Outcome r = pierce("classify boxes.obj --points pts.csv");
    EXPECT_EQ(r.code, 2) << c.csv;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.csv << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  expect_input_error("classify boxes.obj --points missing.csv", "missing.csv: cannot open");
  expect_input_error("classify boxes.obj --point 1,2", "--point '1,2': expected three");
  expect_input_error("classify boxes.obj", "give either --point");
  expect_input_error("classify boxes.obj --point 0,0,0 --csg 'union(a, zz)'", "unknown solid name");
  expect_input_error("classify boxes.obj --point 0,0,0 --format xml", "--format 'xml'");
}

}  // namespace
}  // namespace pierce
