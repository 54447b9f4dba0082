// vtkPierceRayClassify: partitions of line-cell and point-grid rays through touching,
// interpenetrating and inward-wound solids; table; errors.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkLineSource.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkReverseSense.h>
#include <vtkTable.h>

#include "vtkPierceRayClassify.h"
#include "vtk_test_util.h"

namespace pierce::vtk_test {
namespace {

double cell_value(vtkPolyData* pd, const char* array, vtkIdType c) {
  vtkDataArray* a = pd->GetCellData()->GetArray(array);
  EXPECT_NE(a, nullptr) << array;
  return a ? a->GetTuple1(c) : 0.0;
}

vtkSmartPointer<vtkLineSource> line(Vec3d a, Vec3d b) {
  auto l = vtkSmartPointer<vtkLineSource>::New();
  l->SetPoint1(a.x, a.y, a.z);
  l->SetPoint2(b.x, b.y, b.z);
  l->SetResolution(7);  // a polyline: first to last point is the ray
  return l;
}

TEST(VtkRayClassify, TouchingBoxesGiveAdjacentPartitions) {
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {3, 1, 1}, "b")});
  auto f = vtkSmartPointer<vtkPierceRayClassify>::New();
  f->SetInputData(mb);
  f->SetRaysConnection(line({-1, 0.5, 0.5}, {5, 0.5, 0.5})->GetOutputPort());
  f->IncludeGapsOn();
  f->Update();
  vtkPolyData* out = f->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), 2);  // no gap between touching solids
  EXPECT_EQ(cell_value(out, "SolidId", 0), 0.0);
  EXPECT_EQ(cell_value(out, "SolidId", 1), 1.0);
  EXPECT_NEAR(cell_value(out, "Depth", 0), 1.0, 1e-12);
  EXPECT_NEAR(cell_value(out, "Depth", 1), 2.0, 1e-12);
  EXPECT_EQ(cell_value(out, "TOut", 0), cell_value(out, "TIn", 1));
  EXPECT_NEAR(cell_value(out, "TIn", 0), 1.0, 1e-12);
  EXPECT_NEAR(cell_value(out, "EntryObliquity", 0), 0.0, 1e-9);
  EXPECT_EQ(f->GetInconsistentRays(), 0);

  vtkTable* table = f->GetTableOutput();
  ASSERT_EQ(table->GetNumberOfRows(), 2);
  EXPECT_EQ(table->GetValueByName(1, "Names").ToString(), "b");
  EXPECT_EQ(table->GetValueByName(1, "Kind").ToString(), "solid");
}

TEST(VtkRayClassify, OverlapAndGapAlongAGridOfRays) {
  // b overlaps a by 0.3 in x; c stands 0.5 apart from b.
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.7, 0, 0}, {2, 1, 1}, "b"),
                           gen::box({2.5, 0, 0}, {3, 1, 1}, "c")});
  auto grid = vtkSmartPointer<vtkPlaneSource>::New();  // 3 x 3 points in the plane x = -1
  grid->SetOrigin(-1, 0.2, 0.2);
  grid->SetPoint1(-1, 0.8, 0.2);
  grid->SetPoint2(-1, 0.2, 0.8);
  grid->SetResolution(2, 2);
  auto f = vtkSmartPointer<vtkPierceRayClassify>::New();
  f->SetInputData(mb);
  f->SetRaysConnection(grid->GetOutputPort());
  f->SetRayDirection(1, 0, 0);
  f->IncludeGapsOn();
  f->Update();
  vtkPolyData* out = f->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), 9 * 5);  // a | a+b | b | gap | c per ray
  for (vtkIdType ray = 0; ray < 9; ++ray) {
    const vtkIdType c = ray * 5;
    EXPECT_EQ(cell_value(out, "RayId", c), double(ray));
    EXPECT_EQ(cell_value(out, "SolidCount", c + 1), 2.0);
    EXPECT_EQ(cell_value(out, "SolidId", c + 1), -1.0);
    EXPECT_NEAR(cell_value(out, "Depth", c + 1), 0.3, 1e-6);  // float kernels
    EXPECT_EQ(cell_value(out, "SolidCount", c + 3), 0.0);  // the gap
    EXPECT_NEAR(cell_value(out, "Depth", c + 3), 0.5, 1e-6);
    EXPECT_EQ(cell_value(out, "SolidId", c + 4), 2.0);
  }
  EXPECT_EQ(f->GetTableOutput()->GetValueByName(1, "Kind").ToString(), "overlap");
  EXPECT_EQ(f->GetTableOutput()->GetValueByName(1, "Names").ToString(), "a+b");
}

TEST(VtkRayClassify, DirectionArrayAndMaxLength) {
  auto box = to_polydata(gen::box({0, 0, 0}, {1, 1, 1}));
  auto grid = vtkSmartPointer<vtkPlaneSource>::New();  // normals +z
  grid->SetOrigin(0.25, 0.25, 0.5);
  grid->SetPoint1(0.75, 0.25, 0.5);
  grid->SetPoint2(0.25, 0.75, 0.5);
  auto f = vtkSmartPointer<vtkPierceRayClassify>::New();
  f->SetInputData(box);
  f->SetRaysConnection(grid->GetOutputPort());
  f->SetRayDirection(1, 0, 0);  // ignored: the array wins
  f->UseDirectionArrayOn();
  f->SetDirectionArrayName("Normals");
  f->Update();
  vtkPolyData* out = f->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), 4);  // rays start inside: half the box above them
  for (vtkIdType c = 0; c < 4; ++c) {
    EXPECT_NEAR(cell_value(out, "Depth", c), 0.5, 1e-12);
    EXPECT_TRUE(std::isnan(cell_value(out, "EntryObliquity", c)));  // starts inside: no entry face
  }
  f->SetMaxLength(0.2);
  f->Update();
  EXPECT_NEAR(cell_value(f->GetOutput(), "Depth", 0), 0.2, 1e-12);

  f->SetDirectionArrayName("NoSuchArray");
  auto messages = vtkSmartPointer<MessageCollector>::New();
  messages->Watch(f);
  messages->Watch(f->GetExecutive());
  f->Update();
  EXPECT_TRUE(messages->ErrorContains("NoSuchArray"));
}

TEST(VtkRayClassify, InwardWoundSolidIsClassifiedAsIfFlipped) {
  auto reverse = vtkSmartPointer<vtkReverseSense>::New();
  reverse->SetInputData(to_polydata(gen::box({0, 0, 0}, {2, 1, 1})));
  auto f = vtkSmartPointer<vtkPierceRayClassify>::New();
  auto messages = vtkSmartPointer<MessageCollector>::New();
  messages->Watch(f);
  f->SetInputConnection(reverse->GetOutputPort());
  f->SetRaysConnection(line({-1, 0.5, 0.5}, {4, 0.5, 0.5})->GetOutputPort());
  f->Update();
  ASSERT_EQ(f->GetOutput()->GetNumberOfCells(), 1);
  EXPECT_NEAR(cell_value(f->GetOutput(), "Depth", 0), 2.0, 1e-12);
  ASSERT_FALSE(messages->warnings.empty());
  EXPECT_NE(messages->warnings[0].find("inward"), std::string::npos);
}

TEST(VtkRayClassify, RaysWithoutPointsAreAnError) {
  auto f = vtkSmartPointer<vtkPierceRayClassify>::New();
  auto messages = vtkSmartPointer<MessageCollector>::New();
  messages->Watch(f);
  messages->Watch(f->GetExecutive());
  f->SetInputData(to_polydata(gen::box({0, 0, 0}, {1, 1, 1})));
  f->SetRaysData(vtkSmartPointer<vtkPolyData>::New());
  f->Update();
  EXPECT_TRUE(messages->ErrorContains("no points"));
  EXPECT_EQ(f->GetOutput()->GetNumberOfCells(), 0);
}

}  // namespace
}  // namespace pierce::vtk_test
