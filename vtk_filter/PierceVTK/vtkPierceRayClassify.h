/**
 * @class vtkPierceRayClassify
 * @brief Ray classification (Roth 1982, BRL-CAD partitions): for each ray, the intervals it
 * spends inside each solid, where solids overlap, and the gaps between them.
 *
 * Input 0: the solids, a vtkPolyData (one solid) or a composite data set (one solid per
 * non-empty block). Polygons are triangulated; solids wound inward are classified as if flipped.
 * Input 1: the rays, either line/polyline cells (one ray per cell, first to last point) or the
 * points of any data set (a grid, a plane) shot along RayDirection, or along the ray input's
 * 3-component point array DirectionArrayName when UseDirectionArray is on.
 *
 * Output 0 (vtkPolyData): one line cell per partition from entry to exit, with cell arrays
 * RayId (cell or point id in the ray input), SolidId (solid, or -1 for an overlap or gap),
 * SolidCount (0 gap, 1 solid, >= 2 overlap), Depth (line-of-sight length), TIn and TOut (distance
 * from the ray origin), EntryObliquity and ExitObliquity (degrees between ray and surface normal;
 * NaN where the partition is cut by the ray's own ends). Field data SolidNames.
 * Output 1 (vtkTable): the same partitions, one row each, with Kind, Solids, Names and the entry
 * and exit points.
 *
 * Touching solids give adjacent partitions with no gap and no overlap (exact kernels, hits at
 * equal t applied together). Open solids: an entry without exit claims nothing; such rays are
 * counted in a warning.
 *
 * Under MPI every rank gathers the whole surface and shoots the rays of its own piece of the ray
 * input (ghost points and cells skipped); RayId counts the ray inputs of the ranks before it
 * first. The table is reduced to rank 0 (PierceVTKDistributed.h).
 */
#ifndef vtkPierceRayClassify_h
#define vtkPierceRayClassify_h

#include "PierceVTKModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkAlgorithmOutput;
class vtkDataObject;
class vtkTable;

class PIERCEVTK_EXPORT vtkPierceRayClassify : public vtkPolyDataAlgorithm
{
public:
  static vtkPierceRayClassify* New();
  vtkTypeMacro(vtkPierceRayClassify, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The ray input (port 1).
   */
  void SetRaysConnection(vtkAlgorithmOutput* output);
  void SetRaysData(vtkDataObject* rays);

  ///@{
  /**
   * Under MPI (pvserver, pvbatch), every rank holds the whole surface: refuse, with an error
   * naming the size, when it would take more than this many MB per rank. <= 0: no limit.
   * Default 4096.
   */
  vtkSetMacro(MaxReplicatedMB, double);
  vtkGetMacro(MaxReplicatedMB, double);
  ///@}

  /**
   * Output 1, the table of partitions.
   */
  vtkTable* GetTableOutput();

  ///@{
  /**
   * Direction of the rays shot from points, when no direction array is selected. Default +z.
   */
  vtkSetVector3Macro(RayDirection, double);
  vtkGetVector3Macro(RayDirection, double);
  ///@}

  ///@{
  /**
   * Shoot the rays from points along the point array DirectionArrayName of the ray input
   * (e.g. "Normals" of a plane source) instead of RayDirection. Default off.
   */
  vtkSetMacro(UseDirectionArray, bool);
  vtkGetMacro(UseDirectionArray, bool);
  vtkBooleanMacro(UseDirectionArray, bool);
  vtkSetStringMacro(DirectionArrayName);
  vtkGetStringMacro(DirectionArrayName);
  ///@}

  ///@{
  /**
   * Length of the rays shot from points; <= 0 (default) means unlimited.
   */
  vtkSetMacro(MaxLength, double);
  vtkGetMacro(MaxLength, double);
  ///@}

  ///@{
  /**
   * Also output the gaps (air) between consecutive partitions of a ray. Default off.
   */
  vtkSetMacro(IncludeGaps, bool);
  vtkGetMacro(IncludeGaps, bool);
  vtkBooleanMacro(IncludeGaps, bool);
  ///@}

  ///@{
  /**
   * Number of rays with an entry without exit or an exit without entry (open or
   * non-manifold solids) in the last run.
   */
  vtkGetMacro(InconsistentRays, vtkIdType);
  ///@}

protected:
  vtkPierceRayClassify();
  ~vtkPierceRayClassify() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double RayDirection[3];
  bool UseDirectionArray;
  char* DirectionArrayName;
  double MaxLength;
  bool IncludeGaps;
  vtkIdType InconsistentRays;
  double MaxReplicatedMB;

private:
  vtkPierceRayClassify(const vtkPierceRayClassify&) = delete;
  void operator=(const vtkPierceRayClassify&) = delete;
};

#endif
