// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Fingerprint.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"
#include "Mesh/NodalCells.h"

#include <cstring>

namespace mpvtk
{
void Fingerprint::Add(vtkDataArray* array)
{
  if (!array)
  {
    this->Add(std::uint64_t(0));
    return;
  }
  this->Add(static_cast<std::uint64_t>(array->GetDataType()));
  this->Add(static_cast<std::uint64_t>(array->GetNumberOfValues()));
  if (array->HasStandardMemoryLayout())
  {
    this->Add(array->GetVoidPointer(0),
      static_cast<size_t>(array->GetNumberOfValues()) * array->GetDataTypeSize(),
      mpvtk::SMPTaskRunner());
    return;
  }
  const int nc = array->GetNumberOfComponents();
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    for (int k = 0; k < nc; ++k)
    {
      const double v = array->GetComponent(t, k);
      std::uint64_t w;
      std::memcpy(&w, &v, sizeof w);
      this->Add(w); // one round per value (not a block's)
    }
  }
}

void Fingerprint::Add(vtkUnstructuredGrid* grid)
{
  this->Add(grid->GetPoints() ? grid->GetPoints()->GetData() : nullptr);
  vtkCellArray* cells = grid->GetCells();
  this->Add(cells ? cells->GetOffsetsArray() : nullptr);
  this->Add(cells ? cells->GetConnectivityArray() : nullptr);
  this->Add(grid->GetCellTypesArray());
  this->Add(grid->GetCellGhostArray());
}

void Fingerprint::Add(const SimplexMesh& mesh)
{
  this->Add(mesh.Grid());
  const mp::MeshView& view = mesh.View();
  this->Add(static_cast<std::uint64_t>(view.Parents()));
  if (view.Parent)
  {
    this->Add(view.Parent, static_cast<size_t>(view.NumberOfCells) * sizeof(mp::Index),
      mpvtk::SMPTaskRunner());
  }
  if (view.Nodal)
  {
    // Second-order cells: their types and nodes in their own order (what
    // their shape functions read), beside the split on them.
    const size_t parents = static_cast<size_t>(view.Parents());
    const size_t nodes = static_cast<size_t>(view.Nodal->Offsets[parents]);
    this->Add(static_cast<std::uint64_t>(nodes));
    this->Add(static_cast<std::uint64_t>(mesh.GetCurvedLevel())); // the finer split of curved cells
    this->Add(view.Nodal->Type, parents * sizeof(mp::NodalType), mpvtk::SMPTaskRunner());
    this->Add(view.Nodal->Nodes, nodes * sizeof(long long), mpvtk::SMPTaskRunner());
  }
}
} // namespace mpvtk
