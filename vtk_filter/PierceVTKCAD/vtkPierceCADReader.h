/**
 * @class vtkPierceCADReader
 * @brief Reads STEP, IGES and BREP files through Pierce's OpenCASCADE loader.
 *
 * The output is a vtkMultiBlockDataSet with one vtkPolyData block per solid, named by its
 * assembly path (e.g. "bracket_assy/bolt"), triangles wound outward, and cell arrays SolidId,
 * TessellationFolded (1 on triangles where the tessellation folds against the B-rep) and the link
 * of each triangle to the B-rep: BRepModel (the model's key in this process's registry,
 * pierce/io/cad_registry.h), BRepSolid, BRepTriangle (its index in the solid as loaded),
 * BRepFace and BRepUV (the (u, v) of its three corners on the face). vtkPierceThickness uses the link to measure on the exact B-rep.
 * Field data: Units ("mm" for STEP and IGES, "model units" for BREP) and LinearDeflection (the
 * tessellation tolerance used). Unreadable files are reported through the error mechanism;
 * parts that were skipped or repaired are reported as warnings. Asked for piece n > 0 (under MPI),
 * it outputs the same blocks empty: the model is on piece 0 once, for D3 to spread.
 */
#ifndef vtkPierceCADReader_h
#define vtkPierceCADReader_h

#include "PierceVTKCADModule.h"
#include <string> // for ReportedWarnings
#include "vtkMultiBlockDataSetAlgorithm.h"

class PIERCEVTKCAD_EXPORT vtkPierceCADReader : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkPierceCADReader* New();
  vtkTypeMacro(vtkPierceCADReader, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read (.step .stp .iges .igs .brep .brp).
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Maximum distance between the surfaces and their triangles, in model units (mm for STEP and
   * IGES). 0 (default): 0.1% of the model's bounding-box diagonal.
   */
  vtkSetClampMacro(LinearDeflection, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LinearDeflection, double);
  ///@}

  ///@{
  /**
   * Maximum angle in degrees between the normals of adjacent triangles. Default 15.
   */
  vtkSetClampMacro(AngularDeflection, double, 0.1, 90.0);
  vtkGetMacro(AngularDeflection, double);
  ///@}

  /**
   * 1 when the file name has a CAD extension this reader handles.
   */
  static int CanReadFile(const char* fileName);

protected:
  vtkPierceCADReader();
  ~vtkPierceCADReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName;
  double LinearDeflection;
  double AngularDeflection;

private:
  std::string ReportedWarnings;  // file, options and warnings last reported (once per problem)

  vtkPierceCADReader(const vtkPierceCADReader&) = delete;
  void operator=(const vtkPierceCADReader&) = delete;
};

#endif
