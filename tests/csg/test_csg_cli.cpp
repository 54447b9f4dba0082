// The `pierce shot`, `pierce gqa` and `pierce run` commands end to end: output formats, JSON keys,
// error messages and exit codes, no clobbering without --force.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "csg_test_scenes.h"
#include "effect_scene.h"
#include "pierce/generators.h"
#include "png_decode.h"

namespace pierce {
namespace {

namespace fs = std::filesystem;

using csgtest::Outcome;

class CsgCli : public csgtest::CliTest {
 protected:
  CsgCli() : CliTest("pierce_csg_cli") {}
};

std::string boxes_obj() {
  return gen::to_obj({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.75, 0, 0}, {1.75, 1, 1}, "b"),
                      gen::box({3, 0, 0}, {4, 1, 1}, "c")});
}

TEST_F(CsgCli, GqaJsonHasSolidsWithVolumeCentroidAndOverlaps) {
  write("boxes.obj", boxes_obj());
  const Outcome r = pierce("gqa boxes.obj --start-n 16 --json gqa.json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("OVERLAP a <-> b"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("converged"), std::string::npos);
  const auto j = nlohmann::json::parse(read(path("gqa.json")));
  ASSERT_EQ(j["solids"].size(), 3u);
  const auto& a = j["solids"][0];
  EXPECT_EQ(a["name"], "a");
  EXPECT_NEAR(a["volume"].get<double>(), 1.0, 1e-5);
  EXPECT_NEAR(a["centroid"][0].get<double>(), 0.5, 1e-5);
  ASSERT_EQ(a["overlaps"].size(), 1u);
  const auto& ov = a["overlaps"][0];
  EXPECT_EQ(ov["a"], "a");
  EXPECT_EQ(ov["b"], "b");
  EXPECT_GT(ov["count"].get<int>(), 0);
  EXPECT_NEAR(ov["max_depth"].get<double>(), 1.0, 1e-5);
  EXPECT_EQ(ov["at"].size(), 3u);
  EXPECT_TRUE(j["solids"][2]["overlaps"].empty());
  EXPECT_EQ(j["converged"], true);
  ASSERT_EQ(j["gaps"].size(), 1u);

  // No clobbering without --force; the file stays as it was.
  const std::string before = read(path("gqa.json"));
  expect_input_error("gqa boxes.obj --json gqa.json", "gqa.json");
  EXPECT_EQ(read(path("gqa.json")), before);
  EXPECT_EQ(pierce("gqa boxes.obj --json gqa.json --force --tol 0.01").code, 0);
}

TEST_F(CsgCli, GqaRegionsAndBadExpressions) {
  write("boxes.obj", boxes_obj());
  const Outcome r = pierce("gqa boxes.obj --start-n 16 --csg 'union(a, b)' --json g.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(read(path("g.json")));
  ASSERT_EQ(j["regions"].size(), 1u);
  EXPECT_NEAR(j["regions"][0]["volume"].get<double>(), 1.75, 1e-5);
  expect_input_error("gqa boxes.obj --csg 'union(a, wing)'", "unknown solid name 'wing'");
}

TEST_F(CsgCli, ShotTableCsvAndJson) {
  write("boxes.obj", boxes_obj());
  const Outcome table = pierce("shot boxes.obj --from -1,0.5,0.5 --dir 1,0,0");
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.find("overlap  a+b"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("gap      b | c"), std::string::npos) << table.out;

  const Outcome csv = pierce("shot boxes.obj --from -1,0.5,0.5 --dir 1,0,0 --format csv -o shot.csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  std::istringstream lines(read(path("shot.csv")));
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 6u);  // header, a, a+b, b, gap, c
  EXPECT_EQ(rows[0].rfind("ray,kind,solids,in_x", 0), 0u);
  EXPECT_EQ(rows[4].rfind("0,gap,b+c,1.75,0.5,0.5,3,0.5,0.5,1.25,nan,nan,nan,", 0), 0u) << rows[4];

  const Outcome json = pierce("shot boxes.obj --grid axis=x,n=2 --csg 'difference(a, b)' --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j["rays"].size(), 4u);
  EXPECT_EQ(j["rays"][0]["rows"][0]["kind"], "region");
  EXPECT_NEAR(j["rays"][0]["rows"][0]["los"].get<double>(), 0.75, 1e-6);
}

TEST_F(CsgCli, ShotRejectsBadArguments) {
  write("boxes.obj", boxes_obj());
  expect_input_error("shot boxes.obj --from 1,2 --dir 1,0,0", "--from '1,2'");
  expect_input_error("shot boxes.obj --from 0,0,0 --dir 1,0,0 --grid axis=z,n=2", "exactly one of");
  expect_input_error("shot boxes.obj --from 0,0,0 --dir 1,0,0 --csg 'union(a,'", "column 9");
  const Outcome d = pierce("shot boxes.obj --from 0,0,0 --dir 0,0,0");
  EXPECT_EQ(d.code, 2);
}

TEST_F(CsgCli, RunXraySceneWritesImagesAndReportsSavedWork) {
  write("stack.obj", gen::to_obj(gen::stacked_plates(20, 1.0, 0.1)));
  write("xray.json", R"js({
    "models": ["stack.obj"],
    "materials": {"lead": {"mu": 5, "density": 11.3}},
    "solids": {"*": "lead"},
    "rays": "grid:axis=z,n=8",
    "effects": {"xray": {"threshold": 0.001, "image": "out/xray.png", "vti": "out/xray.vti"}},
    "output": {"rays": "out/rays.csv", "report": "out/report.json"}
  })js");
  const Outcome r = pierce("run xray.json --audit");
  ASSERT_EQ(r.code, 0) << r.err;
  // exp(-0.5 k) < 1e-3 first after k = 14 plates: 30 of the 40 hits of each of the 64 rays.
  EXPECT_NE(r.out.find("hits traversed: 1920 of 2560 existing"), std::string::npos) << r.out;
  const auto rep = nlohmann::json::parse(read(path("out/report.json")));
  EXPECT_EQ(rep["hits_traversed"], 1920);
  EXPECT_EQ(rep["hits_existing"], 2560);
  EXPECT_EQ(rep["work"]["effect_updates"]["classification"], 0);
  EXPECT_EQ(rep["xray"]["rays_below_threshold"], 64);
  EXPECT_EQ(read(path("out/xray.png")).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_NE(read(path("out/xray.vti")).find("WholeExtent=\"0 7 0 7 0 0\""), std::string::npos);
  // Outputs exist now: a second run refuses to overwrite them.
  expect_input_error("run xray.json", "not overwriting");
  EXPECT_EQ(pierce("run xray.json --out-dir elsewhere").code, 0);
  EXPECT_TRUE(fs::exists(path("elsewhere/out/xray.png")));
}

TEST_F(CsgCli, RunXrayImageMatchesBeerLambertPixelByPixel) {
  // Alternating lead (mu 5) and foam (mu 0.5) plates under an oblique camera: pixels see different
  // path lengths, some rays leave through the sides, some miss, some fall below the threshold.
  write("stack.obj", gen::to_obj(gen::stacked_plates(20, 1.0, 0.1)));
  std::string solids;
  for (int i = 0; i < 20; ++i) {
    if (i) solids += ", ";
    solids.append("\"plate").append(std::to_string(i)).append(i % 2 ? "\": \"foam\"" : "\": \"lead\"");
  }
  write("cam.json", R"js({"models": "stack.obj",
    "materials": {"lead": {"mu": 5}, "foam": {"mu": 0.5}},
    "solids": {)js" + solids + R"js(},
    "rays": {"camera": {"center": [0.5, 0.5, -1], "direction": [0.35, 0.15, 1], "up": [0, 1, 0],
                        "size": [1.6, 1.6], "pixels": [24, 20]}},
    "effects": {"xray": {"threshold": 0.02, "image": "x.png"}}})js");
  const Outcome r = pierce("run cam.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const csgtest::DecodedPng png = csgtest::decode_png(read(path("x.png")));
  ASSERT_EQ(png.error, "");
  ASSERT_EQ(png.width, 24u);
  ASSERT_EQ(png.height, 20u);
  EXPECT_EQ(png.bits, 16);
  cli::CameraSpec cam;
  cam.center = {0.5, 0.5, -1};
  cam.direction = {0.35, 0.15, 1};
  cam.up = {0, 1, 0};
  cam.width = cam.height = 1.6;
  cam.pixels_x = 24;
  cam.pixels_y = 20;
  const std::vector<Ray> rays = cli::camera_rays(cam);
  const double q = 1.0 / 65535;  // 16-bit quantisation
  int below = 0, above = 0, dark = 0;
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 0; x < 24; ++x) {
      const double exact = csgtest::plate_stack_transmission(rays[y * 24 + x], 20, 0.1, 5.0, 0.5);
      const double pixel = png.sample(x, y);
      if (exact >= 0.02 * 1.0001) {
        EXPECT_NEAR(pixel, exact, 2e-5 * exact + q) << x << "," << y;
        ++above;
        dark += exact < 0.5;
      } else if (exact < 0.02 * 0.9999) {
        EXPECT_LE(pixel, 0.02 + q) << x << "," << y;
        EXPECT_GE(pixel, exact - q) << x << "," << y;
        ++below;
      }
    }
  EXPECT_GT(below, 20);
  EXPECT_GT(dark, 20);
  EXPECT_GT(above - dark, 20);  // rays that miss or graze
}

TEST_F(CsgCli, RunThicknessOnlySceneBuildsNoPartitions) {
  write("stack.obj", gen::to_obj(gen::stacked_plates(20, 1.0, 0.1)));
  write("thick.json", R"js({"models": "stack.obj", "rays": "grid:axis=z,n=4", "effects": ["thickness"],
                            "output": {"rays": "rays.csv"}})js");
  const Outcome r = pierce("run thick.json --audit --report rep.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rep = nlohmann::json::parse(read(path("rep.json")));
  EXPECT_EQ(rep["work"]["partition_groups"], 0);
  EXPECT_EQ(rep["work"]["partitions_consumed"], 0);
  EXPECT_EQ(rep["hits_traversed"], 32);  // two per ray
  EXPECT_EQ(rep["hits_existing"], 640);
  EXPECT_NE(read(path("rays.csv")).find("thickness_solid,thickness_los,thickness_normal"), std::string::npos);
}

TEST_F(CsgCli, RunReportsSceneErrorsWithFileAndKey) {
  write("stack.obj", gen::to_obj(gen::stacked_plates(2, 1.0, 0.1)));
  write("bad.json", R"js({"models": "stack.obj", "rays": "random:n=4", "effects": {"xray": {"image": "x.png"}},
                          "materials": {"lead": {"mu": 1}}, "solids": {"*": "lead"}})js");
  expect_input_error("run bad.json", "images need rays that form one");
  write("typo.json", R"js({"models": "stack.obj", "rays": "grid", "effects": {"xray": {"treshold": 0.1}}})js");
  expect_input_error("run typo.json", "typo.json: effects.xray: unknown key 'treshold'");
  expect_input_error("run missing.json", "missing.json: cannot open");
}

}  // namespace
}  // namespace pierce
