// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Messages.h
 * @brief Warnings and errors of an execution, in the filter's name (as its
 *        own vtkWarningMacro would say them), for the stages that are not
 *        the filter's methods.
 *
 * Many warnings concern the data rather than one execution (an integer
 * array, a NaN in Source, slivers): said at every time step they would bury
 * the user. WarnOnce says them once per filter, keyed; FirstInRun tells
 * the first time a key comes in one execution (the first leaf of a
 * composite Input, say).
 */
#ifndef MeshProjection_Projection_Messages_h
#define MeshProjection_Projection_Messages_h

#include <set>
#include <string>

class vtkObject;

namespace mpvtk
{
class Messages
{
public:
  /// `warned`: the keys already said, kept by the filter between executions.
  Messages(vtkObject* filter, std::set<std::string>& warned)
    : Filter(filter)
    , Warned(warned)
  {}
  void Warn(const std::string& text) const;
  void Error(const std::string& text) const;
  /// Says `text` unless `key` was said by this filter before; returns whether it did.
  bool WarnOnce(const std::string& key, const std::string& text);
  /// Whether `key` is new to this execution (and marks it said).
  bool FirstInRun(const std::string& key) { return this->WarnedThisRun.insert(key).second; }
  /// Whether `key` is new to the filter (and marks it said): for texts built only then.
  bool First(const std::string& key) { return this->Warned.insert(key).second; }

private:
  vtkObject* Filter;
  std::set<std::string>& Warned;
  std::set<std::string> WarnedThisRun;
};
} // namespace mpvtk

#endif
