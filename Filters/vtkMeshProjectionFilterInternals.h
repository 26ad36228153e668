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

#include <algorithm>
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
  /**
   * A list property of array names (TangentArrays, MassWeightedArrays,
   * CategoricalArrays): in the order added, each name once, no empty name
   * (the panel's entry for none). Add and Clear say whether the list
   * changed (the filter is then Modified).
   */
  class NameList
  {
  public:
    bool Add(const char* name)
    {
      if (!name || !*name ||
        std::find(this->Names.begin(), this->Names.end(), name) != this->Names.end())
      {
        return false;
      }
      this->Names.emplace_back(name);
      return true;
    }
    bool Clear()
    {
      const bool had = !this->Names.empty();
      this->Names.clear();
      return had;
    }
    int Count() const { return static_cast<int>(this->Names.size()); }
    /// Name i, or null out of range.
    const char* Get(int i) const
    {
      return i >= 0 && i < this->Count() ? this->Names[static_cast<size_t>(i)].c_str() : nullptr;
    }
    const std::vector<std::string>& All() const { return this->Names; }

  private:
    std::vector<std::string> Names;
  };

  mpvtk::SourceArrayLists Arrays;
  NameList TangentArrays;       ///< Settings::TangentArrays
  NameList MassWeightedArrays;  ///< Settings::MassWeightedArrays
  NameList CategoricalArrays;   ///< Settings::CategoricalArrays
  std::set<std::string> Warned; ///< warnings said once per filter (mpvtk::Messages)
  vtkTimeStamp Executed; ///< the end of the last execution (GetMatrix reads the cache as of it)
  mpvtk::OperatorCache Cache;
  /// The processes' seam (Parallel/Parts.h): vtkPMeshProjectionFilter installs
  /// its own while it runs on several processes; null, one process
  /// (mpvtk::SerialParts).
  mpvtk::Parts* Parts = nullptr;

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
