// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DataSetChecks.h
 * @brief Whether a dataset can be read at all: the ids, offsets, counts and
 *        sizes every later reader of it takes on trust.
 *
 * VTK reads a cell's points through its offsets and connectivity without
 * bounds checks, so a corrupt file would make the projection read outside
 * its arrays rather than fail. The check comes first, before anything reads
 * a cell; it is about the dataset's structure, not its geometry (points
 * that are NaN or out of the predicates' range are the wrap's to report).
 */
#ifndef MeshProjection_Adapter_DataSetChecks_h
#define MeshProjection_Adapter_DataSetChecks_h

#include <string>

class vtkDataSet;

namespace mpvtk
{
/**
 * Checks what VTK itself trusts: every point id of every cell (and of every
 * polyhedron face) is within [0, number of points), offsets start at 0,
 * never decrease and stay within the connectivity, cell types are known and
 * cells have as many points as their type needs, structured grids hold as
 * many points (coordinates) as their dimensions say, and a ghost array has
 * one value per cell (other arrays are checked where they are read).
 * Returns an error naming `role`, the first offending cell and the value,
 * or an empty string. SimplexMesh::Wrap calls it first; a composite's
 * blocks are checked before they are appended.
 */
std::string CheckDataSet(vtkDataSet* data, const std::string& role);
} // namespace mpvtk

#endif
