// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Fingerprint.h
 * @brief A 64-bit fingerprint of the contents of VTK arrays and meshes:
 *        how the operator cache tells that a mesh came again (readers build
 *        new arrays at every time step, so addresses say nothing).
 *
 * The same contents give the same value on any number of threads: byte
 * ranges are hashed in the filter's threads (pass mpvtk::SMPTaskRunner()).
 */
#ifndef MeshProjection_Projection_Fingerprint_h
#define MeshProjection_Projection_Fingerprint_h

#include "Mesh/ContentHash.h"

#include <cstddef>
#include <cstdint>

class vtkDataArray;
class vtkUnstructuredGrid;

namespace mpvtk
{
class SimplexMesh;

/// The kernel's content hash (Mesh/ContentHash.h), fed with VTK's arrays and meshes.
struct Fingerprint : mp::ContentHash
{
  using mp::ContentHash::Add;
  /// An array's type, size and values (null counts as such).
  void Add(vtkDataArray* array);
  /// Points, cells, cell types and ghost cells: all an operator depends on.
  void Add(vtkUnstructuredGrid* grid);
  /// A wrapped mesh: its simplices and their parents.
  void Add(const SimplexMesh& mesh);
};
} // namespace mpvtk

#endif
