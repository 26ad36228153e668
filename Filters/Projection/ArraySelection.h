// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ArraySelection.h
 * @brief The user's selection of Source arrays and the filter's listing of
 *        Source's fields in it (what a field is: Adapter/FieldArrays.h).
 */
#ifndef MeshProjection_Projection_ArraySelection_h
#define MeshProjection_Projection_ArraySelection_h

#include "vtkNew.h"
#include "vtkWeakPointer.h"

#include <set>
#include <string>

class vtkAlgorithm;
class vtkDataArraySelection;
class vtkDataObject;

namespace mpvtk
{
/**
 * The user's choice of Source arrays (vtkDataArraySelection per
 * association: 0 points, 1 cells) and the filter's listing of Source's
 * fields in them, for ParaView's panel.
 *
 * Every array is projected unless disabled by name, including arrays that
 * appear later (a new time step's, a new Source's). The filter lists each
 * field it sees (every block's); when another producer feeds the Source
 * port, the names only the previous one had leave the lists.
 *
 * ParaView's array lists (ClearStatuses, then SetStatus per name): a list
 * that names every array listed when it started is the panel's whole list,
 * and arrays that appear later are projected as by default; a list that
 * names fewer (a script that set it before Source had run, or with keyword
 * arguments: it could not know the others) wants only those; a list that
 * names none, all.
 */
class SourceArrayLists
{
public:
  SourceArrayLists();
  vtkDataArraySelection* Selection(int association);
  /// Lists the fields of `data` (a dataset or composite) from `producer`.
  void List(vtkDataObject* data, vtkAlgorithm* producer);
  void ClearStatuses(int association);
  void SetStatus(int association, const char* name, int status);
  /// Whether the lists are being filled by List() (not a user's change).
  bool Listing() const { return this->Busy; }

private:
  void ListArrays(vtkDataObject* data);
  vtkNew<vtkDataArraySelection> Selections[2];
  bool Busy = false;
  /// Per association: every name listed; those listed when ParaView's list
  /// last started; those the list named since.
  std::set<std::string> Listed[2];
  std::set<std::string> ListedAtList[2];
  std::set<std::string> Named[2];
  /// The Source's producer when its arrays were last listed.
  vtkWeakPointer<vtkAlgorithm> ListedProducer;
};
} // namespace mpvtk

#endif
