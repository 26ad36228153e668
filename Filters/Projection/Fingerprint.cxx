// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Fingerprint.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace mpvtk
{
namespace
{
/// Four interleaved chains (independent multiplies), then combined.
std::uint64_t HashBlock(const unsigned char* b, size_t bytes)
{
  std::uint64_t h[4] = { 0x452821E638D01377ull, 0xBE5466CF34E90C6Cull, 0xC0AC29B7C97C50DDull,
    0x3F84D5B5B5470917ull };
  size_t i = 0;
  for (; i + 32 <= bytes; i += 32)
  {
    for (int l = 0; l < 4; ++l)
    {
      std::uint64_t w;
      std::memcpy(&w, b + i + 8 * l, 8);
      h[l] = (h[l] ^ w) * 0x100000001B3ull;
      h[l] ^= h[l] >> 29;
    }
  }
  Fingerprint block;
  for (; i + 8 <= bytes; i += 8)
  {
    std::uint64_t w;
    std::memcpy(&w, b + i, 8);
    block.Add(w);
  }
  std::uint64_t last = 0;
  if (bytes > i)
  {
    std::memcpy(&last, b + i, bytes - i);
  }
  block.Add(last);
  for (std::uint64_t lane : h)
  {
    block.Add(lane);
  }
  return block.Hash;
}
} // namespace

void Fingerprint::Add(std::uint64_t word)
{
  this->Hash ^= word + 0x9E3779B97F4A7C15ull + (this->Hash << 6) + (this->Hash >> 2);
  this->Hash *= 0xBF58476D1CE4E5B9ull;
  this->Hash ^= this->Hash >> 31;
}

void Fingerprint::Add(const void* data, size_t bytes)
{
  // Blocks of 1 MiB hashed on their own, in the filter's threads, then
  // their hashes added in order: the same value on any number of threads.
  constexpr size_t Block = size_t(1) << 20;
  const unsigned char* b = static_cast<const unsigned char*>(data);
  this->Add(static_cast<std::uint64_t>(bytes));
  const size_t blocks = (bytes + Block - 1) / Block;
  if (blocks <= 1)
  {
    this->Add(HashBlock(b, bytes));
    return;
  }
  std::vector<std::uint64_t> hashes(blocks);
  mpvtk::For(0, static_cast<vtkIdType>(blocks), 1, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType k = begin; k < end; ++k)
    {
      const size_t from = static_cast<size_t>(k) * Block;
      hashes[k] = HashBlock(b + from, std::min(Block, bytes - from));
    }
  });
  for (std::uint64_t h : hashes)
  {
    this->Add(h);
  }
}

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
      static_cast<size_t>(array->GetNumberOfValues()) * array->GetDataTypeSize());
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
    this->Add(view.Parent, static_cast<size_t>(view.NumberOfCells) * sizeof(mp::Index));
  }
}
} // namespace mpvtk
