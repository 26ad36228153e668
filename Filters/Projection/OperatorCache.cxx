// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/OperatorCache.h"

#include "Projection/Fingerprint.h"
#include "Projection/Settings.h"
#include "Adapter/SimplexMesh.h"

#include <algorithm>

namespace mpvtk
{
void KeptLeaf::Clear()
{
  for (KeptOperator& k : this->Operators)
  {
    k = KeptOperator();
  }
  this->Groups.clear();
  this->HasFingerprint = false;
}

bool KeptLeaf::KeepsAny() const
{
  return std::any_of(std::begin(this->Operators), std::end(this->Operators),
    [](const KeptOperator& k) { return k.Operator != nullptr; });
}

const KeptLeaf* OperatorCache::FirstLeaf(Transfer transfer) const
{
  for (const auto& leaf : this->Leaves)
  {
    if (leaf.second.Operators[transfer].Operator)
    {
      return &leaf.second;
    }
  }
  return nullptr;
}

const mp::MortarOperator* OperatorCache::FirstOperator(Transfer transfer) const
{
  const KeptLeaf* leaf = this->FirstLeaf(transfer);
  return leaf ? leaf->Operators[transfer].Operator.get() : nullptr;
}

size_t OperatorCache::MemoryBytes() const
{
  size_t bytes = 0;
  for (const auto& leaf : this->Leaves)
  {
    for (const KeptOperator& k : leaf.second.Operators)
    {
      if (k.Operator)
      {
        bytes += k.Operator->MemoryBytes() + k.Solution.capacity() * sizeof(double);
      }
    }
  }
  if (this->Reconstruction.Geometry)
  {
    bytes += this->Reconstruction.Geometry->MemoryBytes();
  }
  return bytes;
}

void OperatorCache::KeepOnly(const std::vector<unsigned int>& present, bool keep)
{
  for (auto it = this->Leaves.begin(); it != this->Leaves.end();)
  {
    const bool there = std::find(present.begin(), present.end(), it->first) != present.end();
    it = there && keep ? std::next(it) : this->Leaves.erase(it);
  }
  if (!keep)
  {
    this->Reconstruction = KeptReconstruction();
  }
}

std::uint64_t LeafFingerprint(
  const SimplexMesh& target, std::uint64_t sourcePrint, const Settings& settings, bool trace)
{
  Fingerprint print;
  print.Add(target);
  print.Add(sourcePrint);
  print.Add(static_cast<std::uint64_t>(settings.SearchMethod));
  print.Add(static_cast<std::uint64_t>(settings.OutputIntersections));
  if (settings.ReconstructsCellData())
  {
    print.Add(std::uint64_t(0xD1)); // cell data read as DP1: other operators
  }
  print.Add(&settings.FringeThreshold, sizeof settings.FringeThreshold); // kept with the operator
  if (!trace && (target.View().IsSurfaceMesh() || target.View().IsCurveMesh()))
  {
    const double contact[3] = { settings.SurfaceReach, settings.MaximumNormalAngle,
      static_cast<double>(settings.NormalOrientation) };
    print.Add(contact, sizeof contact);
  }
  return print.Hash;
}
} // namespace mpvtk
