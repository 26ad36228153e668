// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellCopier.h
 * @brief Copies cells of datasets into one vtkUnstructuredGrid, their point
 *        ids renumbered: the pieces of Source cut for each process and the
 *        merged grid made of the pieces received (not public, not wrapped).
 */
#ifndef MeshProjection_Parallel_CellCopier_h
#define MeshProjection_Parallel_CellCopier_h

#include "vtkCellType.h"
#include "vtkDataSet.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkType.h"
#include "vtkUnstructuredGrid.h"

#include <vector>

namespace mpvtk
{
/**
 * Appends cells of other datasets to a grid, their point ids through a map.
 * Without polyhedra the cells are gathered in bulk (types, offsets,
 * connectivity) and set on the grid at once by Finish(), instead of one
 * InsertNextCell each; with polyhedra among them each cell is inserted,
 * a polyhedron with its face stream.
 */
class CellCopier
{
public:
  CellCopier(vtkUnstructuredGrid* to, bool polyhedra, vtkIdType cells)
    : To(to)
    , Polyhedra(polyhedra)
  {
    if (polyhedra)
    {
      to->AllocateExact(cells, 8 * cells);
    }
  }
  /// Appends cell c of `from`, its point ids through `map`.
  template <class Map>
  void Add(vtkDataSet* from, vtkIdType c, const Map& map)
  {
    if (from != this->From)
    {
      this->From = from;
      this->Grid = vtkUnstructuredGrid::SafeDownCast(from);
    }
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    if (this->Grid)
    {
      this->Grid->GetCellPoints(c, npts, pts);
    }
    else
    {
      from->GetCellPoints(c, this->Ids);
      npts = this->Ids->GetNumberOfIds();
      pts = this->Ids->GetPointer(0);
    }
    const int type = from->GetCellType(c);
    if (!this->Polyhedra)
    {
      this->Types.push_back(static_cast<unsigned char>(type));
      for (vtkIdType k = 0; k < npts; ++k)
      {
        this->Connectivity.push_back(map(pts[k]));
      }
      this->Offsets.push_back(static_cast<vtkIdType>(this->Connectivity.size()));
      return;
    }
    this->Points.resize(static_cast<size_t>(npts));
    for (vtkIdType k = 0; k < npts; ++k)
    {
      this->Points[k] = map(pts[k]);
    }
    if (type != VTK_POLYHEDRON || !this->Grid)
    {
      this->To->InsertNextCell(type, npts, this->Points.data());
      return;
    }
    vtkIdType nfaces = 0;
    const vtkIdType* f = nullptr;
    this->Grid->GetFaceStream(c, nfaces, f);
    this->Faces.clear();
    for (vtkIdType k = 0; k < nfaces; ++k)
    {
      const vtkIdType m = *f++;
      this->Faces.push_back(m);
      for (vtkIdType i = 0; i < m; ++i)
      {
        this->Faces.push_back(map(*f++));
      }
    }
    this->To->InsertNextCell(type, npts, this->Points.data(), nfaces, this->Faces.data());
  }
  /// Sets the gathered cells on the grid (nothing to do with polyhedra).
  void Finish() const;

private:
  vtkUnstructuredGrid* To;
  bool Polyhedra;
  vtkDataSet* From = nullptr;
  vtkUnstructuredGrid* Grid = nullptr;
  vtkNew<vtkIdList> Ids;
  std::vector<unsigned char> Types;
  std::vector<vtkIdType> Offsets{ 0 };
  std::vector<vtkIdType> Connectivity;
  std::vector<vtkIdType> Points, Faces; // one cell's, with polyhedra
};
} // namespace mpvtk

#endif
