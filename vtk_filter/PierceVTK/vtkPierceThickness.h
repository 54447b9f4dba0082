/**
 * @class vtkPierceThickness
 * @brief Wall-thickness map of closed surfaces with Pierce's exact multi-hit kernels.
 *
 * Input: a vtkPolyData (one solid) or a composite data set (one solid per non-empty block);
 * polygons and strips are triangulated, vertex and line cells dropped.
 * Output 0: the triangulated surfaces (same structure as the input) with point or cell arrays
 *  - Thickness: distance through the solid (NaN where there is none: open mesh, no exit within
 *    MaxDistance, or no usable normal);
 *  - Thin: 1 where Thickness < MinThickness;
 *  - ThicknessStatus: 0 ok, 1 no exit, 2 no normal, 3 tessellation (CAD input: an artefact of
 *    the mesh, left out of the statistics);
 *  - SolidId: the solid (block) index;
 *  - Region: the thin (Thickness < MinThickness) or thick (> MaxThickness) region of the sample,
 *    -1 for none: ids below the number of thin regions are thin regions, thinnest first; the
 *    others thick regions, thickest first (pierce/analysis/thickness_regions.h);
 *  - BRepFaces (CAD input on its B-rep): B-rep faces sampled at the element, 2 or more at a
 *    vertex on an edge (the value is the smallest of their samples).
 * Field data of output 0: the region table, one tuple per Region id (RegionThick 0/1,
 * RegionSolid, RegionThickness: the region's minimum (thin) or maximum (thick), RegionArea: both
 * sides of the wall, RegionSamples, RegionPoint and RegionExit: the extreme sample and where its
 * ray leaves), and ThicknessColorRange: the colour range every Pierce front end gives the map by
 * default (0 to 4 x MinThickness when set, else the 2nd to 98th percentile of the samples;
 * pierce::analysis::default_color_range).
 * Output 1 (vtkTable): per-solid statistics (counts, min, max, mean, percentiles; OnBRep).
 *
 * CAD input (vtkPierceCADReader output, also after D3 or block extraction) is measured on the
 * exact B-rep, as `pierce thickness` measures STEP files: samples start on the exact faces along
 * their exact normals and exits are refined on them (pierce/analysis/thickness.h). That needs the
 * reader's model in this process and triangles as read; where either is missing (a moved or cut
 * surface, data saved and read back), the solid is measured on its mesh and a warning says why
 * (PierceVTKBRep.h).
 *
 * Methods: Ray (from each sample along the inward normal to where the ray leaves the solid it
 * started in; touching neighbours and coincident faces of other solids do not change it), Cone
 * (shape-diameter function over ConeRays rays in a ConeAngle cone), Sphere (largest inscribed
 * ball touching the point). Values equal `pierce thickness` on the same triangles.
 *
 * Under MPI every rank gathers the whole surface, measures the samples of its own piece and
 * keeps its piece (without ghost cells) as output; the statistics are reduced to rank 0. The
 * values are those of a serial run (PierceVTKDistributed.h).
 */
#ifndef vtkPierceThickness_h
#define vtkPierceThickness_h

#include "PierceVTKModule.h"
#include "vtkPierceSurfaceAlgorithm.h"

class vtkTable;

class PIERCEVTK_EXPORT vtkPierceThickness : public vtkPierceSurfaceAlgorithm
{
public:
  static vtkPierceThickness* New();
  vtkTypeMacro(vtkPierceThickness, vtkPierceSurfaceAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    RAY = 0,
    CONE = 1,
    SPHERE = 2
  };
  enum SampleLocations
  {
    POINTS = 0,
    CELLS = 1
  };
  enum ConeAggregates
  {
    SHAPIRA = 0,
    MEDIAN = 1
  };

  // The codes are the positions of the values in core's name tables (pierce/enum_names.h); the
  // string forms take and give core's names, as `pierce thickness` does ("ray", "vertex", ...).

  ///@{
  /**
   * Thickness method: RAY (default), CONE or SPHERE; or by name: "ray", "cone", "sphere".
   */
  vtkSetClampMacro(Method, int, RAY, SPHERE);
  vtkGetMacro(Method, int);
  void SetMethod(const char* name);
  const char* GetMethodAsString();
  void SetMethodToRay() { this->SetMethod(RAY); }
  void SetMethodToCone() { this->SetMethod(CONE); }
  void SetMethodToSphere() { this->SetMethod(SPHERE); }
  ///@}

  ///@{
  /**
   * Sample at POINTS (default: point arrays) or CELLS (triangle centroids: cell arrays); or by
   * name: "vertex", "face".
   */
  vtkSetClampMacro(SampleAt, int, POINTS, CELLS);
  vtkGetMacro(SampleAt, int);
  void SetSampleAt(const char* name);
  const char* GetSampleAtAsString();
  ///@}

  ///@{
  /**
   * Search no farther than this; <= 0 (default) means unlimited.
   */
  vtkSetMacro(MaxDistance, double);
  vtkGetMacro(MaxDistance, double);
  ///@}

  ///@{
  /**
   * Thin flag threshold: Thin = 1 where Thickness < MinThickness. Default 0 (nothing thin).
   */
  vtkSetClampMacro(MinThickness, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinThickness, double);
  ///@}

  ///@{
  /**
   * Thick regions: samples with Thickness > MaxThickness (strictly) connected on the surface form
   * thick regions (sink marks in moulding), as `pierce thickness --max`. Default 0: none.
   */
  vtkSetClampMacro(MaxThickness, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaxThickness, double);
  ///@}

  ///@{
  /**
   * Cone method: rays per sample (default 30), full opening angle in degrees (default 120),
   * aggregation SHAPIRA (outlier-rejecting weighted mean, default) or MEDIAN (by name:
   * "shapira", "median").
   */
  vtkSetClampMacro(ConeRays, int, 1, 10000);
  vtkGetMacro(ConeRays, int);
  vtkSetClampMacro(ConeAngle, double, 1.0, 179.0);
  vtkGetMacro(ConeAngle, double);
  vtkSetClampMacro(ConeAggregate, int, SHAPIRA, MEDIAN);
  vtkGetMacro(ConeAggregate, int);
  void SetConeAggregate(const char* name);
  const char* GetConeAggregateAsString();
  ///@}

  /**
   * Output 1, the per-solid statistics (under MPI: on rank 0, over all ranks' samples).
   */
  vtkTable* GetStatisticsOutput();

protected:
  vtkPierceThickness();
  ~vtkPierceThickness() override;

  int AnalyseSurfaces(
    pierce_vtk::SurfaceRun& run, vtkDataObject* input, vtkInformationVector* outputVector) override;

  int Method;
  int SampleAt;
  double MaxDistance;
  double MinThickness;
  double MaxThickness;
  int ConeRays;
  double ConeAngle;
  int ConeAggregate;

private:
  vtkPierceThickness(const vtkPierceThickness&) = delete;
  void operator=(const vtkPierceThickness&) = delete;
};

#endif
