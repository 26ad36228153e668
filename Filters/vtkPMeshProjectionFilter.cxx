// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPMeshProjectionFilter.h"

#include "Parallel/Parts.h"
#include "Projection/ArraySelection.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMPICommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>

vtkStandardNewMacro(vtkPMeshProjectionFilter);
vtkCxxSetObjectMacro(vtkPMeshProjectionFilter, Controller, vtkMultiProcessController);

namespace
{
using Box = std::array<double, 6>; // xmin, xmax, ymin, ymax, zmin, zmax

Box EmptyBox()
{
  const double big = std::numeric_limits<double>::max();
  return { big, -big, big, -big, big, -big };
}

void Grow(Box& b, const double* x)
{
  for (int d = 0; d < 3; ++d)
  {
    b[2 * d] = std::min(b[2 * d], x[d]);
    b[2 * d + 1] = std::max(b[2 * d + 1], x[d]);
  }
}

/// a := the box of a and b.
void Unite(Box& a, const Box& b)
{
  for (int d = 0; d < 3; ++d)
  {
    a[2 * d] = std::min(a[2 * d], b[2 * d]);
    a[2 * d + 1] = std::max(a[2 * d + 1], b[2 * d + 1]);
  }
}

bool Meet(const Box& a, const Box& b)
{
  for (int d = 0; d < 3; ++d)
  {
    if (a[2 * d] > b[2 * d + 1] || b[2 * d] > a[2 * d + 1])
    {
      return false;
    }
  }
  return true;
}

bool Inside(const Box& b, const double* x)
{
  for (int d = 0; d < 3; ++d)
  {
    if (x[d] < b[2 * d] || x[d] > b[2 * d + 1])
    {
      return false;
    }
  }
  return true;
}

/// A process's part of Input seen from afar: its bounding box, cut into a
/// grid of bins, each with the box of the cells' parts inside it.
struct Cover
{
  Box Bounds = EmptyBox();
  int Bins[3] = { 1, 1, 1 };
  std::vector<Box> Boxes; ///< per bin (empty boxes where no cell reaches)

  bool Empty() const { return this->Bounds[0] > this->Bounds[1]; }
  /// The range of bins along axis d that [lo, hi] reaches.
  void Range(int d, double lo, double hi, int& first, int& last) const
  {
    const double a = this->Bounds[2 * d];
    const double w = this->Bounds[2 * d + 1] - a;
    const int n = this->Bins[d];
    if (n == 1 || !(w > 0))
    {
      first = last = 0;
      return;
    }
    first = std::max(0, std::min(n - 1, static_cast<int>(std::floor((lo - a) / w * n))));
    last = std::max(0, std::min(n - 1, static_cast<int>(std::floor((hi - a) / w * n))));
  }
  bool Meets(const Box& b) const
  {
    if (this->Empty() || !Meet(this->Bounds, b))
    {
      return false;
    }
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d)
    {
      this->Range(d, b[2 * d], b[2 * d + 1], lo[d], hi[d]);
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          if (Meet(this->Boxes[(k * this->Bins[1] + j) * this->Bins[0] + i], b))
          {
            return true;
          }
        }
      }
    }
    return false;
  }
};

/// The box of a cell's points.
Box CellBox(vtkDataSet* data, vtkIdType c, vtkIdList* ids)
{
  Box b = EmptyBox();
  data->GetCellPoints(c, ids);
  double x[3];
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
  {
    data->GetPoint(ids->GetId(k), x);
    Grow(b, x);
  }
  return b;
}

/**
 * The boxes of a dataset's cells: straight from an unstructured grid's cell
 * array and double points (no id list, no virtual call per point), else
 * through vtkDataSet's calls. One cell at a time, on one thread.
 */
class CellBoxes
{
public:
  explicit CellBoxes(vtkDataSet* data)
    : Data(data)
    , Grid(vtkUnstructuredGrid::SafeDownCast(data))
  {
    vtkPoints* points = this->Grid ? this->Grid->GetPoints() : nullptr;
    vtkDoubleArray* x = points ? vtkDoubleArray::SafeDownCast(points->GetData()) : nullptr;
    this->X = x && x->GetNumberOfComponents() == 3 && this->Grid->GetCells() ? x->GetPointer(0) : nullptr;
  }
  Box operator()(vtkIdType c)
  {
    if (!this->X)
    {
      return CellBox(this->Data, c, this->Ids);
    }
    Box b = EmptyBox();
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    this->Grid->GetCellPoints(c, npts, pts);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      Grow(b, this->X + 3 * pts[k]);
    }
    return b;
  }

private:
  vtkDataSet* Data;
  vtkUnstructuredGrid* Grid;
  const double* X = nullptr;
  vtkNew<vtkIdList> Ids;
};

/**
 * Appends cells of other datasets to a grid, their point ids through a map.
 * Without polyhedra the cells are gathered in bulk (types, offsets,
 * connectivity) and set on the grid at once by Finish(), instead of one
 * InsertNextCell each; with polyhedra among them each cell is inserted,
 * a polyhedron with its face stream.
 */
class CellCopier
{
public:
  CellCopier(vtkUnstructuredGrid* to, bool polyhedra, vtkIdType cells)
    : To(to)
    , Polyhedra(polyhedra)
  {
    if (polyhedra)
    {
      to->AllocateExact(cells, 8 * cells);
    }
  }
  /// Appends cell c of `from`, its point ids through `map`.
  template <class Map>
  void Add(vtkDataSet* from, vtkIdType c, const Map& map)
  {
    if (from != this->From)
    {
      this->From = from;
      this->Grid = vtkUnstructuredGrid::SafeDownCast(from);
    }
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    if (this->Grid)
    {
      this->Grid->GetCellPoints(c, npts, pts);
    }
    else
    {
      from->GetCellPoints(c, this->Ids);
      npts = this->Ids->GetNumberOfIds();
      pts = this->Ids->GetPointer(0);
    }
    const int type = from->GetCellType(c);
    if (!this->Polyhedra)
    {
      this->Types.push_back(static_cast<unsigned char>(type));
      for (vtkIdType k = 0; k < npts; ++k)
      {
        this->Connectivity.push_back(map(pts[k]));
      }
      this->Offsets.push_back(static_cast<vtkIdType>(this->Connectivity.size()));
      return;
    }
    this->Points.resize(static_cast<size_t>(npts));
    for (vtkIdType k = 0; k < npts; ++k)
    {
      this->Points[k] = map(pts[k]);
    }
    if (type != VTK_POLYHEDRON || !this->Grid)
    {
      this->To->InsertNextCell(type, npts, this->Points.data());
      return;
    }
    vtkIdType nfaces = 0;
    const vtkIdType* f = nullptr;
    this->Grid->GetFaceStream(c, nfaces, f);
    this->Faces.clear();
    for (vtkIdType k = 0; k < nfaces; ++k)
    {
      const vtkIdType m = *f++;
      this->Faces.push_back(m);
      for (vtkIdType i = 0; i < m; ++i)
      {
        this->Faces.push_back(map(*f++));
      }
    }
    this->To->InsertNextCell(type, npts, this->Points.data(), nfaces, this->Faces.data());
  }
  /// Sets the gathered cells on the grid (nothing to do with polyhedra).
  void Finish() const
  {
    if (this->Polyhedra)
    {
      return;
    }
    auto array = [](const std::vector<vtkIdType>& values) {
      vtkNew<vtkIdTypeArray> a;
      a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
      std::copy(values.begin(), values.end(), a->GetPointer(0));
      return a;
    };
    vtkNew<vtkCellArray> cells;
    cells->SetData(array(this->Offsets), array(this->Connectivity));
    vtkNew<vtkUnsignedCharArray> types;
    types->SetNumberOfValues(static_cast<vtkIdType>(this->Types.size()));
    std::copy(this->Types.begin(), this->Types.end(), types->GetPointer(0));
    this->To->SetCells(types, cells);
  }

private:
  vtkUnstructuredGrid* To;
  bool Polyhedra;
  vtkDataSet* From = nullptr;
  vtkUnstructuredGrid* Grid = nullptr;
  vtkNew<vtkIdList> Ids;
  std::vector<unsigned char> Types;
  std::vector<vtkIdType> Offsets{ 0 };
  std::vector<vtkIdType> Connectivity;
  std::vector<vtkIdType> Points, Faces; // one cell's, with polyhedra
};

bool IsGhost(vtkUnsignedCharArray* ghosts, vtkIdType c)
{
  return ghosts &&
    (ghosts->GetValue(c) & (vtkDataSetAttributes::DUPLICATECELL | vtkDataSetAttributes::HIDDENCELL));
}

/// The datasets of a data object (itself, or a composite's leaves).
std::vector<vtkDataSet*> DataSetsOf(vtkDataObject* data)
{
  std::vector<vtkDataSet*> all;
  if (vtkDataSet* one = vtkDataSet::SafeDownCast(data))
  {
    all.push_back(one);
  }
  else if (vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> iter;
    iter.TakeReference(composite->NewIterator());
    iter->SkipEmptyNodesOn();
    for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
    {
      if (vtkDataSet* leaf = vtkDataSet::SafeDownCast(iter->GetCurrentDataObject()))
      {
        all.push_back(leaf);
      }
    }
  }
  return all;
}

/// A point's identity across processes: its global id, or its coordinates' bits.
struct PointKey
{
  double X[3];
  bool operator==(const PointKey& o) const { return std::memcmp(this->X, o.X, sizeof X) == 0; }
};
/// FNV-1a over bytes.
std::uint64_t Fnv1a(const void* data, size_t bytes)
{
  std::uint64_t h = 1469598103934665603ull;
  const unsigned char* b = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i)
  {
    h = (h ^ b[i]) * 1099511628211ull;
  }
  return h;
}

struct PointKeyHash
{
  size_t operator()(const PointKey& k) const { return static_cast<size_t>(Fnv1a(k.X, sizeof k.X)); }
};

PointKey KeyOf(const double* x)
{
  PointKey k;
  for (int d = 0; d < 3; ++d)
  {
    k.X[d] = x[d] == 0.0 ? 0.0 : x[d]; // -0 is 0
  }
  return k;
}

template <class T>
void Append(std::vector<char>& buffer, const T* values, size_t count)
{
  const size_t at = buffer.size();
  buffer.resize(at + count * sizeof(T));
  if (count)
  {
    std::memcpy(buffer.data() + at, values, count * sizeof(T));
  }
}

template <class T>
std::vector<T> Read(const std::vector<char>& buffer)
{
  std::vector<T> values(buffer.size() / sizeof(T));
  if (!values.empty())
  {
    std::memcpy(values.data(), buffer.data(), values.size() * sizeof(T));
  }
  return values;
}

/// The arrays of a dataset's points or cells that take part: numeric, named
/// fields (Projection/ArraySelection.h).
std::vector<vtkDataArray*> ArraysOf(vtkDataSetAttributes* data)
{
  std::vector<vtkDataArray*> arrays;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = data->GetArray(i);
    if (!a || !a->GetName() || !mpvtk::IsField(data, a))
    {
      continue;
    }
    arrays.push_back(a);
  }
  return arrays;
}

std::string Signature(vtkDataArray* a)
{
  return std::string(a->GetName()) + "\t" + std::to_string(a->GetDataType()) + "\t" +
    std::to_string(a->GetNumberOfComponents());
}

class MPIParts : public mpvtk::Parts
{
public:
  explicit MPIParts(vtkMultiProcessController* controller)
    : C(controller)
    , Mpi(vtkMPICommunicator::SafeDownCast(controller->GetCommunicator()))
    , Me(controller->GetLocalProcessId())
    , N(controller->GetNumberOfProcesses())
  {
  }
  int Rank() const override { return this->Me; }
  int Size() const override { return this->N; }
  double SentBytes() const override { return this->Sent; }
  vtkIdType Received = 0;

  mpvtk::Verdict Agree(const mpvtk::Verdict& verdict, bool* flag) override
  {
    const bool done = verdict.Ok();
    int mine[2] = { done ? this->N : this->Me, flag ? (*flag ? 1 : 0) : 1 };
    int all[2] = { 0, 0 };
    this->C->AllReduce(mine, all, 2, vtkCommunicator::MIN_OP);
    if (flag)
    {
      *flag = all[1] != 0;
    }
    const int first = all[0];
    if (first >= this->N)
    {
      return mpvtk::Verdict();
    }
    // The first process's outcome and reason, to the others.
    std::string text = first == this->Me ? verdict.Why : std::string();
    long long head[2] = { static_cast<long long>(verdict.What), static_cast<long long>(text.size()) };
    this->C->Broadcast(head, 2, first);
    text.resize(static_cast<size_t>(head[1]));
    if (head[1] > 0)
    {
      this->C->Broadcast(&text[0], head[1], first);
    }
    if (first == this->Me)
    {
      return verdict;
    }
    return { static_cast<mpvtk::Outcome>(head[0]), text + " (on process " + std::to_string(first) + ")" };
  }

  void Or(std::vector<char>& flags) override
  {
    std::vector<int> mine(flags.begin(), flags.end()), all(flags.size());
    if (!flags.empty())
    {
      this->C->AllReduce(mine.data(), all.data(), static_cast<vtkIdType>(mine.size()),
        vtkCommunicator::MAX_OP);
    }
    for (size_t i = 0; i < flags.size(); ++i)
    {
      flags[i] = all[i] != 0;
    }
  }

  void Sum(double* values, int count) override
  {
    if (count <= 0)
    {
      return;
    }
    std::vector<double> mine(values, values + count);
    this->C->AllReduce(mine.data(), values, count, vtkCommunicator::SUM_OP);
  }

  std::vector<unsigned int> Union(const std::vector<unsigned int>& values) override
  {
    std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
    for (int r = 0; r < this->N; ++r)
    {
      Append(out[r], values.data(), values.size());
    }
    std::vector<unsigned int> all;
    for (const std::vector<char>& in : this->AllToAll(out))
    {
      const std::vector<unsigned int> v = Read<unsigned int>(in);
      all.insert(all.end(), v.begin(), v.end());
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  }

  std::vector<double> SumByKey(
    const std::vector<long long>& keys, int width, const std::vector<double>& values) override
  {
    // Each entry goes to the process its key hashes to, which sums the
    // entries of each key and answers every entry, in the order received.
    const int n = this->N;
    const size_t w = static_cast<size_t>(width);
    std::vector<std::vector<char>> out(static_cast<size_t>(n));
    std::vector<std::vector<size_t>> sent(static_cast<size_t>(n));
    for (size_t i = 0; i < values.size(); ++i)
    {
      const std::uint64_t h = Fnv1a(keys.data() + w * i, w * sizeof(long long));
      const size_t r = static_cast<size_t>((h ^ (h >> 29)) % static_cast<std::uint64_t>(n));
      long long bits;
      std::memcpy(&bits, &values[i], sizeof(bits));
      Append(out[r], keys.data() + w * i, w);
      Append(out[r], &bits, 1);
      sent[r].push_back(i);
    }
    std::vector<std::vector<char>> in = this->AllToAll(out);
    // Received entries (process, position), sorted by key: runs of one key.
    std::vector<std::vector<long long>> got(static_cast<size_t>(n));
    std::vector<std::pair<int, size_t>> order;
    for (int r = 0; r < n; ++r)
    {
      got[r] = Read<long long>(in[r]);
      for (size_t j = 0; j < got[r].size() / (w + 1); ++j)
      {
        order.emplace_back(r, j);
      }
    }
    auto keyOf = [&](const std::pair<int, size_t>& e) { return got[e.first].data() + (w + 1) * e.second; };
    std::sort(order.begin(), order.end(), [&](const std::pair<int, size_t>& a, const std::pair<int, size_t>& b) {
      const long long* x = keyOf(a);
      const long long* y = keyOf(b);
      return std::lexicographical_compare(x, x + w, y, y + w) || (std::equal(x, x + w, y) && a < b);
    });
    std::vector<std::vector<double>> answer(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r)
    {
      answer[r].resize(got[r].size() / (w + 1));
    }
    for (size_t a = 0; a < order.size();)
    {
      size_t b = a;
      double total = 0.0;
      for (; b < order.size() && std::equal(keyOf(order[a]), keyOf(order[a]) + w, keyOf(order[b])); ++b)
      {
        double v;
        std::memcpy(&v, keyOf(order[b]) + w, sizeof(v));
        total += v; // in (process, position) order: the same on any run
      }
      for (; a < b; ++a)
      {
        answer[order[a].first][order[a].second] = total;
      }
    }
    for (int r = 0; r < n; ++r)
    {
      out[r].clear();
      Append(out[r], answer[r].data(), answer[r].size());
    }
    in = this->AllToAll(out);
    std::vector<double> sums(values.size(), 0.0);
    for (int r = 0; r < n; ++r)
    {
      const std::vector<double> back = Read<double>(in[r]);
      for (size_t j = 0; j < back.size() && j < sent[r].size(); ++j)
      {
        sums[sent[r][j]] = back[j];
      }
    }
    return sums;
  }

  vtkSmartPointer<vtkDataSet> GatherSource(
    vtkDataSet* source, vtkDataObject* input, double reach, std::string& error) override;
  vtkSmartPointer<vtkDataSet> ShareTarget(vtkDataSet* target) override;
  mp::SolverHooks Hooks(bool points, mp::Index rows,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) override;
  /// The hooks' Exchange: completes the shared rows of v (rows x width) with
  /// the parts' sum, in the order of their processes (the same value
  /// everywhere, bit for bit), or with their minimum.
  void Complete(double* v, int width, bool minimum);

private:
  /// Every process sends out[r] to process r; returns what each sent here.
  std::vector<std::vector<char>> AllToAll(std::vector<std::vector<char>>& out);
  /// Sends send[k] to ranks[k] and receives recv[k] (sizes known) from it.
  void Swap(const std::vector<int>& ranks, std::vector<std::vector<double>>& send,
    std::vector<std::vector<double>>& recv);

  vtkMultiProcessController* C;
  vtkMPICommunicator* Mpi;
  int Me;
  int N;
  double Sent = 0;
  // The last shared target: per neighbour (ascending ranks), the points
  // shared with it, in an order both agree on; per point, the lowest
  // process that has it.
  std::vector<int> Neighbours;
  std::vector<std::vector<vtkIdType>> SharedPoints;
  std::vector<int> Owner;
  // The hooks' state (kernel rows).
  std::vector<std::vector<mp::Index>> Rows;
  std::vector<char> Counted;
  std::vector<mp::Index> SharedRows; ///< distinct, ascending
  /// Points of one process at one place (or with one global id, as a
  /// ghost cells generator may leave them) are one point: each point's
  /// first copy (Representative), and the rows of those with copies.
  std::vector<vtkIdType> Representative;
  std::vector<std::vector<mp::Index>> Copies; ///< rows of one point, ascending, first the rows' representative
  /// Per point of the last shared target: its global identity (its
  /// GlobalIds value, given or made); per row of the hooks: its point's.
  std::vector<long long> GlobalOf;
  std::vector<long long> RowGlobal;
  /// The hooks' Direct: the system's parts gathered on process 0, solved
  /// there, each process's rows sent back.
  bool SolveGathered(const mp::CsrMatrix& A, const double* B, double* X, int c,
    const std::vector<char>& converged);
};

std::vector<std::vector<char>> MPIParts::AllToAll(std::vector<std::vector<char>>& out)
{
  const int n = this->N;
  std::vector<long long> sizes(static_cast<size_t>(n)), all(static_cast<size_t>(n) * n);
  for (int r = 0; r < n; ++r)
  {
    sizes[r] = static_cast<long long>(out[r].size());
  }
  this->C->AllGather(sizes.data(), all.data(), n);
  std::vector<std::vector<char>> in(static_cast<size_t>(n));
  in[this->Me].swap(out[this->Me]);
  // Messages in chunks below 2^31 bytes (MPI counts are ints).
  const long long chunk = 1LL << 30;
  size_t count = 0;
  for (int r = 0; r < n; ++r)
  {
    if (r != this->Me)
    {
      in[r].resize(static_cast<size_t>(all[static_cast<size_t>(r) * n + this->Me]));
      count += static_cast<size_t>((static_cast<long long>(in[r].size()) + chunk - 1) / chunk);
      count += static_cast<size_t>((sizes[r] + chunk - 1) / chunk);
    }
  }
  std::vector<vtkMPICommunicator::Request> requests(count);
  size_t k = 0;
  const int tag = 73901;
  for (int r = 0; r < n; ++r)
  {
    for (long long at = 0; r != this->Me && at < static_cast<long long>(in[r].size()); at += chunk)
    {
      const int length = static_cast<int>(std::min<long long>(chunk, in[r].size() - at));
      this->Mpi->NoBlockReceive(in[r].data() + at, length, r, tag, requests[k++]);
    }
  }
  for (int r = 0; r < n; ++r)
  {
    for (long long at = 0; r != this->Me && at < sizes[r]; at += chunk)
    {
      const int length = static_cast<int>(std::min<long long>(chunk, sizes[r] - at));
      this->Mpi->NoBlockSend(out[r].data() + at, length, r, tag, requests[k++]);
      this->Sent += length;
    }
  }
  if (k > 0)
  {
    this->Mpi->WaitAll(static_cast<int>(k), requests.data());
  }
  return in;
}

void MPIParts::Swap(const std::vector<int>& ranks, std::vector<std::vector<double>>& send,
  std::vector<std::vector<double>>& recv)
{
  std::vector<vtkMPICommunicator::Request> requests(2 * ranks.size());
  size_t k = 0;
  const int tag = 73902;
  for (size_t i = 0; i < ranks.size(); ++i)
  {
    if (!recv[i].empty())
    {
      this->Mpi->NoBlockReceive(
        recv[i].data(), static_cast<int>(recv[i].size()), ranks[i], tag, requests[k++]);
    }
  }
  for (size_t i = 0; i < ranks.size(); ++i)
  {
    if (!send[i].empty())
    {
      this->Mpi->NoBlockSend(
        send[i].data(), static_cast<int>(send[i].size()), ranks[i], tag, requests[k++]);
      this->Sent += static_cast<double>(send[i].size() * sizeof(double));
    }
  }
  if (k > 0)
  {
    this->Mpi->WaitAll(static_cast<int>(k), requests.data());
  }
}

vtkSmartPointer<vtkDataSet> MPIParts::GatherSource(
  vtkDataSet* source, vtkDataObject* input, double reach, std::string& error)
{
  const int n = this->N;
  // 1. This process's part of Input, as boxes: a grid of bins over its
  // bounds, each with the box of the (grown) cells' parts inside it.
  Cover mine;
  {
    std::vector<Box> cells;
    for (vtkDataSet* leaf : DataSetsOf(input))
    {
      vtkUnsignedCharArray* ghosts = leaf->GetCellGhostArray();
      CellBoxes boxOf(leaf);
      for (vtkIdType c = 0; c < leaf->GetNumberOfCells(); ++c)
      {
        if (IsGhost(ghosts, c) || leaf->GetCellType(c) == VTK_EMPTY_CELL)
        {
          continue;
        }
        Box b = boxOf(c);
        double size = 0;
        for (int d = 0; d < 3; ++d)
        {
          size = std::max(size, b[2 * d + 1] - b[2 * d]);
        }
        const double grow = reach * size + 1e-9 * size;
        for (int d = 0; d < 3; ++d)
        {
          b[2 * d] -= grow;
          b[2 * d + 1] += grow;
        }
        cells.push_back(b);
        Unite(mine.Bounds, b);
      }
    }
    if (!cells.empty())
    {
      for (int d = 0; d < 3; ++d)
      {
        mine.Bins[d] = mine.Bounds[2 * d + 1] > mine.Bounds[2 * d] ? 16 : 1;
      }
      mine.Boxes.assign(static_cast<size_t>(mine.Bins[0]) * mine.Bins[1] * mine.Bins[2], EmptyBox());
      for (const Box& b : cells)
      {
        int lo[3], hi[3];
        for (int d = 0; d < 3; ++d)
        {
          mine.Range(d, b[2 * d], b[2 * d + 1], lo[d], hi[d]);
        }
        for (int k = lo[2]; k <= hi[2]; ++k)
        {
          for (int j = lo[1]; j <= hi[1]; ++j)
          {
            for (int i = lo[0]; i <= hi[0]; ++i)
            {
              // The cell's part inside the bin (bins tile the bounds).
              const int at[3] = { i, j, k };
              Box part = b;
              for (int d = 0; d < 3; ++d)
              {
                const double a = mine.Bounds[2 * d];
                const double w = (mine.Bounds[2 * d + 1] - a) / mine.Bins[d];
                if (mine.Bins[d] > 1)
                {
                  part[2 * d] = std::max(part[2 * d], at[d] == 0 ? -HUGE_VAL : a + w * at[d]);
                  part[2 * d + 1] = std::min(
                    part[2 * d + 1], at[d] == mine.Bins[d] - 1 ? HUGE_VAL : a + w * (at[d] + 1));
                }
              }
              Unite(mine.Boxes[(k * mine.Bins[1] + j) * mine.Bins[0] + i], part);
            }
          }
        }
      }
    }
  }
  // 2. Every process's boxes, to every process.
  std::vector<Cover> covers(static_cast<size_t>(n));
  {
    std::vector<char> packed;
    std::vector<double> head(mine.Bounds.begin(), mine.Bounds.end());
    for (int d = 0; d < 3; ++d)
    {
      head.push_back(mine.Bins[d]);
    }
    Append(packed, head.data(), head.size());
    for (const Box& b : mine.Boxes)
    {
      Append(packed, b.data(), 6);
    }
    std::vector<std::vector<char>> out(static_cast<size_t>(n), packed);
    std::vector<std::vector<char>> in = this->AllToAll(out);
    for (int r = 0; r < n; ++r)
    {
      const std::vector<double> v = Read<double>(in[r]);
      if (v.size() < 9)
      {
        continue;
      }
      std::copy(v.begin(), v.begin() + 6, covers[r].Bounds.begin());
      for (int d = 0; d < 3; ++d)
      {
        covers[r].Bins[d] = static_cast<int>(v[6 + d]);
      }
      for (size_t at = 9; at + 6 <= v.size(); at += 6)
      {
        Box b;
        std::copy(v.begin() + at, v.begin() + at + 6, b.begin());
        covers[r].Boxes.push_back(b);
      }
    }
  }
  // 3. The arrays every process's Source has (those with cells); global ids
  // of the Source's points: its own when every process has them, else each
  // process's numbering after those of the processes before it.
  const vtkIdType np = source->GetNumberOfPoints();
  std::vector<vtkDataArray*> arrays[2] = { ArraysOf(source->GetPointData()),
    ArraysOf(source->GetCellData()) };
  std::vector<std::string> common[2];
  bool ownIds = true;
  long long offset = 0;
  {
    vtkDataArray* global = source->GetPointData()->GetGlobalIds();
    const bool has = source->GetNumberOfCells() > 0;
    const bool usable = global && global->GetNumberOfComponents() == 1 &&
      global->GetNumberOfTuples() >= np;
    std::string text = has ? "1" : "0";
    text += usable || !has ? "1\n" : "0\n";
    for (int a = 0; a < 2; ++a)
    {
      for (vtkDataArray* array : arrays[a])
      {
        text += std::to_string(a) + "\t" + Signature(array) + "\n";
      }
    }
    std::vector<std::vector<char>> out(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r)
    {
      Append(out[r], text.data(), text.size());
    }
    std::vector<long long> counts(static_cast<size_t>(n));
    const long long mineCount = static_cast<long long>(np);
    this->C->AllGather(&mineCount, counts.data(), 1);
    for (int r = 0; r < this->Me; ++r)
    {
      offset += counts[r];
    }
    std::map<std::string, int> seen;
    int sources = 0;
    for (const std::vector<char>& in : this->AllToAll(out))
    {
      const std::string t(in.begin(), in.end());
      if (t.size() < 2 || t[0] != '1')
      {
        ownIds = ownIds && (t.size() < 2 || t[1] == '1');
        continue;
      }
      ownIds = ownIds && t[1] == '1';
      ++sources;
      size_t at = t.find('\n') + 1;
      while (at < t.size())
      {
        const size_t end = t.find('\n', at);
        ++seen[t.substr(at, end - at)];
        at = end + 1;
      }
    }
    for (const auto& s : seen)
    {
      if (s.second == sources)
      {
        common[s.first[0] - '0'].push_back(s.first.substr(2));
      }
    }
  }
  std::vector<long long> key(static_cast<size_t>(np));
  {
    vtkDataArray* global = source->GetPointData()->GetGlobalIds();
    for (vtkIdType p = 0; p < np; ++p)
    {
      key[p] = ownIds && global ? static_cast<long long>(global->GetTuple1(p)) : offset + p;
    }
  }
  for (int a = 0; a < 2; ++a)
  {
    std::vector<vtkDataArray*> kept;
    for (vtkDataArray* array : arrays[a])
    {
      if (std::find(common[a].begin(), common[a].end(), Signature(array)) != common[a].end())
      {
        kept.push_back(array);
      }
    }
    arrays[a].swap(kept);
  }
  // 4. Each Source cell (not a ghost) to every process whose boxes it meets,
  // as a grid of its own: double points, their global ids, the common arrays.
  std::vector<std::vector<vtkIdType>> toSend(static_cast<size_t>(n));
  {
    vtkUnsignedCharArray* ghosts = source->GetCellGhostArray();
    CellBoxes boxOf(source);
    for (vtkIdType c = 0; c < source->GetNumberOfCells(); ++c)
    {
      if (IsGhost(ghosts, c) || source->GetCellType(c) == VTK_EMPTY_CELL)
      {
        continue;
      }
      const Box b = boxOf(c);
      for (int r = 0; r < n; ++r)
      {
        if (covers[r].Meets(b))
        {
          toSend[r].push_back(c);
        }
      }
    }
  }
  auto pieceOf = [&](const std::vector<vtkIdType>& cells) {
    vtkNew<vtkUnstructuredGrid> piece;
    // The piece's points in the order its cells first use them.
    std::vector<vtkIdType> local(static_cast<size_t>(source->GetNumberOfPoints()), -1);
    std::vector<vtkIdType> points;
    auto idOf = [&](vtkIdType p) {
      vtkIdType& id = local[static_cast<size_t>(p)];
      if (id < 0)
      {
        id = static_cast<vtkIdType>(points.size());
        points.push_back(p);
      }
      return id;
    };
    bool polyhedra = false;
    for (vtkIdType c : cells)
    {
      polyhedra = polyhedra || source->GetCellType(c) == VTK_POLYHEDRON;
    }
    CellCopier copier(piece, polyhedra, static_cast<vtkIdType>(cells.size()));
    for (vtkIdType c : cells)
    {
      copier.Add(source, c, idOf);
    }
    copier.Finish();
    vtkNew<vtkPoints> xyz;
    xyz->SetDataTypeToDouble();
    xyz->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
    vtkNew<vtkIdTypeArray> global;
    global->SetName("vtkMeshProjectionGlobalIds");
    global->SetNumberOfValues(static_cast<vtkIdType>(points.size()));
    double x[3];
    for (size_t i = 0; i < points.size(); ++i)
    {
      source->GetPoint(points[i], x);
      xyz->SetPoint(static_cast<vtkIdType>(i), x);
      global->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(key[points[i]]));
    }
    piece->SetPoints(xyz);
    piece->GetPointData()->AddArray(global);
    for (int a = 0; a < 2; ++a)
    {
      const std::vector<vtkIdType>& from = a == 0 ? points : cells;
      vtkDataSetAttributes* to = a == 0 ? static_cast<vtkDataSetAttributes*>(piece->GetPointData())
                                        : piece->GetCellData();
      for (vtkDataArray* array : arrays[a])
      {
        vtkSmartPointer<vtkDataArray> copy;
        copy.TakeReference(array->NewInstance());
        copy->SetName(array->GetName());
        copy->SetNumberOfComponents(array->GetNumberOfComponents());
        for (int k = 0; k < array->GetNumberOfComponents(); ++k)
        {
          if (array->GetComponentName(k))
          {
            copy->SetComponentName(k, array->GetComponentName(k));
          }
        }
        copy->SetNumberOfTuples(static_cast<vtkIdType>(from.size()));
        for (size_t i = 0; i < from.size(); ++i)
        {
          copy->SetTuple(static_cast<vtkIdType>(i), from[i], array);
        }
        to->AddArray(copy);
      }
    }
    return vtkSmartPointer<vtkUnstructuredGrid>(piece.GetPointer());
  };
  std::vector<vtkSmartPointer<vtkUnstructuredGrid>> pieces;
  {
    std::vector<std::vector<char>> out(static_cast<size_t>(n));
    vtkSmartPointer<vtkUnstructuredGrid> own;
    for (int r = 0; r < n; ++r)
    {
      if (toSend[r].empty())
      {
        continue;
      }
      vtkSmartPointer<vtkUnstructuredGrid> piece = pieceOf(toSend[r]);
      if (r == this->Me)
      {
        own = piece;
        continue;
      }
      vtkNew<vtkCharArray> bytes;
      if (!vtkCommunicator::MarshalDataObject(piece, bytes))
      {
        error = "the Source cells for process " + std::to_string(r) + " could not be packed";
      }
      Append(out[r], bytes->GetPointer(0), static_cast<size_t>(bytes->GetNumberOfValues()));
    }
    std::vector<std::vector<char>> in = this->AllToAll(out);
    for (int r = 0; r < n; ++r)
    {
      if (r == this->Me)
      {
        if (own)
        {
          pieces.push_back(own);
        }
        continue;
      }
      if (in[r].empty())
      {
        continue;
      }
      vtkNew<vtkCharArray> bytes;
      bytes->SetArray(in[r].data(), static_cast<vtkIdType>(in[r].size()), 1);
      vtkNew<vtkUnstructuredGrid> piece;
      if (!vtkCommunicator::UnMarshalDataObject(bytes, piece))
      {
        error = "the Source cells from process " + std::to_string(r) + " could not be read";
        continue;
      }
      pieces.push_back(piece.GetPointer());
    }
  }
  // 5. One grid: points merged by global id, in the order of their ids.
  vtkNew<vtkUnstructuredGrid> merged;
  std::vector<std::vector<vtkIdType>> newId(pieces.size());
  std::vector<std::pair<long long, std::pair<size_t, vtkIdType>>> all;
  vtkIdType cellCount = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    vtkDataArray* global = pieces[i]->GetPointData()->GetArray("vtkMeshProjectionGlobalIds");
    if (!global || global->GetNumberOfTuples() != pieces[i]->GetNumberOfPoints())
    {
      error = "Source cells arrived without their points' global ids";
      return merged.GetPointer();
    }
    for (vtkIdType p = 0; p < pieces[i]->GetNumberOfPoints(); ++p)
    {
      all.push_back({ static_cast<long long>(global->GetTuple1(p)), { i, p } });
    }
    newId[i].resize(static_cast<size_t>(pieces[i]->GetNumberOfPoints()));
    cellCount += pieces[i]->GetNumberOfCells();
  }
  std::sort(all.begin(), all.end());
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  vtkNew<vtkIdTypeArray> globalIds;
  globalIds->SetName("GlobalIds");
  std::vector<std::pair<size_t, vtkIdType>> firstOf; // per merged point
  for (size_t k = 0; k < all.size(); ++k)
  {
    if (k == 0 || all[k].first != all[k - 1].first)
    {
      firstOf.push_back(all[k].second);
      globalIds->InsertNextValue(static_cast<vtkIdType>(all[k].first));
    }
    newId[all[k].second.first][all[k].second.second] = static_cast<vtkIdType>(firstOf.size() - 1);
  }
  xyz->SetNumberOfPoints(static_cast<vtkIdType>(firstOf.size()));
  for (size_t p = 0; p < firstOf.size(); ++p)
  {
    xyz->SetPoint(static_cast<vtkIdType>(p),
      pieces[firstOf[p].first]->GetPoints()->GetPoint(firstOf[p].second));
  }
  merged->SetPoints(xyz);
  bool polyhedra = false;
  for (const auto& piece : pieces)
  {
    vtkUnsignedCharArray* types = piece->GetCellTypesArray();
    const unsigned char* t = types ? types->GetPointer(0) : nullptr;
    for (vtkIdType c = 0; t && c < types->GetNumberOfValues(); ++c)
    {
      polyhedra = polyhedra || t[c] == VTK_POLYHEDRON;
    }
  }
  CellCopier copier(merged, polyhedra, cellCount);
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    const std::vector<vtkIdType>& to = newId[i];
    for (vtkIdType c = 0; c < pieces[i]->GetNumberOfCells(); ++c)
    {
      copier.Add(pieces[i], c, [&to](vtkIdType p) { return to[p]; });
    }
  }
  copier.Finish();
  this->Received = cellCount;
  // The common arrays, in the Source's own types and order.
  for (int a = 0; a < 2; ++a)
  {
    vtkDataSetAttributes* to = a == 0 ? static_cast<vtkDataSetAttributes*>(merged->GetPointData())
                                      : merged->GetCellData();
    const vtkIdType size = a == 0 ? static_cast<vtkIdType>(firstOf.size()) : cellCount;
    for (const std::string& signature : common[a])
    {
      const size_t tab = signature.find('\t');
      const std::string name = signature.substr(0, tab);
      const int type = std::stoi(signature.substr(tab + 1));
      const int nc = std::stoi(signature.substr(signature.rfind('\t') + 1));
      vtkSmartPointer<vtkDataArray> array;
      array.TakeReference(vtkDataArray::CreateDataArray(type));
      array->SetName(name.c_str());
      array->SetNumberOfComponents(nc);
      array->SetNumberOfTuples(size);
      vtkIdType at = 0;
      for (size_t i = 0; i < pieces.size(); ++i)
      {
        vtkDataArray* from = (a == 0 ? static_cast<vtkDataSetAttributes*>(pieces[i]->GetPointData())
                                     : pieces[i]->GetCellData())
                               ->GetArray(name.c_str());
        if (!from)
        {
          error = "Source array '" + name + "' is missing from the cells of a process";
          return merged.GetPointer();
        }
        if (a == 0)
        {
          for (vtkIdType p = 0; p < pieces[i]->GetNumberOfPoints(); ++p)
          {
            array->SetTuple(newId[i][p], p, from);
          }
        }
        else
        {
          for (vtkIdType c = 0; c < pieces[i]->GetNumberOfCells(); ++c)
          {
            array->SetTuple(at + c, c, from);
          }
          at += pieces[i]->GetNumberOfCells();
        }
      }
      // Component names and the active attributes as the Source has them.
      vtkDataSetAttributes* own = source->GetAttributes(a == 0 ? vtkDataObject::POINT : vtkDataObject::CELL);
      if (vtkDataArray* original = own->GetArray(name.c_str()))
      {
        for (int k = 0; k < nc && k < original->GetNumberOfComponents(); ++k)
        {
          if (original->GetComponentName(k))
          {
            array->SetComponentName(k, original->GetComponentName(k));
          }
        }
      }
      to->AddArray(array);
      if (own->GetScalars() && own->GetScalars()->GetName() && name == own->GetScalars()->GetName())
      {
        to->SetActiveScalars(name.c_str());
      }
      if (own->GetVectors() && own->GetVectors()->GetName() && name == own->GetVectors()->GetName())
      {
        to->SetActiveVectors(name.c_str());
      }
    }
  }
  merged->GetPointData()->SetGlobalIds(globalIds);
  return merged.GetPointer();
}

vtkSmartPointer<vtkDataSet> MPIParts::ShareTarget(vtkDataSet* target)
{
  const int n = this->N;
  const vtkIdType np = target->GetNumberOfPoints();
  vtkDataArray* global = target->GetPointData()->GetGlobalIds();
  bool useIds = np == 0 ||
    (global && global->GetNumberOfComponents() == 1 && global->GetNumberOfTuples() >= np);
  this->Agree(mpvtk::Verdict(), &useIds);
  std::vector<double> x(static_cast<size_t>(3 * np));
  Box bounds = EmptyBox();
  for (vtkIdType p = 0; p < np; ++p)
  {
    target->GetPoint(p, &x[3 * p]);
    Grow(bounds, &x[3 * p]);
  }
  std::vector<double> boxes(static_cast<size_t>(6 * n));
  this->C->AllGather(bounds.data(), boxes.data(), 6);
  auto boxOf = [&](int r) {
    Box b;
    std::copy(boxes.begin() + 6 * r, boxes.begin() + 6 * r + 6, b.begin());
    return b;
  };
  auto idOf = [&](vtkIdType p) { return static_cast<double>(global->GetTuple1(p)); };
  // Each point's identity: its global id (then the key's first number), or
  // its coordinates; sent as the key's first `width` numbers.
  const size_t width = useIds ? 1 : 3;
  std::vector<PointKey> keys(static_cast<size_t>(np));
  std::unordered_map<PointKey, vtkIdType, PointKeyHash> index;
  index.reserve(static_cast<size_t>(np));
  this->Representative.resize(static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    if (useIds)
    {
      keys[p].X[0] = idOf(p);
      keys[p].X[1] = keys[p].X[2] = 0.0;
    }
    else
    {
      keys[p] = KeyOf(&x[3 * p]);
    }
    this->Representative[p] = index.emplace(keys[p], p).first->second;
  }
  // Candidates to each higher process: the points inside its box (their
  // ids, or coordinates); it answers which it has.
  std::vector<std::vector<vtkIdType>> candidates(static_cast<size_t>(n));
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (int r = this->Me + 1; r < n; ++r)
  {
    const Box b = boxOf(r);
    if (!Meet(b, bounds))
    {
      continue;
    }
    for (vtkIdType p = 0; p < np; ++p)
    {
      if (this->Representative[p] == p && Inside(b, &x[3 * p]))
      {
        candidates[r].push_back(p);
        Append(out[r], keys[p].X, width);
      }
    }
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  std::vector<std::vector<vtkIdType>> shared(static_cast<size_t>(n));
  std::vector<std::vector<char>> answers(static_cast<size_t>(n));
  for (int s = 0; s < this->Me; ++s)
  {
    const std::vector<double> v = Read<double>(in[s]);
    if (v.empty())
    {
      continue;
    }
    for (size_t at = 0; at + width <= v.size(); at += width)
    {
      PointKey k{ { 0.0, 0.0, 0.0 } };
      std::copy(v.begin() + at, v.begin() + at + width, k.X);
      auto found = index.find(k);
      const char yes = found != index.end();
      answers[s].push_back(yes);
      if (yes)
      {
        shared[s].push_back(found->second);
      }
    }
  }
  std::vector<std::vector<char>> replies = this->AllToAll(answers);
  for (int r = this->Me + 1; r < n; ++r)
  {
    for (size_t i = 0; i < replies[r].size() && i < candidates[r].size(); ++i)
    {
      if (replies[r][i])
      {
        shared[r].push_back(candidates[r][i]);
      }
    }
  }
  this->Neighbours.clear();
  this->SharedPoints.clear();
  this->Owner.assign(static_cast<size_t>(np), this->Me);
  for (int r = 0; r < n; ++r)
  {
    if (!shared[r].empty())
    {
      this->Neighbours.push_back(r);
      for (vtkIdType p : shared[r])
      {
        this->Owner[p] = std::min(this->Owner[p], r);
      }
      this->SharedPoints.push_back(shared[r]);
    }
  }
  for (vtkIdType p = 0; p < np; ++p)
  {
    this->Owner[p] = this->Owner[this->Representative[p]];
  }
  if (useIds)
  {
    this->GlobalOf.resize(static_cast<size_t>(np));
    for (vtkIdType p = 0; p < np; ++p)
    {
      this->GlobalOf[p] = static_cast<long long>(idOf(this->Representative[p]));
    }
    return target;
  }
  // Global ids made: each process numbers the points it owns after those
  // of the processes before it; the others learn them from their owner.
  long long owned = 0;
  for (vtkIdType p = 0; p < np; ++p)
  {
    owned += this->Owner[p] == this->Me && this->Representative[p] == p;
  }
  std::vector<long long> counts(static_cast<size_t>(n));
  this->C->AllGather(&owned, counts.data(), 1);
  long long next = 0;
  for (int r = 0; r < this->Me; ++r)
  {
    next += counts[r];
  }
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GlobalIds");
  ids->SetNumberOfValues(np);
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p,
      this->Owner[p] == this->Me && this->Representative[p] == p ? static_cast<vtkIdType>(next++) : -1);
  }
  std::vector<std::vector<double>> send(this->Neighbours.size()), recv(this->Neighbours.size());
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    for (vtkIdType p : this->SharedPoints[i])
    {
      send[i].push_back(static_cast<double>(ids->GetValue(p)));
    }
    recv[i].resize(this->SharedPoints[i].size());
  }
  this->Swap(this->Neighbours, send, recv);
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    if (this->Neighbours[i] > this->Me)
    {
      continue;
    }
    for (size_t k = 0; k < this->SharedPoints[i].size(); ++k)
    {
      const vtkIdType p = this->SharedPoints[i][k];
      if (this->Owner[p] == this->Neighbours[i])
      {
        ids->SetValue(p, static_cast<vtkIdType>(recv[i][k]));
      }
    }
  }
  this->GlobalOf.resize(static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p, ids->GetValue(this->Representative[p]));
    this->GlobalOf[p] = static_cast<long long>(ids->GetValue(p));
  }
  vtkSmartPointer<vtkDataSet> copy;
  copy.TakeReference(target->NewInstance());
  copy->ShallowCopy(target);
  copy->GetPointData()->SetGlobalIds(ids);
  return copy;
}

bool MPIParts::SolveGathered(const mp::CsrMatrix& A, const double* B, double* X, int c,
  const std::vector<char>& converged)
{
  // The rare case of iterations that did not converge (targets covered
  // only in slivers): the whole matrix on process 0. Each process sends,
  // per row, its global id, whether it counts it and its right-hand sides
  // (complete already), then its entries by global ids (a shared row's
  // parts are summed there, as the iterations' products sum them);
  // process 0 factors the matrix and sends each process its rows' values.
  std::vector<int> open;
  for (int k = 0; k < c; ++k)
  {
    if (!converged[static_cast<size_t>(k)])
    {
      open.push_back(k);
    }
  }
  const mp::Index rows = A.Rows;
  const size_t width = open.size();
  const size_t perRow = 2 + width;
  std::vector<double> mine;
  mine.reserve(2 + static_cast<size_t>(rows) * perRow + 3 * A.Values.size());
  mine.push_back(static_cast<double>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    mine.push_back(static_cast<double>(this->RowGlobal[f]));
    mine.push_back(this->Counted[f] ? 1.0 : 0.0);
    for (int k : open)
    {
      mine.push_back(B[f * c + k]);
    }
  }
  mine.push_back(static_cast<double>(A.RowStart[rows]));
  for (mp::Index f = 0; f < rows; ++f)
  {
    for (mp::Index e = A.RowStart[f]; e < A.RowStart[f + 1]; ++e)
    {
      mine.push_back(static_cast<double>(this->RowGlobal[f]));
      mine.push_back(static_cast<double>(this->RowGlobal[static_cast<size_t>(A.ColumnIndex[e])]));
      mine.push_back(A.Values[e]);
    }
  }
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  Append(out[0], mine.data(), mine.size());
  std::vector<double>().swap(mine);
  std::vector<std::vector<char>> in = this->AllToAll(out);
  std::vector<std::vector<char>> back(static_cast<size_t>(this->N));
  if (this->Me == 0)
  {
    std::unordered_map<long long, mp::Index> index;
    auto id = [&index](double g) {
      return index.emplace(static_cast<long long>(g), static_cast<mp::Index>(index.size())).first->second;
    };
    std::vector<std::vector<double>> parts(static_cast<size_t>(this->N));
    std::vector<mp::Index> row, column;
    std::vector<double> value, b;
    for (int r = 0; r < this->N; ++r)
    {
      parts[r] = Read<double>(in[r]);
      std::vector<char>().swap(in[r]);
      const std::vector<double>& v = parts[r];
      const size_t n = v.empty() ? 0 : static_cast<size_t>(v[0]);
      for (size_t i = 0; i < n; ++i)
      {
        const double* at = v.data() + 1 + i * perRow;
        const size_t g = static_cast<size_t>(id(at[0]));
        b.resize(std::max(b.size(), (g + 1) * width), 0.0);
        for (size_t k = 0; k < width && at[1] != 0.0; ++k)
        {
          b[g * width + k] = at[2 + k];
        }
      }
      const size_t first = 1 + n * perRow;
      const size_t entries = v.empty() ? 0 : static_cast<size_t>(v[first]);
      for (size_t e = 0; e < entries; ++e)
      {
        const double* at = v.data() + first + 1 + 3 * e;
        row.push_back(id(at[0]));
        column.push_back(id(at[1]));
        value.push_back(at[2]);
      }
    }
    const mp::Index total = static_cast<mp::Index>(index.size());
    b.resize(static_cast<size_t>(total) * width, 0.0);
    std::vector<double> x(b.size(), 0.0);
    const bool solved = mp::BlockCG::SolveEntries(total, row, column, value, b.data(), x.data(),
      static_cast<int>(width));
    for (int r = 0; r < this->N; ++r)
    {
      const std::vector<double>& v = parts[r];
      const size_t n = v.empty() ? 0 : static_cast<size_t>(v[0]);
      std::vector<double> answer(1, solved ? 1.0 : 0.0);
      for (size_t i = 0; i < n && solved; ++i)
      {
        const size_t g = static_cast<size_t>(index[static_cast<long long>(v[1 + i * perRow])]);
        answer.insert(answer.end(), x.begin() + g * width, x.begin() + (g + 1) * width);
      }
      Append(back[r], answer.data(), answer.size());
    }
  }
  std::vector<std::vector<char>> answers = this->AllToAll(back);
  const std::vector<double> mineBack = Read<double>(answers[0]);
  if (mineBack.empty() || mineBack[0] == 0.0)
  {
    return false;
  }
  for (mp::Index f = 0; f < rows; ++f)
  {
    for (size_t k = 0; k < width; ++k)
    {
      X[f * c + open[k]] = mineBack[1 + static_cast<size_t>(f) * width + k];
    }
  }
  return true;
}

void MPIParts::Complete(double* v, int width, bool minimum)
{
  auto combine = [minimum](double& into, double value) {
    into = minimum ? std::min(into, value) : into + value;
  };
  // Copies of one point here: combined into its first copy (in row order).
  for (const std::vector<mp::Index>& rows : this->Copies)
  {
    for (size_t j = 1; j < rows.size(); ++j)
    {
      for (int c = 0; c < width; ++c)
      {
        combine(v[rows[0] * width + c], v[rows[j] * width + c]);
      }
    }
  }
  const size_t k = this->Neighbours.size();
  std::vector<std::vector<double>> send(k), recv(k);
  for (size_t i = 0; i < k; ++i)
  {
    send[i].reserve(this->Rows[i].size() * width);
    for (mp::Index f : this->Rows[i])
    {
      send[i].insert(send[i].end(), v + f * width, v + (f + 1) * width);
    }
    recv[i].resize(send[i].size());
  }
  this->Swap(this->Neighbours, send, recv);
  // Each shared row: the parts combined in the order of their processes,
  // from 0, on every process alike (the same value everywhere, bit for bit).
  std::unordered_map<mp::Index, size_t> slot;
  slot.reserve(this->SharedRows.size());
  std::vector<double> own(this->SharedRows.size() * width);
  std::vector<double> sum(own.size(), minimum ? std::numeric_limits<double>::infinity() : 0.0);
  for (size_t s = 0; s < this->SharedRows.size(); ++s)
  {
    slot[this->SharedRows[s]] = s;
    std::copy(v + this->SharedRows[s] * width, v + (this->SharedRows[s] + 1) * width,
      own.begin() + s * width);
  }
  bool mineAdded = false;
  auto addOwn = [&]() {
    for (size_t e = 0; e < own.size(); ++e)
    {
      combine(sum[e], own[e]);
    }
    mineAdded = true;
  };
  for (size_t i = 0; i < k; ++i)
  {
    if (!mineAdded && this->Neighbours[i] > this->Me)
    {
      addOwn();
    }
    for (size_t j = 0; j < this->Rows[i].size(); ++j)
    {
      const size_t s = slot[this->Rows[i][j]];
      for (int c = 0; c < width; ++c)
      {
        combine(sum[s * width + c], recv[i][j * width + c]);
      }
    }
  }
  if (!mineAdded)
  {
    addOwn();
  }
  for (size_t s = 0; s < this->SharedRows.size(); ++s)
  {
    std::copy(sum.begin() + s * width, sum.begin() + (s + 1) * width,
      v + this->SharedRows[s] * width);
  }
  for (const std::vector<mp::Index>& rows : this->Copies)
  {
    for (size_t j = 1; j < rows.size(); ++j)
    {
      std::copy(v + rows[0] * width, v + (rows[0] + 1) * width, v + rows[j] * width);
    }
  }
  }

mp::SolverHooks MPIParts::Hooks(
  bool points, mp::Index rows, const std::function<vtkIdType(mp::Index)>& dataSetPoint)
{
  mp::SolverHooks hooks;
  hooks.Reduce = [this](double* values, int count) { this->Sum(values, count); };
  if (!points)
  {
    // Cells: no row is shared (BlockCG factors each part's own rows).
    return hooks;
  }
  std::vector<mp::Index> rowOf(static_cast<size_t>(rows));
  this->Counted.assign(static_cast<size_t>(rows), 0);
  this->RowGlobal.resize(static_cast<size_t>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    const vtkIdType p = dataSetPoint(f);
    rowOf[static_cast<size_t>(p)] = f;
    this->RowGlobal[f] = this->GlobalOf[static_cast<size_t>(p)];
    this->Counted[f] =
      this->Owner[static_cast<size_t>(p)] == this->Me && this->Representative[static_cast<size_t>(p)] == p;
  }
  this->Copies.clear();
  {
    std::map<vtkIdType, std::vector<mp::Index>> groups;
    for (mp::Index f = 0; f < rows; ++f)
    {
      const vtkIdType p = dataSetPoint(f);
      if (this->Representative[static_cast<size_t>(p)] != p)
      {
        groups[this->Representative[static_cast<size_t>(p)]].push_back(f);
      }
    }
    for (auto& g : groups)
    {
      std::vector<mp::Index> rowsOf(1, rowOf[static_cast<size_t>(g.first)]);
      std::sort(g.second.begin(), g.second.end());
      rowsOf.insert(rowsOf.end(), g.second.begin(), g.second.end());
      this->Copies.push_back(rowsOf);
    }
  }
  this->Rows.assign(this->Neighbours.size(), std::vector<mp::Index>());
  this->SharedRows.clear();
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    for (vtkIdType p : this->SharedPoints[i])
    {
      this->Rows[i].push_back(rowOf[static_cast<size_t>(p)]);
    }
    this->SharedRows.insert(this->SharedRows.end(), this->Rows[i].begin(), this->Rows[i].end());
  }
  std::sort(this->SharedRows.begin(), this->SharedRows.end());
  this->SharedRows.erase(
    std::unique(this->SharedRows.begin(), this->SharedRows.end()), this->SharedRows.end());
  hooks.Counted = this->Counted.data();
  hooks.Exchange = [this](double* v, int width) { this->Complete(v, width, false); };
  hooks.ExchangeMinimum = [this](double* v, int width) { this->Complete(v, width, true); };
  hooks.Direct = [this](const mp::CsrMatrix& A, const double* B, double* X, int c,
                   const std::vector<char>& converged) {
    return this->SolveGathered(A, B, X, c, converged);
  };
  return hooks;
}
} // namespace

//------------------------------------------------------------------------------
vtkPMeshProjectionFilter::vtkPMeshProjectionFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPMeshProjectionFilter::~vtkPMeshProjectionFilter()
{
  this->SetController(nullptr);
}

int vtkPMeshProjectionFilter::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  if (this->Controller && this->Controller->GetNumberOfProcesses() > 1)
  {
    // Each process reads its own piece of Source (not the whole of it): the
    // cells its part of Input needs come from the others.
    using SDDP = vtkStreamingDemandDrivenPipeline;
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0);
    if (sourceInfo)
    {
      sourceInfo->CopyEntry(outInfo, SDDP::UPDATE_PIECE_NUMBER());
      sourceInfo->CopyEntry(outInfo, SDDP::UPDATE_NUMBER_OF_PIECES());
      sourceInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
  return 1;
}

int vtkPMeshProjectionFilter::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->GlobalNumberOfIntersections = 0;
  this->GlobalCoveredMeasure = 0;
  this->GlobalReceivedSourceCells = this->ReceivedSourceCells = 0;
  this->GlobalSentBytes = this->SentBytes = 0;
  vtkMultiProcessController* controller = this->Controller;
  if (!controller || controller->GetNumberOfProcesses() <= 1)
  {
    const int done = this->Superclass::RequestData(request, inputVector, outputVector);
    this->GlobalNumberOfIntersections = this->NumberOfIntersections;
    this->GlobalCoveredMeasure = this->CoveredMeasure;
    return done;
  }
  if (!vtkMPICommunicator::SafeDownCast(controller->GetCommunicator()))
  {
    vtkErrorMacro(<< "Several processes need an MPI controller (vtkMPIController); this one is a "
                  << controller->GetClassName() << ".");
    return 0;
  }
  MPIParts parts(controller);
  this->Parts = &parts;
  const int done = this->Superclass::RequestData(request, inputVector, outputVector);
  this->Parts = nullptr;
  this->ReceivedSourceCells = parts.Received;
  this->SentBytes = parts.SentBytes();
  double totals[4] = { static_cast<double>(this->NumberOfIntersections), this->CoveredMeasure,
    static_cast<double>(this->ReceivedSourceCells), this->SentBytes };
  double sums[4] = { 0, 0, 0, 0 };
  controller->AllReduce(totals, sums, 4, vtkCommunicator::SUM_OP);
  this->GlobalNumberOfIntersections = static_cast<vtkIdType>(sums[0]);
  this->GlobalCoveredMeasure = sums[1];
  this->GlobalReceivedSourceCells = static_cast<vtkIdType>(sums[2]);
  this->GlobalSentBytes = sums[3];
  return done;
}

void vtkPMeshProjectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "GlobalNumberOfIntersections: " << this->GlobalNumberOfIntersections << "\n";
  os << indent << "GlobalCoveredMeasure: " << this->GlobalCoveredMeasure << "\n";
  os << indent << "GlobalReceivedSourceCells: " << this->GlobalReceivedSourceCells << "\n";
  os << indent << "GlobalSentBytes: " << this->GlobalSentBytes << "\n";
}
