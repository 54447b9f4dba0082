// vtkPierceThickness: known widths, touching and duplicated faces, point and cell sampling,
// triangulation of polygons, composite structure, agreement with the core analysis, errors and
// abort.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <vtkAppendPolyData.h>
#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkReverseSense.h>
#include <vtkSphereSource.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include "pierce/analysis/thickness.h"
#include "pierce/kernel.h"
#include "vtkPierceThickness.h"
#include "vtk_test_util.h"

namespace pierce::vtk_test {
namespace {

// Unit normal of cell c of a triangle surface.
Vec3d cell_normal(vtkPolyData* pd, vtkIdType c) {
  const vtkIdType* ids;
  vtkIdType n;
  pd->GetCellPoints(c, n, ids);
  double a[3], b[3], d[3];
  pd->GetPoint(ids[0], a);
  pd->GetPoint(ids[1], b);
  pd->GetPoint(ids[2], d);
  const Vec3d nrm = cross(Vec3d{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, Vec3d{d[0] - a[0], d[1] - a[1], d[2] - a[2]});
  return nrm * (1.0 / length(nrm));
}

// Expected per-cell thickness of an axis-aligned box: its extent along the face's normal.
void expect_box_widths(vtkPolyData* pd, Vec3d extent, const char* what) {
  vtkDataArray* thickness = pd->GetCellData()->GetArray("Thickness");
  ASSERT_NE(thickness, nullptr) << what;
  ASSERT_EQ(thickness->GetNumberOfTuples(), pd->GetNumberOfCells()) << what;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) {
    const Vec3d n = cell_normal(pd, c);
    const int axis = std::abs(n.x) > 0.5 ? 0 : (std::abs(n.y) > 0.5 ? 1 : 2);
    EXPECT_NEAR(thickness->GetTuple1(c), extent[std::size_t(axis)], 1e-9) << what << " cell " << c;
  }
}

TEST(VtkThickness, TouchingBoxesEachGetTheirOwnWidth) {
  // Two boxes sharing the face x = 1: each box's thickness is its own width, not the sum, not 0.
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 2, 3}, "left"), gen::box({1, 0, 0}, {3, 2, 3}, "right")});
  auto f = thickness_per_cell(mb);
  auto* out = vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  ASSERT_EQ(out->GetNumberOfBlocks(), 2u);
  EXPECT_STREQ(out->GetMetaData(1u)->Get(vtkCompositeDataSet::NAME()), "right");
  expect_box_widths(vtkPolyData::SafeDownCast(out->GetBlock(0)), {1, 2, 3}, "left");
  expect_box_widths(vtkPolyData::SafeDownCast(out->GetBlock(1)), {2, 2, 3}, "right");
  vtkDataArray* solid = vtkPolyData::SafeDownCast(out->GetBlock(1))->GetCellData()->GetArray("SolidId");
  ASSERT_NE(solid, nullptr);
  EXPECT_EQ(solid->GetRange()[0], 1.0);
  EXPECT_EQ(solid->GetRange()[1], 1.0);
  auto* names = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("SolidNames"));
  ASSERT_NE(names, nullptr);
  EXPECT_EQ(names->GetValue(0), "left");
}

TEST(VtkThickness, DuplicatedCoplanarFaceGivesTheTrueWidth) {
  auto f = thickness_per_cell(to_polydata(gen::duplicated(gen::box({0, 0, 0}, {2, 1, 1}), 2, false)));
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  expect_box_widths(out, {2, 1, 1}, "duplicated box");
}

TEST(VtkThickness, MinThicknessFlagsThinCells) {
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputData(to_polydata(gen::box({0, 0, 0}, {1, 4, 4})));
  f->SetSampleAt(vtkPierceThickness::CELLS);
  f->SetMinThickness(2.0);
  f->Update();
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  vtkDataArray* thickness = out->GetCellData()->GetArray("Thickness");
  vtkDataArray* thin = out->GetCellData()->GetArray("Thin");
  ASSERT_NE(thin, nullptr);
  int thin_cells = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) {
    EXPECT_EQ(thin->GetTuple1(c) == 1.0, thickness->GetTuple1(c) < 2.0);
    thin_cells += thin->GetTuple1(c) == 1.0;
  }
  EXPECT_EQ(thin_cells, 4);  // the two x faces
  // Both x faces are one thin region (id 0), across the wall; the others none.
  vtkDataArray* region = out->GetCellData()->GetArray("Region");
  ASSERT_NE(region, nullptr);
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
    EXPECT_EQ(region->GetTuple1(c), thin->GetTuple1(c) == 1.0 ? 0.0 : -1.0) << "cell " << c;
  vtkTable* stats = f->GetStatisticsOutput();
  ASSERT_NE(stats, nullptr);
  ASSERT_EQ(stats->GetNumberOfRows(), 1);
  EXPECT_EQ(stats->GetValueByName(0, "Thin").ToInt(), 4);
  EXPECT_DOUBLE_EQ(stats->GetValueByName(0, "Min").ToDouble(), 1.0);
  EXPECT_DOUBLE_EQ(stats->GetValueByName(0, "Max").ToDouble(), 4.0);
}

// Outer sphere radius 1 (outward), inner radius 0.95 (reversed): a 0.05 wall.
vtkSmartPointer<vtkPolyData> hollow_sphere(int resolution) {
  auto outer = vtkSmartPointer<vtkSphereSource>::New();
  outer->SetRadius(1.0);
  outer->SetThetaResolution(resolution);
  outer->SetPhiResolution(resolution);
  auto inner = vtkSmartPointer<vtkSphereSource>::New();
  inner->SetRadius(0.95);
  inner->SetThetaResolution(resolution);
  inner->SetPhiResolution(resolution);
  auto reverse = vtkSmartPointer<vtkReverseSense>::New();
  reverse->SetInputConnection(inner->GetOutputPort());
  auto append = vtkSmartPointer<vtkAppendPolyData>::New();
  append->AddInputConnection(outer->GetOutputPort());
  append->AddInputConnection(reverse->GetOutputPort());
  append->Update();
  return append->GetOutput();
}

TEST(VtkThickness, HollowSpherePointThicknessIsTheWall) {
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputData(hollow_sphere(48));
  f->Update();
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  vtkDataArray* thickness = out->GetPointData()->GetArray("Thickness");
  ASSERT_NE(thickness, nullptr);
  ASSERT_EQ(thickness->GetNumberOfTuples(), out->GetNumberOfPoints());
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "Thickness");
  vtkIdType close = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i) close += std::abs(thickness->GetTuple1(i) - 0.05) < 0.01;
  EXPECT_GE(double(close), 0.99 * double(out->GetNumberOfPoints()));
}

TEST(VtkThickness, PolygonsAndStripsAreTriangulated) {
  auto cube = vtkSmartPointer<vtkCubeSource>::New();  // 6 quads
  cube->SetBounds(0, 1, 0, 2, 0, 3);
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputConnection(cube->GetOutputPort());
  f->SetSampleAt(vtkPierceThickness::CELLS);
  f->Update();
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_EQ(out->GetNumberOfCells(), 12);
  ASSERT_EQ(out->GetPolys()->IsHomogeneous(), 3);
  expect_box_widths(out, {1, 2, 3}, "cube source");
}

TEST(VtkThickness, EqualsTheCoreAnalysisOnTheSameTriangles) {
  const gen::Mesh blob = gen::blob(2, 5, 0.2);
  for (int method : {vtkPierceThickness::RAY, vtkPierceThickness::CONE, vtkPierceThickness::SPHERE}) {
    auto f = vtkSmartPointer<vtkPierceThickness>::New();
    f->SetInputData(to_polydata(blob));
    f->SetMethod(method);
    f->Update();
    vtkDataArray* thickness = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0))->GetPointData()->GetArray("Thickness");

    const Scene scene = gen::to_scene({blob});
    const Accel accel(scene);
    analysis::ThicknessOptions o;
    o.method = method == vtkPierceThickness::CONE
                 ? analysis::ThicknessMethod::cone
                 : (method == vtkPierceThickness::SPHERE ? analysis::ThicknessMethod::sphere
                                                         : analysis::ThicknessMethod::ray);
    const analysis::ThicknessResult core = analysis::compute_thickness(accel, o);
    ASSERT_EQ(std::size_t(thickness->GetNumberOfTuples()), core.size());
    for (std::size_t i = 0; i < core.size(); ++i) {
      const double v = thickness->GetTuple1(vtkIdType(i));
      if (std::isnan(core.thickness[i])) {
        EXPECT_TRUE(std::isnan(v));
      } else {
        EXPECT_EQ(v, core.thickness[i]) << "method " << method << " vertex " << i;
      }
    }
  }
}

TEST(VtkThickness, OpenMeshGivesNaNAndNoExitStatus) {
  gen::Mesh open = gen::box({0, 0, 0}, {1, 1, 1});
  open.triangles.resize(10);  // two faces' worth of triangles removed
  auto f = thickness_per_cell(to_polydata(open));
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  vtkDataArray* thickness = out->GetCellData()->GetArray("Thickness");
  vtkDataArray* status = out->GetCellData()->GetArray("ThicknessStatus");
  int no_exit = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) {
    if (status->GetTuple1(c) == 1.0) {
      ++no_exit;
      EXPECT_TRUE(std::isnan(thickness->GetTuple1(c)));
    }
  }
  EXPECT_GT(no_exit, 0);
}

struct ErrorCase {
  const char* name;
  vtkSmartPointer<vtkPolyData> input;
  const char* expected;
};

vtkSmartPointer<vtkPolyData> lines_only() {
  auto pd = to_polydata(gen::box({0, 0, 0}, {1, 1, 1}));
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType ids[2] = {0, 1};
  lines->InsertNextCell(2, ids);
  pd->SetPolys(vtkSmartPointer<vtkCellArray>::New());
  pd->SetLines(lines);
  return pd;
}

vtkSmartPointer<vtkPolyData> with_nan_point() {
  auto pd = to_polydata(gen::box({0, 0, 0}, {1, 1, 1}));
  pd->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  return pd;
}

TEST(VtkThickness, BadInputIsAnErrorNotACrash) {
  const ErrorCase cases[] = {
    {"empty", vtkSmartPointer<vtkPolyData>::New(), "no cells"},
    {"lines only", lines_only(), "no polygons"},
    {"NaN point", with_nan_point(), "point 3"},
  };
  for (const ErrorCase& c : cases) {
    auto f = vtkSmartPointer<vtkPierceThickness>::New();
    auto messages = vtkSmartPointer<MessageCollector>::New();
    messages->Watch(f);
    messages->Watch(f->GetExecutive());
    f->SetInputData(c.input);
    f->Update();
    EXPECT_TRUE(messages->ErrorContains(c.expected)) << c.name << ": "
                                                     << (messages->errors.empty() ? "no error" : messages->errors[0]);
    auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
    EXPECT_TRUE(out == nullptr || out->GetNumberOfCells() == 0) << c.name;
  }
}

TEST(VtkThickness, AbortDuringProgressGivesAnEmptyOutput) {
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputData(hollow_sphere(64));
  int progress_events = 0;
  auto abort = vtkSmartPointer<vtkCallbackCommand>::New();
  abort->SetClientData(&progress_events);
  abort->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    ++*static_cast<int*>(client);
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  f->AddObserver(vtkCommand::ProgressEvent, abort);
  f->Update();
  EXPECT_GE(progress_events, 1);
  auto* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  EXPECT_TRUE(out == nullptr || out->GetPointData()->GetArray("Thickness") == nullptr);

  // Without the observer the same filter runs to the end.
  f->RemoveObserver(abort);
  f->SetAbortExecute(0);
  f->Modified();
  f->Update();
  out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  EXPECT_NE(out->GetPointData()->GetArray("Thickness"), nullptr);
}

}  // namespace
}  // namespace pierce::vtk_test
