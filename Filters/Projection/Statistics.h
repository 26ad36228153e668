// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Statistics.h
 * @brief What an execution reports (counts and the wall-clock seconds of
 *        its stages), as a value: each stage returns its share and the
 *        caller adds them up; the filter copies the total to its getters.
 *
 * StageClock measures the stages back to back: each Lap() is the time
 * since the previous one, so the stages' seconds add up to the execution's.
 */
#ifndef MeshProjection_Projection_Statistics_h
#define MeshProjection_Projection_Statistics_h

#include "vtkType.h"

#include <chrono>

namespace mpvtk
{
struct Statistics
{
  vtkIdType Intersections = 0;     ///< simplex pairs with a piece of positive measure
  vtkIdType IntersectionTests = 0; ///< simplex pairs tested
  vtkIdType LocatorQueries = 0;
  double CoveredMeasure = 0;
  int OperatorsBuilt = 0;
  /// Meshes renumbered by the last leaf (its target and the Source); -1: no leaf wrapped.
  int RenumberedMeshes = -1;
  // Seconds per stage.
  double Input = 0, Check = 0, Renumber = 0, Neighbors = 0, Locator = 0, Search = 0;
  double Assembly = 0, Solve = 0, Output = 0;

  Statistics& operator+=(const Statistics& o)
  {
    this->Intersections += o.Intersections;
    this->IntersectionTests += o.IntersectionTests;
    this->LocatorQueries += o.LocatorQueries;
    this->CoveredMeasure += o.CoveredMeasure;
    this->OperatorsBuilt += o.OperatorsBuilt;
    this->RenumberedMeshes = o.RenumberedMeshes >= 0 ? o.RenumberedMeshes : this->RenumberedMeshes;
    this->Input += o.Input;
    this->Check += o.Check;
    this->Renumber += o.Renumber;
    this->Neighbors += o.Neighbors;
    this->Locator += o.Locator;
    this->Search += o.Search;
    this->Assembly += o.Assembly;
    this->Solve += o.Solve;
    this->Output += o.Output;
    return *this;
  }
};

/// Seconds between consecutive laps.
class StageClock
{
public:
  using Time = std::chrono::steady_clock::time_point;
  /// The seconds since the last lap (or the start), and a new lap begins.
  double Lap()
  {
    const Time now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - this->Since).count();
    this->Since = now;
    return seconds;
  }
  /// The seconds since the start of the execution.
  double Total() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }

private:
  Time Start = std::chrono::steady_clock::now();
  Time Since = Start;
};
} // namespace mpvtk

#endif
