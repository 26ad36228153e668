// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMeshProjectionFilterInternals.h
 * @brief The private side of vtkMeshProjectionFilter: what the filter keeps
 *        between executions and the stages of an execution that take the
 *        internal types (Projection/, Parallel/). Not installed, not
 *        wrapped; included by the filters' two .cxx files only.
 *
 * vtkPMeshProjectionFilter installs its processes' seam here (Parts) for
 * the duration of an execution. The rooms below the filter never include
 * this header nor the public one.
 */
#ifndef vtkMeshProjectionFilterInternals_h
#define vtkMeshProjectionFilterInternals_h

#include "vtkMeshProjectionFilter.h"

#include "Projection/ArraySelection.h"
#include "Projection/OperatorCache.h"
#include "Projection/Settings.h"

#include "vtkTimeStamp.h"

#include <set>
#include <string>
#include <vector>

namespace mpvtk
{
class Messages;
class Parts;
class StageClock;
struct Statistics;
struct Verdict;
} // namespace mpvtk

struct vtkMeshProjectionFilter::Internals
{
  mpvtk::SourceArrayLists Arrays;
  std::vector<std::string> TangentArrays; ///< the TangentArrays property (Settings::TangentArrays)
  std::set<std::string> Warned;           ///< warnings said once per filter (mpvtk::Messages)
  vtkTimeStamp Executed; ///< the end of the last execution (GetMatrix reads the cache as of it)
  mpvtk::OperatorCache Cache;
  /// The processes' seam (Parallel/Parts.h): vtkPMeshProjectionFilter installs
  /// its own while it runs on several processes; null, one process
  /// (mpvtk::SerialParts).
  mpvtk::Parts* Parts = nullptr;
  /// The arrays named as labels (AddCategoricalArray), in the order named.
  std::vector<std::string> CategoricalNames;

  /**
   * The one list of the properties with their fields of mpvtk::Settings:
   * each(property, field) for every pair. Read one way it gives a new
   * filter the defaults (a default mpvtk::Settings, the one place they are
   * written), the other way an execution's settings.
   */
  template <typename Filter, typename Fields, typename Each>
  static void ForEachProperty(Filter& f, Fields& s, Each each);
  /// The properties as one value (and whether GetMatrix asked for M_ts).
  static mpvtk::Settings Read(const vtkMeshProjectionFilter& filter);
  /// The defaults: those of a default mpvtk::Settings.
  static void SetDefaults(vtkMeshProjectionFilter& filter);

  /// The execution's stages over `parts`: Source, each leaf of Input, the pieces.
  static mpvtk::Verdict Project(vtkMeshProjectionFilter& filter, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector, mpvtk::Parts& parts, mpvtk::StageClock& clock,
    mpvtk::Statistics& stats);
  /// The Input blocks that could not be projected: an error if none was, else a warning once.
  static void ReportSkipped(
    const std::vector<std::string>& skipped, size_t leaves, int projected, mpvtk::Messages& say);
  /// The statistics getters' values.
  static void Publish(
    vtkMeshProjectionFilter& filter, const mpvtk::Statistics& stats, double seconds);
};

#endif
