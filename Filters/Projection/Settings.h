// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Settings.h
 * @brief The filter's properties as one value, read once per execution, so
 *        that the stages take what they need as an argument instead of
 *        reaching into the filter.
 *
 * The meaning and defaults of each are the filter's (vtkMeshProjectionFilter.h
 * and docs/user-guide.md); the enumerations are the filter's too.
 */
#ifndef MeshProjection_Projection_Settings_h
#define MeshProjection_Projection_Settings_h

#include <limits>

namespace mpvtk
{
struct Settings
{
  int SearchMethod = 0;        ///< vtkMeshProjectionFilter::SearchMethods
  bool OutputIntersections = false;
  bool FillWithNaN = true;
  double FillValue = 0;
  int Extrapolation = 0;        ///< vtkMeshProjectionFilter::Extrapolations
  double FringeThreshold = 0.25; ///< aggregate point functions covered less than this
  int PointDataTarget = 1;     ///< vtkMeshProjectionFilter::Targets (bits: 1 points, 2 cells)
  int CellDataTarget = 2;
  bool Extensive = false;      ///< CellDataQuantity is EXTENSIVE
  int CellDataReconstruction = 0; ///< vtkMeshProjectionFilter::Reconstructions
  bool Lumped = false;         ///< MassMatrix is LUMPED_MASS
  bool PreserveBounds = false;
  int MaximumIterations = 500;
  double SurfaceReach = 0.5;
  double MaximumNormalAngle = 45.0;
  int NormalOrientation = 0;   ///< SAME_, OPPOSITE_ or ANY_ORIENTATION
  bool ConserveSourceIntegral = false;
  bool CacheOperator = true;
  int Renumbering = 0;         ///< AUTOMATIC_RENUMBERING, ALWAYS_RENUMBER, NEVER_RENUMBER
  bool AssembleNext = false;   ///< GetMatrix asked for M_ts

  /// Whether cell data is reconstructed (CellReconstruction.h): a mode, and cell data going somewhere.
  bool ReconstructsCellData() const { return this->CellDataReconstruction != 0 && this->CellDataTarget != 0; }
  /// The value of target functions that the Source does not reach.
  double Fill() const
  {
    return this->FillWithNaN ? std::numeric_limits<double>::quiet_NaN() : this->FillValue;
  }
};
} // namespace mpvtk

#endif
