/**
 * @class vtkPierceOverlaps
 * @brief Coplanar-overlap and interference diagnostics between solids.
 *
 * Input: a vtkPolyData (one solid) or a composite data set (one solid per non-empty block);
 * polygons and strips are triangulated, vertex and line cells dropped.
 *
 * Two analyses:
 *  - coplanar pairs: triangles lying in the same plane and overlapping there (duplicated faces,
 *    faces shared by touching solids), exactly or within Tolerance;
 *  - rays: RaysPerAxis x RaysPerAxis parallel rays along each axis through the bounds, walked with
 *    Pierce's exact kernels; an interval inside two solids at once is an interference of that pair
 *    (BRL-CAD's OVERLAP), a solid leaving where another enters is a contact. The share of rays with
 *    two crossings at exactly equal t and within EpsilonRel * scene diagonal (Gribble et al.) is
 *    stored as field data CoplanarRayShareEqual / CoplanarRayShareWithinEps.
 *
 * Output 0: the triangulated surfaces (same structure as the input) with cell arrays SolidId,
 * OverlapCount (coplanar partners + interference crossings), CoplanarCount, CoplanarPartner
 * (solid of a coplanar partner, another solid first; -1 none), CoplanarHits, InterferenceHits,
 * and, when the rays run, Clearance: each triangle's distance to the nearest other solid, capped
 * at the Clearance property (0 where it touches or clashes; `pierce overlaps --clearance`,
 * pierce/analysis/solid_pairs.h).
 * Output 1 (vtkTable): one row per solid pair and kind ("interference", "contact", "coplanar")
 * with SolidA, SolidB, NameA, NameB, Count, MaxDepth, Penetration, Area and Where.
 *
 * Under MPI every rank gathers the whole surface and runs the analysis on it (the pairs and the
 * ray grid are global), keeps the arrays of its own piece, and rank 0 the table
 * (PierceVTKDistributed.h).
 */
#ifndef vtkPierceOverlaps_h
#define vtkPierceOverlaps_h

#include "PierceVTKModule.h"
#include "vtkPierceSurfaceAlgorithm.h"

class vtkTable;

class PIERCEVTK_EXPORT vtkPierceOverlaps : public vtkPierceSurfaceAlgorithm
{
public:
  static vtkPierceOverlaps* New();
  vtkTypeMacro(vtkPierceOverlaps, vtkPierceSurfaceAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Find coplanar overlapping triangle pairs. Default on.
   */
  vtkSetMacro(FindCoplanar, bool);
  vtkGetMacro(FindCoplanar, bool);
  vtkBooleanMacro(FindCoplanar, bool);
  ///@}

  ///@{
  /**
   * Coplanar pairs: absolute distance within which faces count as coplanar; 0 (default) reports
   * exactly coplanar pairs only.
   */
  vtkSetClampMacro(Tolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Rays per axis and direction of the interference grid (n x n rays along x, y and z); 0 skips
   * the ray analysis. Default 128, as `pierce overlaps` (--rays axes:n=128).
   */
  vtkSetClampMacro(RaysPerAxis, int, 0, 4096);
  vtkGetMacro(RaysPerAxis, int);
  ///@}

  ///@{
  /**
   * Gribble's epsilon for the coplanar-ray statistic, relative to the scene diagonal. Default 1e-5.
   */
  vtkSetClampMacro(EpsilonRel, double, 0.0, 1.0);
  vtkGetMacro(EpsilonRel, double);
  ///@}

  ///@{
  /**
   * Distance (model units) up to which the Clearance array measures the gap to the nearest other
   * solid; triangles with none nearer get this value. Default 0 (the array is then 0 everywhere).
   * Needs the rays (RaysPerAxis > 0).
   */
  vtkSetClampMacro(Clearance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Clearance, double);
  ///@}

  /**
   * Output 1, the solid-pair table.
   */
  vtkTable* GetPairsOutput();

protected:
  vtkPierceOverlaps();
  ~vtkPierceOverlaps() override;

  int AnalyseSurfaces(
    pierce_vtk::SurfaceRun& run, vtkDataObject* input, vtkInformationVector* outputVector) override;

  bool FindCoplanar;
  double Tolerance;
  int RaysPerAxis;
  double EpsilonRel;
  double Clearance;

private:
  vtkPierceOverlaps(const vtkPierceOverlaps&) = delete;
  void operator=(const vtkPierceOverlaps&) = delete;
};

#endif
