// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FieldArrays.h
 * @brief Which arrays of a dataset are fields to project: the one rule,
 *        used by the serial filter (Projection/SourceFields,
 *        Projection/ArraySelection) and by the gathering of Source on
 *        several processes (Parallel/SourceGather).
 *
 * A field is any array of the point or cell data except the ghost array,
 * the filter's own masks (vtkValidPointMask..., vtkValidCellMask..., left
 * by an earlier projection) and id arrays (GlobalIds, PedigreeIds, and
 * arrays named like them: numbering, not values). Whether a field is then
 * projected is the user's selection and its type (numeric, long enough),
 * decided by the filter where it gathers the fields.
 */
#ifndef MeshProjection_Adapter_FieldArrays_h
#define MeshProjection_Adapter_FieldArrays_h

#include <string>

class vtkAbstractArray;
class vtkDataSet;
class vtkDataSetAttributes;

namespace mpvtk
{
/// The point (association 0) or cell (1) data of `data`.
vtkDataSetAttributes* AttributesOf(vtkDataSet* data, int association);

/// The filter's own masks (of an earlier projection): not fields.
bool IsMask(const std::string& name);

/// Whether `array` of `data` is a field (see the file's comment).
bool IsField(vtkDataSetAttributes* data, vtkAbstractArray* array);
} // namespace mpvtk

#endif
