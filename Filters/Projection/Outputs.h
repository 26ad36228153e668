// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Outputs.h
 * @brief What the filter writes: Input passed through, one array per
 *        projected Source array, the masks of where the result is defined,
 *        the covered fractions, the integrals, and the intersection pieces.
 *
 * Each projected array is a vtkDoubleArray of the Source array's name and
 * components, a label array (Labels.h) one of the Source array's type with
 * its "<name>_Fractions" when asked for (an array projected to the other association next to one of
 * the same name there gets " (from points)" or " (from cells)"); the first
 * projected scalar array becomes the active scalars when neither input
 * has any, so that ParaView colours by it. vtkValidPointMask and
 * vtkValidCellMask mark where the Source reaches; when arrays with NaN
 * groups are valid elsewhere, either the mask becomes theirs (all agree)
 * or each gets a mask of its own, "<mask>_<array>". Points valid only
 * through slivers (every cell around them covered less than 0.1%) are
 * counted and said once.
 */
#ifndef MeshProjection_Projection_Outputs_h
#define MeshProjection_Projection_Outputs_h

#include "Projection/Apply.h"
#include "Projection/Leaf.h"

#include "Mesh/LargeArray.h"

#include "vtkSmartPointer.h"

#include <vector>

class vtkDataObject;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace mpvtk
{
class SourceWeights;

/// Output 0 is Input as it came (each leaf a shallow copy), the pieces' ports empty.
void PassInput(vtkDataObject* input, vtkDataObject* output, vtkPolyData* polygons,
  vtkUnstructuredGrid* polyhedra);

/**
 * Per kernel point of the target, the largest covered fraction of the
 * cells around it (made with M_tt by an operator built here, else here).
 */
mp::LargeVector<double> PointCover(const SimplexMesh& target, OperatorSet& ops);

/// Writes the leaf's outputs (arrays, integrals, masks, coverage) into `output`.
void WriteLeafOutputs(LeafContext& ctx, vtkDataSet* output, const OperatorSet& ops,
  const LeafSolutions& solutions, SourceWeights& weights, const mp::LargeVector<double>& pointCover,
  const mp::SolverHooks& pointHooks);

/// The intersection pieces of the leaf (segments, polygons or tetrahedra), for the pieces' ports.
vtkSmartPointer<vtkDataObject> LeafPieces(const LeafContext& ctx, const OperatorSet& ops);

/// Puts every leaf's pieces into the port of their kind (appended when several).
void WritePieces(const std::vector<vtkSmartPointer<vtkDataObject>>& pieces, vtkPolyData* polygons,
  vtkUnstructuredGrid* polyhedra);
} // namespace mpvtk

#endif
