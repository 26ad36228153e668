// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellReconstruction.h
 * @brief The last step of gathering the Source's cell arrays: with
 *        CellDataReconstruction, each array made linear on each Source cell
 *        (the kernel's LinearReconstruction) and handed to the operators as
 *        DP1 functions, the values at the corners of the Source's simplices.
 *
 * The operators of cell data then read the Source in the DP1 space
 * (Transfers.h, SourceSpaceOf); the transfers, the NaN groups, the
 * integrals and the outputs are otherwise those of constant cell data.
 * A NaN group's cells left out are no neighbours for its arrays' gradients
 * (a cell next to a hole uses the neighbours it has). A Source made of
 * parts (a composite's blocks appended, the processes' parts gathered) has
 * its own copy of each point between two parts: the kernel joins copies at
 * the same coordinates. On several processes
 * each process's gathered Source holds, besides the cells its part needs,
 * two rings of cells around them (SourceGather.cxx, the neighbour layer),
 * so each gradient is the serial one.
 */
#ifndef MeshProjection_Projection_CellReconstruction_h
#define MeshProjection_Projection_CellReconstruction_h

#include "Mesh/MeshView.h"

#include <cstdint>

namespace mpvtk
{
struct GatheredFields;
struct KeptReconstruction;
struct Settings;
class SimplexMesh;

/**
 * Fills `cells`' Corners (and each NaN group's) when the settings ask for a
 * reconstruction (Settings::ReconstructsCellData). The reconstruction's
 * geometry is kept in `kept` (as the cache decides: KeptReconstruction::Store) and serves again while
 * Source's fingerprint `sourcePrint` is the same; made, it uses the
 * Source's face neighbours (built here, for the search too).
 */
void ReconstructCellFields(const Settings& settings, SimplexMesh& source, std::uint64_t sourcePrint,
  GatheredFields& cells, KeptReconstruction& kept);
} // namespace mpvtk

#endif
