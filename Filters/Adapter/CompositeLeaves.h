// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CompositeLeaves.h
 * @brief Walking composite datasets: the one loop over leaves that the
 *        filter's stages use (Input's blocks, Source's blocks, the checks
 *        and the gathering on several processes), and how a leaf is named.
 *
 * Leaves are visited in the composite's own order (flat indices
 * increasing), empty nodes skipped. A plain dataset is its own single leaf
 * (DataSetsOf).
 */
#ifndef MeshProjection_Adapter_CompositeLeaves_h
#define MeshProjection_Adapter_CompositeLeaves_h

#include <functional>
#include <string>
#include <vector>

class vtkCompositeDataIterator;
class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
/// visit(at) for every non-empty leaf of `data` (a composite dataset; nothing otherwise).
void ForEachLeaf(
  vtkDataObject* data, const std::function<void(vtkCompositeDataIterator* at)>& visit);

/// The datasets of `data`: itself, or a composite's dataset leaves.
std::vector<vtkDataSet*> DataSetsOf(vtkDataObject* data);

/// How a leaf is named in messages: "block 'name' (flat index k)" or "block of flat index k".
std::string BlockName(unsigned int flat, const char* name);
std::string BlockName(vtkCompositeDataIterator* at);
} // namespace mpvtk

#endif
