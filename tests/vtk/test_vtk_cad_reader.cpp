// vtkPierceCADReader on a STEP assembly written here: one block per solid with its assembly name,
// placements, SolidId; then thickness per solid through the reader's output; errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <limits>
#include <map>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include "pierce/analysis/thickness.h"
#include "pierce/io/cad_registry.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/io/model_io.h"
#include "step_assembly.h"
#include "vtkPierceCADReader.h"
#include "vtkPierceThickness.h"
#include "vtk_test_util.h"

namespace pierce::vtk_test {
namespace {

namespace fs = std::filesystem;

const std::string& assembly_path() {
  static const std::string path = [] {
    const fs::path dir = fs::temp_directory_path() / ("pierce_vtk_cad_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string p = (dir / "assembly.step").string();
    test_models::write_step_assembly(p);
    return p;
  }();
  return path;
}

std::map<std::string, vtkPolyData*> blocks_by_name(vtkMultiBlockDataSet* mb) {
  std::map<std::string, vtkPolyData*> m;
  for (unsigned int i = 0; i < mb->GetNumberOfBlocks(); ++i)
    m[mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())] = vtkPolyData::SafeDownCast(mb->GetBlock(i));
  return m;
}

TEST(VtkCadReader, StepAssemblyGivesOneNamedBlockPerSolid) {
  auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
  reader->SetFileName(assembly_path().c_str());
  reader->Update();
  vtkMultiBlockDataSet* out = reader->GetOutput();
  ASSERT_EQ(out->GetNumberOfBlocks(), 4u);
  auto blocks = blocks_by_name(out);
  ASSERT_EQ(blocks.count("plate_assy/plate"), 1u);
  ASSERT_EQ(blocks.count("plate_assy/block#2"), 1u);
  double b[6];
  blocks["plate_assy/block#2"]->GetBounds(b);
  EXPECT_NEAR(b[0], 6.0, 1e-9);
  EXPECT_NEAR(b[4], 2.0, 1e-9);
  blocks["plate_assy/clash"]->GetBounds(b);
  EXPECT_NEAR(b[4], 1.5, 1e-9);
  auto* units = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("Units"));
  ASSERT_NE(units, nullptr);
  EXPECT_EQ(units->GetValue(0), "mm");
  EXPECT_NE(blocks["plate_assy/plate"]->GetCellData()->GetArray("SolidId"), nullptr);
}

TEST(VtkCadReader, ThicknessOfTheAssemblyIsEachPartsOwnWidth) {
  auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
  reader->SetFileName(assembly_path().c_str());
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputConnection(reader->GetOutputPort());
  f->SetSampleAt(vtkPierceThickness::CELLS);
  f->Update();
  auto blocks = blocks_by_name(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0)));
  // The block touches the plate and the clash is sunk into it: neither changes the plate's
  // thickness, which is 2 through z and 10 through x and y.
  vtkPolyData* plate = blocks["plate_assy/plate"];
  vtkDataArray* t = plate->GetCellData()->GetArray("Thickness");
  ASSERT_NE(t, nullptr);
  for (vtkIdType c = 0; c < plate->GetNumberOfCells(); ++c) {
    const double v = t->GetTuple1(c);
    EXPECT_TRUE(std::abs(v - 2.0) < 1e-6 || std::abs(v - 10.0) < 1e-6) << "cell " << c << ": " << v;
  }
  vtkDataArray* tb = blocks["plate_assy/block"]->GetCellData()->GetArray("Thickness");
  EXPECT_NEAR(tb->GetRange()[0], 2.0, 1e-6);
  EXPECT_NEAR(tb->GetRange()[1], 2.0, 1e-6);
}

// The reader marks folded triangles (none here, every box meshes cleanly); the thickness filter
// gives samples that start on or leave through a marked triangle the status tessellation (3), leaves them out of
// the statistics and counts them in the table's Tessellation column.
TEST(VtkCadReader, FoldedTrianglesGiveTheTessellationStatus) {
  auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
  reader->SetFileName(assembly_path().c_str());
  reader->Update();
  auto blocks = blocks_by_name(reader->GetOutput());
  vtkPolyData* plate = blocks["plate_assy/plate"];
  vtkDataArray* folded = plate->GetCellData()->GetArray("TessellationFolded");
  ASSERT_NE(folded, nullptr);
  ASSERT_EQ(folded->GetNumberOfTuples(), plate->GetNumberOfCells());
  EXPECT_EQ(folded->GetRange()[1], 0.0);
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(plate);
  vtkDataArray* marks = copy->GetCellData()->GetArray("TessellationFolded");
  marks->SetTuple1(0, 1);
  auto f = thickness_per_cell(copy);
  vtkPolyData* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  vtkDataArray* status = out->GetCellData()->GetArray("ThicknessStatus");
  vtkDataArray* t = out->GetCellData()->GetArray("Thickness");
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->GetTuple1(0), 3.0);
  EXPECT_TRUE(std::isnan(t->GetTuple1(0)));
  vtkTable* stats = f->GetStatisticsOutput();
  ASSERT_NE(stats, nullptr);
  vtkAbstractArray* tess = stats->GetColumnByName("Tessellation");
  ASSERT_NE(tess, nullptr);
  // The marked cell, and any whose ray leaves through it (the opposite face's).
  int marked = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) marked += status->GetTuple1(c) == 3.0;
  EXPECT_GE(marked, 1);
  EXPECT_EQ(tess->GetVariantValue(0).ToInt(), marked);
  EXPECT_EQ(stats->GetColumnByName("Valid")->GetVariantValue(0).ToInt(), plate->GetNumberOfCells() - marked);
}

// vtkPierceThickness per cell on CAD reader output whose B-rep link no longer holds: it warns
// with `why` and measures the mesh (OnBRep 0).
vtkSmartPointer<vtkPierceThickness> thickness_on_mesh_with_warning(vtkPolyData* input, const std::string& why) {
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  auto messages = vtkSmartPointer<MessageCollector>::New();
  messages->Watch(f);
  f->SetInputData(input);
  f->SetSampleAt(vtkPierceThickness::CELLS);
  f->Update();
  bool warned = false;
  for (const std::string& w : messages->warnings) warned = warned || w.find(why) != std::string::npos;
  EXPECT_TRUE(warned) << "no warning containing '" << why << "'";
  EXPECT_EQ(f->GetStatisticsOutput()->GetColumnByName("OnBRep")->GetVariantValue(0).ToInt(), 0);
  return f;
}

// The thin blended plate (tests/occt/step_assembly.h): its bare mesh reads 0.07 at the blends of
// the 0.3 sheet. Through the reader the filter measures the exact B-rep, bit for bit what core
// gives on the same file; moved after reading, the link no longer holds: the mesh is measured,
// with a warning that says why.
TEST(VtkCadReader, CadInputIsMeasuredOnTheExactBRep) {
  const std::string path = (fs::path(assembly_path()).parent_path() / "thin_plate.brep").string();
  test_models::write_brep(test_models::thin_blended_plate(), path);
  Scene scene;
  const std::vector<LoadedFile> files = add_any_model(scene, {path});
  const auto exact = cad_surfaces(files, scene.geometries().size());
  ASSERT_NE(exact, nullptr);
  const Accel accel(scene);

  auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
  reader->SetFileName(path.c_str());
  for (const int at : {vtkPierceThickness::CELLS, vtkPierceThickness::POINTS}) {
    const bool per_cell = at == vtkPierceThickness::CELLS;
    analysis::ThicknessOptions o;
    o.per = per_cell ? analysis::SampleAt::face : analysis::SampleAt::vertex;
    o.exact = exact.get();
    const analysis::ThicknessResult reference = analysis::compute_thickness(accel, o);

    auto f = vtkSmartPointer<vtkPierceThickness>::New();
    f->SetInputConnection(reader->GetOutputPort());
    f->SetSampleAt(at);
    f->Update();
    auto* out = vtkPolyData::SafeDownCast(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0))->GetBlock(0));
    ASSERT_NE(out, nullptr);
    vtkDataSetAttributes* data = per_cell ? static_cast<vtkDataSetAttributes*>(out->GetCellData())
                                          : static_cast<vtkDataSetAttributes*>(out->GetPointData());
    vtkDataArray* t = data->GetArray("Thickness");
    vtkDataArray* faces = data->GetArray("BRepFaces");
    ASSERT_NE(t, nullptr);
    ASSERT_NE(faces, nullptr);
    ASSERT_EQ(std::size_t(t->GetNumberOfTuples()), reference.size());
    double min = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const double v = t->GetTuple1(vtkIdType(reference.element[i]));
      EXPECT_TRUE(v == reference.thickness[i] || (std::isnan(v) && std::isnan(reference.thickness[i])))
        << (per_cell ? "cell " : "point ") << reference.element[i] << ": " << v << " vs " << reference.thickness[i];
      EXPECT_EQ(faces->GetTuple1(vtkIdType(reference.element[i])), double(reference.brep_faces[i]));
      if (std::isfinite(v)) min = std::min(min, v);
    }
    EXPECT_NEAR(min, 0.3, 1e-6);
    vtkTable* stats = f->GetStatisticsOutput();
    EXPECT_EQ(stats->GetColumnByName("OnBRep")->GetVariantValue(0).ToInt(), 1);
    EXPECT_NEAR(stats->GetColumnByName("Min")->GetVariantValue(0).ToDouble(), 0.3, 1e-6);
  }

  // Moved after reading: the triangles are off the faces they were read from.
  reader->Update();
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(reader->GetOutput()->GetBlock(0));
  for (vtkIdType p = 0; p < moved->GetNumberOfPoints(); ++p) {
    double x[3];
    moved->GetPoint(p, x);
    moved->GetPoints()->SetPoint(p, x[0] + 0.5, x[1], x[2]);
  }
  auto f = thickness_on_mesh_with_warning(moved, "no longer lie on the B-rep");
  vtkTable* stats = f->GetStatisticsOutput();
  EXPECT_LT(stats->GetColumnByName("Min")->GetVariantValue(0).ToDouble(), 0.1);  // the mesh's chord artefact
}

// The registry keeps the last kRegisteredCadModels models: data whose model was released are
// measured on their mesh, with a warning that says so (never with a stale B-rep).
TEST(VtkCadReader, ReleasedModelIsMeasuredOnItsMeshWithAWarning) {
  auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
  reader->SetFileName(assembly_path().c_str());
  reader->Update();
  auto kept = vtkSmartPointer<vtkPolyData>::New();
  kept->DeepCopy(blocks_by_name(reader->GetOutput())["plate_assy/plate"]);
  EXPECT_EQ(thickness_per_cell(kept)->GetStatisticsOutput()->GetColumnByName("OnBRep")->GetVariantValue(0).ToInt(), 1);
  for (std::size_t k = 0; k < kRegisteredCadModels; ++k) {  // the same file read with other options
    auto other = vtkSmartPointer<vtkPierceCADReader>::New();
    other->SetFileName(assembly_path().c_str());
    other->SetAngularDeflection(20.0 + double(k));
    other->Update();
  }
  thickness_on_mesh_with_warning(kept, "is not loaded in this process");
}

TEST(VtkCadReader, MissingAndMalformedFilesAreErrors) {
  const fs::path dir = fs::path(assembly_path()).parent_path();
  const std::string garbage = (dir / "garbage.step").string();
  std::ofstream(garbage) << "this is not a STEP file\n";
  for (const std::string& path : {(dir / "missing.step").string(), garbage}) {
    auto reader = vtkSmartPointer<vtkPierceCADReader>::New();
    auto messages = vtkSmartPointer<MessageCollector>::New();
    messages->Watch(reader);
    messages->Watch(reader->GetExecutive());
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_TRUE(messages->ErrorContains(fs::path(path).filename().string())) << path;
    EXPECT_EQ(reader->GetOutput()->GetNumberOfBlocks(), 0u);
  }
  EXPECT_EQ(vtkPierceCADReader::CanReadFile("a.STP"), 1);
  EXPECT_EQ(vtkPierceCADReader::CanReadFile("a.stl"), 0);
}

}  // namespace
}  // namespace pierce::vtk_test
