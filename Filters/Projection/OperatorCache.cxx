// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/OperatorCache.h"

#include "Projection/Apply.h"
#include "Projection/Fingerprint.h"
#include "Projection/Leaf.h"
#include "Projection/Settings.h"
#include "Adapter/SimplexMesh.h"

#include "Mesh/ContentHash.h"

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

std::uint64_t ExtensionKey(mp::ExtrapolationMode mode, const std::vector<char>& valid)
{
  mp::ContentHash key;
  key.Add(static_cast<std::uint64_t>(mode));
  key.Add(valid.data(), valid.size());
  return key.Hash != 0 ? key.Hash : 1; // (0: no extension)
}

CachePlan KeptLeaf::LookUp(const SimplexMesh& target, std::uint64_t sourcePrint,
  const Settings& settings, bool trace, bool timeVarying) const
{
  CachePlan plan;
  plan.Fingerprint = LeafFingerprint(target, sourcePrint, settings, trace);
  plan.Keep = settings.CacheOperator;
  plan.SameGeometry =
    plan.Keep && this->HasFingerprint && this->GeometryFingerprint == plan.Fingerprint;
  plan.Asked = timeVarying || settings.KeepMatrices;
  return plan;
}

void KeptLeaf::Begin(const CachePlan& plan)
{
  if (!plan.SameGeometry)
  {
    this->Clear();
  }
  this->HasFingerprint = plan.Keep;
  this->GeometryFingerprint = plan.Fingerprint;
}

const mp::MortarOperator* KeptLeaf::Group(Transfer transfer, std::uint64_t cellsLeftOut) const
{
  auto found = this->Groups.find(std::make_pair(static_cast<int>(transfer), cellsLeftOut));
  return found != this->Groups.end() ? found->second.get() : nullptr;
}

void KeptLeaf::KeepOnlyGroups(const std::vector<GroupKey>& used)
{
  for (auto it = this->Groups.begin(); it != this->Groups.end();)
  {
    const bool inUse = std::find(used.begin(), used.end(), it->first) != used.end();
    it = inUse ? std::next(it) : this->Groups.erase(it);
  }
}

const mp::LargeVector<double>* KeptLeaf::WarmStart(
  Transfer transfer, const std::string& key, size_t size) const
{
  const KeptOperator& k = this->Operators[transfer];
  return k.Operator && k.SolutionKey == key && k.Solution.size() == size ? &k.Solution : nullptr;
}

const mp::Extension* KeptLeaf::Extension(Transfer transfer, std::uint64_t key) const
{
  const KeptOperator& k = this->Operators[transfer];
  return k.Operator && key != 0 && k.ExtensionKey == key ? &k.Extension : nullptr;
}

void KeptLeaf::Store(const OperatorPlan& used, OperatorSet& ops, LeafSolutions& solutions,
  const SimplexMesh& target, const SimplexMesh& source)
{
  const CachePlan& plan = used.Cache;
  const bool builtHere = ops.BuiltAny();
  for (Transfer t : AllTransfers)
  {
    std::unique_ptr<mp::MortarOperator>& fresh = ops.Fresh[t];
    KeptOperator& k = this->Operators[t];
    if (fresh && plan.Keeps(*fresh))
    {
      k.Operator = std::move(fresh);
    }
    else if (!used.Used[t] || !plan.Keep)
    {
      k = KeptOperator();
    }
    if (fresh)
    {
      fresh->ReleaseMatrices(); // solved and not kept: room for the outputs
    }
    if (!k.Operator || k.Operator.get() != ops.Operators[t])
    {
      continue;
    }
    // This leaf's: its solution, its system, the extension it took (none without Extrapolation).
    if (solutions.Aside[t])
    {
      k.SolutionKey.swap(solutions.SolvedKey[t]);
      k.Solution.swap(solutions.Solved[t]);
    }
    k.System = solutions.System[t];
    if (solutions.Built[t])
    {
      k.Extension = std::move(solutions.Extension[t]);
    }
    else if (solutions.ExtensionKey[t] == 0)
    {
      k.Extension = mp::Extension();
    }
    k.ExtensionKey = solutions.ExtensionKey[t];
  }
  for (auto& group : ops.GroupFresh)
  {
    if (plan.Keeps(*group.second))
    {
      this->Groups[group.first] = std::move(group.second);
    }
  }
  if (!builtHere)
  {
    return;
  }
  // The meshes' point orders, for GetMatrix (only kept operators are read).
  const bool anyKept = this->KeepsAny();
  auto keep = [anyKept](const SimplexMesh& mesh, std::vector<mp::Index>& order) {
    std::vector<mp::Index>().swap(order);
    if (mesh.Ordered() && anyKept)
    {
      order.assign(mesh.PointOrderData(), mesh.PointOrderData() + mesh.View().NumberOfPoints);
    }
  };
  keep(target, this->TargetPoints);
  keep(source, this->SourcePoints);
}

void KeptReconstruction::Store(const Settings& settings)
{
  if (!settings.CacheOperator)
  {
    *this = KeptReconstruction();
  }
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

void OperatorCache::KeepOnly(const std::vector<unsigned int>& present, const Settings& settings)
{
  const bool keep = settings.CacheOperator;
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
