// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Settings.h
 * @brief The filter's properties as one typed value, read once per
 *        execution, so that the stages take what they need as an argument
 *        instead of reaching into the filter.
 *
 * This struct is the one place the defaults are written: a default
 * Settings is what a new vtkMeshProjectionFilter starts from (its
 * constructor copies it), and the documentation test
 * (Testing/Documentation/TestPropertyDocs.py) reads these initializers. A
 * property with a kernel counterpart has the kernel's type; the filter's
 * .cxx maps its public constants onto these, in one place, where
 * static_asserts tie the values together. The meaning of each property:
 * vtkMeshProjectionFilter.h and docs/user-guide.md.
 */
#ifndef MeshProjection_Projection_Settings_h
#define MeshProjection_Projection_Settings_h

#include "Search/SearchStatistics.h"       // mp::SearchMethod
#include "Transfer/Extrapolation.h"        // mp::ExtrapolationMode
#include "Transfer/LinearReconstruction.h" // mp::Reconstruction

#include <limits>
#include <set>
#include <string>
#include <vector>

namespace mpvtk
{
/// Where one association's Source arrays go (PointDataTarget, CellDataTarget): bits.
enum TargetBits : int
{
  ToPointsBit = 1,
  ToCellsBit = 2
};

/// How two surfaces' normals are compared (NormalOrientation; mp::MeshView::SurfaceOrientation).
enum SurfaceOrientation : int
{
  SameOrientation = 0,
  OppositeOrientation = 1,
  AnyOrientation = 2
};

/// Which Source arrays are labels (CategoricalMode; Labels.h).
enum CategoricalModes : int
{
  CategoricalAutomatic = 0, ///< single-component integer arrays
  CategoricalSelected = 1   ///< exactly the arrays named in CategoricalArrays
};

struct Settings
{
  mp::SearchMethod SearchMethod = mp::SearchMethod::AdvancingFront;
  bool OutputIntersections = false;
  bool FillWithNaN = true;
  double FillValue = 0;
  mp::ExtrapolationMode Extrapolation = mp::ExtrapolationMode::None;
  double FringeThreshold = 0.25;     ///< aggregate point functions covered less than this
  int PointDataTarget = ToPointsBit; ///< TargetBits
  int CellDataTarget = ToCellsBit;   ///< TargetBits
  bool Extensive = false;            ///< CellDataQuantity is EXTENSIVE
  mp::Reconstruction CellDataReconstruction = mp::Reconstruction::Constant;
  bool Lumped = false; ///< MassMatrix is LUMPED_MASS
  bool PreserveBounds = false;
  /// Names of 3-component arrays tangent to a surface or curve (TangentFields.h).
  std::vector<std::string> TangentArrays; ///< empty: none
  int MaximumIterations = 500;
  double SurfaceReach = 0.5;
  double MaximumNormalAngle = 45.0;
  int NormalOrientation = SameOrientation; ///< SurfaceOrientation
  bool ConserveSourceIntegral = false;
  bool CacheOperator = true;
  int NumberOfThreads = 0; ///< 0: every core (the filter's RequestData)
  int Renumbering = 0;     ///< SimplexMesh::Ordering (AUTOMATIC)
  /// SimplexMesh::SetCurvedLevel: curved second-order cells split on the
  /// lattice of order 2 L through their isoparametric map (1: on their nodes).
  int CurvedCellSubdivision = 1;
  bool KeepMatrices = false;
  /// Mass weighting (MassWeighting.h): the Source's density array ("": off), and the
  /// arrays weighted by it (empty: every array of its association).
  std::string DensityArray = "";
  std::vector<std::string> MassWeightedArrays; ///< empty: all
  int CategoricalMode = CategoricalAutomatic;  ///< CategoricalModes
  bool LabelFractions = false;                 ///< also <name>_Fractions per label array
  int FillLabel = -1;                          ///< the label of uncovered target points and cells
  /// The arrays named as labels (CategoricalSelected), point or cell arrays alike.
  std::set<std::string> CategoricalArrays; ///< empty: none

  /// Whether cell data is reconstructed (CellReconstruction.h): a mode, and cell data going somewhere.
  bool ReconstructsCellData() const
  {
    return this->CellDataReconstruction != mp::Reconstruction::Constant &&
      this->CellDataTarget != 0;
  }
  /// Whether, on several processes, Source comes with the cells around those
  /// that meet Input: a reconstruction's gradients and a tangent point
  /// array's normals read them (Parts::GatherSource).
  bool GathersNeighborLayer() const
  {
    return this->ReconstructsCellData() || !this->TangentArrays.empty();
  }
  /// The value of target functions that the Source does not reach.
  double Fill() const
  {
    return this->FillWithNaN ? std::numeric_limits<double>::quiet_NaN() : this->FillValue;
  }
};
} // namespace mpvtk

#endif
