// SPDX-License-Identifier: BSD-3-Clause
#include "Parallel/Parts.h"

#include "vtkDataSet.h"

#include <map>

namespace mpvtk
{
vtkSmartPointer<vtkDataSet> SerialParts::GatherSource(
  vtkDataSet* source, vtkDataObject*, double, bool, std::string& error, JoinedFields&)
{
  return error.empty() ? source : nullptr;
}

SharedTarget SerialParts::ShareTarget(vtkDataSet* target)
{
  SharedTarget shared;
  shared.Data = target;
  return shared;
}

std::vector<double> SerialParts::SumByKey(
  const std::vector<long long>& keys, int width, const std::vector<double>& values)
{
  // The only process: entries sharing a key are summed among themselves.
  const size_t w = static_cast<size_t>(width);
  std::map<std::vector<long long>, double> sums;
  auto keyOf = [&](size_t i) {
    return std::vector<long long>(keys.begin() + w * i, keys.begin() + w * (i + 1));
  };
  for (size_t i = 0; i < values.size(); ++i)
  {
    sums[keyOf(i)] += values[i];
  }
  std::vector<double> result(values.size());
  for (size_t i = 0; i < values.size(); ++i)
  {
    result[i] = sums[keyOf(i)];
  }
  return result;
}
} // namespace mpvtk
