// vtkPierceOverlaps: interpenetrating solids reported with pair and depth, touching solids as
// contact and coplanar faces (never as interference), per-triangle arrays, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkTable.h>

#include "vtkPierceOverlaps.h"
#include "vtk_test_util.h"

namespace pierce::vtk_test {
namespace {

// Rows of the pair table with this kind, as (SolidA, SolidB) -> row index.
std::vector<vtkIdType> rows_of(vtkTable* t, const std::string& kind) {
  std::vector<vtkIdType> rows;
  for (vtkIdType r = 0; r < t->GetNumberOfRows(); ++r)
    if (t->GetValueByName(r, "Kind").ToString() == kind) rows.push_back(r);
  return rows;
}

TEST(VtkOverlaps, InterpenetratingAndTouchingSolids) {
  // a = [0,1]^3; b pokes 0.25 into a through x = 1; c touches a at x = 0.
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.75, 0.25, 0.25}, {2, 0.75, 0.75}, "b"),
                           gen::box({-1, 0, 0}, {0, 1, 1}, "c")});
  auto f = vtkSmartPointer<vtkPierceOverlaps>::New();
  f->SetInputData(mb);
  f->SetRaysPerAxis(20);
  f->Update();
  vtkTable* pairs = f->GetPairsOutput();
  ASSERT_NE(pairs, nullptr);

  const auto interference = rows_of(pairs, "interference");
  ASSERT_EQ(interference.size(), 1u);
  const vtkIdType r = interference[0];
  EXPECT_EQ(pairs->GetValueByName(r, "SolidA").ToInt(), 0);
  EXPECT_EQ(pairs->GetValueByName(r, "SolidB").ToInt(), 1);
  EXPECT_EQ(pairs->GetValueByName(r, "NameB").ToString(), "b");
  EXPECT_NEAR(pairs->GetValueByName(r, "Penetration").ToDouble(), 0.25, 1e-9);
  EXPECT_GT(pairs->GetValueByName(r, "Count").ToInt(), 0);

  // a and c only touch: a contact and a coplanar pair, no interference.
  bool contact_ac = false, coplanar_ac = false;
  for (vtkIdType k : rows_of(pairs, "contact"))
    contact_ac |= pairs->GetValueByName(k, "SolidA").ToInt() == 0 && pairs->GetValueByName(k, "SolidB").ToInt() == 2;
  for (vtkIdType k : rows_of(pairs, "coplanar")) {
    if (pairs->GetValueByName(k, "SolidA").ToInt() == 0 && pairs->GetValueByName(k, "SolidB").ToInt() == 2) {
      coplanar_ac = true;
      EXPECT_NEAR(pairs->GetValueByName(k, "Area").ToDouble(), 1.0, 1e-12);
    }
  }
  EXPECT_TRUE(contact_ac);
  EXPECT_TRUE(coplanar_ac);

  auto* out = vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  auto* c = vtkPolyData::SafeDownCast(out->GetBlock(2));
  vtkDataArray* partner = c->GetCellData()->GetArray("CoplanarPartner");
  vtkDataArray* overlap = c->GetCellData()->GetArray("OverlapCount");
  ASSERT_NE(partner, nullptr);
  ASSERT_NE(overlap, nullptr);
  int partnered = 0;
  for (vtkIdType k = 0; k < c->GetNumberOfCells(); ++k) partnered += partner->GetTuple1(k) == 0.0;
  EXPECT_EQ(partnered, 2);  // c's two triangles on x = 0 lie on a's face
  auto* b = vtkPolyData::SafeDownCast(out->GetBlock(1));
  EXPECT_GT(b->GetCellData()->GetArray("InterferenceHits")->GetRange()[1], 0.0);
  EXPECT_NE(out->GetFieldData()->GetArray("CoplanarRayShareEqual"), nullptr);
}

TEST(VtkOverlaps, SeparateSolidsHaveNoPairs) {
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({2, 0, 0}, {3, 1, 1}, "b")});
  auto f = vtkSmartPointer<vtkPierceOverlaps>::New();
  f->SetInputData(mb);
  f->SetRaysPerAxis(8);
  f->Update();
  EXPECT_EQ(f->GetPairsOutput()->GetNumberOfRows(), 0);
  auto* a = vtkPolyData::SafeDownCast(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0))->GetBlock(0));
  EXPECT_EQ(a->GetCellData()->GetArray("OverlapCount")->GetRange()[1], 0.0);
}

TEST(VtkOverlaps, ClearanceArrayMeasuresTheGap) {
  // b is 0.3 from a's face x = 1; a's face x = 0 is 1.3 away, beyond the clearance.
  auto mb = to_multiblock({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1.3, 0, 0}, {2.3, 1, 1}, "b")});
  auto f = vtkSmartPointer<vtkPierceOverlaps>::New();
  f->SetInputData(mb);
  f->SetRaysPerAxis(8);
  f->SetClearance(0.5);
  f->Update();
  auto* a = vtkPolyData::SafeDownCast(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0))->GetBlock(0));
  vtkDataArray* clearance = a->GetCellData()->GetArray("Clearance");
  ASSERT_NE(clearance, nullptr);
  ASSERT_EQ(clearance->GetNumberOfTuples(), a->GetNumberOfCells());
  for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c) {
    double xmax = 0;
    for (vtkIdType k = 0; k < 3; ++k) xmax = std::max(xmax, a->GetPoint(a->GetCell(c)->GetPointId(int(k)))[0]);
    EXPECT_NEAR(clearance->GetTuple1(c), xmax == 1.0 ? 0.3 : 0.5, 1e-9) << c;
  }
}

TEST(VtkOverlaps, EmptyInputIsAnError) {
  auto f = vtkSmartPointer<vtkPierceOverlaps>::New();
  auto messages = vtkSmartPointer<MessageCollector>::New();
  messages->Watch(f);
  messages->Watch(f->GetExecutive());
  f->SetInputData(vtkSmartPointer<vtkMultiBlockDataSet>::New());
  f->Update();
  EXPECT_TRUE(messages->ErrorContains("no cells"));
}

}  // namespace
}  // namespace pierce::vtk_test
