// SPDX-License-Identifier: BSD-3-Clause
// mesh-projection-bench: how fast is the mortar projection, stage by stage,
// and against the alternatives, on random non-matching meshes of the unit
// square (triangles) and the unit cube (tetrahedra).
//
//   mesh-projection-bench [--dim 2|3|23] [--sizes 1e3,1e4,1e5,1e6]
//                         [--brute-max 2e4] [--csv FILE] [--filter-only [--threads N]]
//
// For each size n (cells of the target; the source has about as many, on a
// different, jittered grid) it prints one table: the time of every stage of
// the kernel (neighbours, seeding, search + intersections + local
// integrals, assembly, solve), pairs and pairs per second,
// peak memory beyond the inputs, and in the same run the ratios of the
// advancing front against the brute force (up to --brute-max cells), against
// a locator search (vtkStaticCellLocator::FindCellsWithinBounds per target
// cell, then the same intersector), and of the whole VTK filter against
// ParaView's Resample With Dataset (vtkResampleWithDataSet) on the same
// target, with the filter on 1 and 2 threads (its own scope: STDThread, on
// the filter's WorkerPool).
// --filter-only runs just the VTK filter once per size (the best of N runs
// with --runs N, the peer's too, the two alternating), on the calling thread (or on N threads with
// --threads N; with --threads N,M on N and on M threads in alternating runs,
// so that both meet the same spells of a shared host's load, and their
// ratio), and prints its stages (for profiling).
// --order asis|sorted|shuffled renumbers both meshes first, --renumber sets
// the filter's Renumbering, --target/--source read a pair of .vtu files
// instead (one run), and --peer LIB times libsupermesh's intersections on
// the same meshes (see Peer below).
// Timings are wall-clock seconds, the best of three runs for the kernel's
// stages and the filter's, one run for the others; ratios, not absolute
// seconds, carry the comparison.
#include "Mesh/SpatialOrder.h"
#include "Search/PairSearch.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/MortarOperator.h"
#include "GeneratedMeshes.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkMeshProjectionFilter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkResampleWithDataSet.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <array>
#include <numeric>
#include <random>

#include <chrono>
#include <dlfcn.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// A memory figure of /proc/self/status in MiB: VmHWM (peak resident memory
/// since the last ResetPeakMemory()) or VmRSS (current).
double StatusMiB(const char* key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  const size_t n = std::strlen(key);
  while (std::getline(status, line))
  {
    if (line.compare(0, n, key) == 0)
    {
      return std::atof(line.c_str() + n) / 1024.0;
    }
  }
  return 0;
}
void ResetPeakMemory()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}

double InputMemory(const TestMesh& m)
{
  return (m.Points.size() * sizeof(double) + m.Cells.size() * sizeof(Index)) / 1048576.0;
}

/// --order: how the cells and points of both meshes are numbered.
std::string Order = "asis";

/**
 * Renumbers `m`'s cells and points. "asis": unchanged (the generator's or
 * the file's numbering); "shuffled": cells and points in a random order;
 * "sorted": cells sorted into bands of about four cells' width along y,
 * by x inside a band, and points in the order the cells first use them
 * (the locality of a sweeping mesher).
 */
void MakeGeneratedPair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source);

void Renumber(TestMesh& m, const std::string& order, unsigned seed)
{
  const int corners = m.Dimension + 1;
  const Index cells = m.NumberOfCells();
  const Index points = m.NumberOfPoints();
  if (order == "asis" || cells == 0)
  {
    return;
  }
  std::vector<Index> cellOrder(static_cast<size_t>(cells)); // new -> old
  std::iota(cellOrder.begin(), cellOrder.end(), Index(0));
  std::vector<double> x(m.Points.size());
  std::vector<Index> ids(m.Cells.size());
  if (order == "shuffled")
  {
    std::vector<Index> pointOrder(static_cast<size_t>(points)); // new -> old
    std::iota(pointOrder.begin(), pointOrder.end(), Index(0));
    std::mt19937_64 random(seed);
    std::shuffle(cellOrder.begin(), cellOrder.end(), random);
    std::shuffle(pointOrder.begin(), pointOrder.end(), random);
    std::vector<Index> newId(static_cast<size_t>(points));
    for (Index p = 0; p < points; ++p)
    {
      newId[pointOrder[p]] = p;
      std::copy_n(&m.Points[3 * pointOrder[p]], 3, &x[3 * p]);
    }
    for (Index c = 0; c < cells; ++c)
    {
      for (int k = 0; k < corners; ++k)
      {
        ids[corners * c + k] = newId[m.Cells[corners * cellOrder[c] + k]];
      }
    }
  }
  else
  {
    double lo[3] = { 1e300, 1e300, 1e300 };
    double hi[3] = { -1e300, -1e300, -1e300 };
    for (Index p = 0; p < points; ++p)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], m.Points[3 * p + a]);
        hi[a] = std::max(hi[a], m.Points[3 * p + a]);
      }
    }
    double volume = 1;
    for (int a = 0; a < m.Dimension; ++a)
    {
      volume *= std::max(1e-300, hi[a] - lo[a]);
    }
    const double band = 4 * std::pow(volume / double(cells), 1.0 / m.Dimension);
    std::vector<std::array<double, 3>> key(static_cast<size_t>(cells));
    for (Index c = 0; c < cells; ++c)
    {
      double centre[3] = {};
      for (int k = 0; k < corners; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          centre[a] += m.Points[3 * m.Cells[corners * c + k] + a] / corners;
        }
      }
      // 2D: bands along y, x inside; 3D: slabs along z, bands along y, x inside.
      key[c] = m.Dimension == 2
        ? std::array<double, 3>{ std::floor((centre[1] - lo[1]) / band), centre[0], 0.0 }
        : std::array<double, 3>{ std::floor((centre[2] - lo[2]) / band),
            std::floor((centre[1] - lo[1]) / band), centre[0] };
    }
    std::sort(cellOrder.begin(), cellOrder.end(),
      [&](Index a, Index b) { return key[a] < key[b]; });
    // Points in the order the sorted cells first use them: the kernel's
    // renumbering, given this cell order.
    mp::SpatialOrder sorted;
    sorted.Cells.assign(cellOrder.begin(), cellOrder.end());
    mp::RenumberMesh(m.View(false), sorted, x.data(), ids.data(), sorted.Cells.data());
  }
  m.Points.swap(x);
  m.Cells.swap(ids);
  m.Neighbors.clear();
}

/// --target/--source: meshes read from files instead of generated.
std::string TargetFile;
std::string SourceFile;

/// The tetrahedra of a .vtu file, or its triangles when it has no tetrahedra.
bool ReadMesh(const std::string& name, TestMesh& m)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(name.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  const vtkIdType n = grid->GetNumberOfPoints();
  m.Points.resize(static_cast<size_t>(3 * n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    grid->GetPoint(p, &m.Points[3 * p]);
  }
  for (int type : { VTK_TETRA, VTK_TRIANGLE })
  {
    m.Dimension = type == VTK_TETRA ? 3 : 2;
    m.Cells.clear();
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      if (grid->GetCellType(c) == type)
      {
        vtkIdType count;
        const vtkIdType* ids;
        grid->GetCellPoints(c, count, ids);
        m.Cells.insert(m.Cells.end(), ids, ids + count);
      }
    }
    if (!m.Cells.empty())
    {
      return true;
    }
  }
  std::fprintf(stderr, "no triangles or tetrahedra in %s\n", name.c_str());
  return false;
}

/// A pair of non-matching meshes with about n target cells.
void MakePair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source)
{
  if (!TargetFile.empty())
  {
    if (!ReadMesh(TargetFile, target) || !ReadMesh(SourceFile, source))
    {
      std::exit(1);
    }
  }
  else
  {
    MakeGeneratedPair(dim, n, seed, target, source);
  }
  if (target.Dimension != source.Dimension)
  {
    std::fprintf(stderr, "the target has %d-dimensional cells, the source %d-dimensional ones\n",
      target.Dimension, source.Dimension);
    std::exit(1);
  }
  Renumber(target, Order, seed);
  Renumber(source, Order, seed + 17);
}

/// A pair of non-matching jittered grids with about n target cells.
void MakeGeneratedPair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source)
{
  if (dim == 2)
  {
    const int k = std::max(2, int(std::lround(std::sqrt(n / 2))));
    target = mptest::GridMesh(k, k, 0.25, seed);
    source = mptest::GridMesh(k + 3, k - 1, 0.25, seed + 1);
  }
  else
  {
    const int k = std::max(2, int(std::lround(std::cbrt(n / 6))));
    target = mptest::CubeMesh(k, k, k, 0.15, seed);
    source = mptest::CubeMesh(k + 1, k, k - 1, 0.15, seed + 1);
  }
}

vtkSmartPointer<vtkUnstructuredGrid> ToVTK(const TestMesh& m, const std::vector<double>* field)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkDoubleArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(m.NumberOfPoints());
  std::copy(m.Points.begin(), m.Points.end(), coords->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  grid->SetPoints(points);
  const int corners = m.Dimension + 1;
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(m.NumberOfCells() + 1);
  for (Index c = 0; c <= m.NumberOfCells(); ++c)
  {
    offsets->SetValue(c, corners * c);
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(m.Cells.size()));
  std::copy(m.Cells.begin(), m.Cells.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  grid->SetCells(m.Dimension == 2 ? VTK_TRIANGLE : VTK_TETRA, cells);
  if (field)
  {
    vtkNew<vtkDoubleArray> u;
    u->SetName("u");
    u->SetNumberOfValues(m.NumberOfPoints());
    std::copy(field->begin(), field->end(), u->GetPointer(0));
    grid->GetPointData()->AddArray(u);
  }
  return grid;
}

struct Row
{
  int Dim;
  Index TargetCells;
  Index SourceCells;
  double Neighbors, Seeding, Search, Assembly, Solve, Total;
  Index Pairs;
  double PeakBeyondInputs, InputSize;
  double Brute = -1, Locator = -1, Filter1 = -1, Filter2 = -1, Resample = -1;
  double Peer = -1;        ///< --peer: libsupermesh's intersections, seconds
  double PeerMeasure = 0;  ///< --peer: the summed measure of its pieces
  Index PeerCandidates = 0, PeerPieces = 0;
  double FilterPeak = -1;  ///< --filter-only: the filter's peak memory beyond its inputs, MiB
  double VTKInputs = 0;    ///< --filter-only: the two vtkUnstructuredGrids, MiB
  double KernelOnPairs = -1; ///< intersection kernel alone on the true pairs
  Index Tests = 0;   ///< --filter-only: intersection tests
  Index Queries = 0; ///< --filter-only: locator queries
  /// The VTK filter's own stages (vtkMeshProjectionFilter::Get*Time) on 1
  /// and 2 threads: input, neighbours, locator, search, assembly, solve, output.
  double FilterStages[2][7] = {};
  double CheckTime[2] = {}; ///< of the filter's input stage: the id and offset checks
  double RenumberTime[2] = {}; ///< of the filter's input stage: renumbering along space
  int Renumbered = 0;          ///< meshes the filter renumbered
};

/// Pairs found by asking vtkStaticCellLocator for the candidates of every
/// target cell, then intersecting each candidate: the usual alternative to
/// the advancing front.
template <class Intersector>
Index LocatorSearch(const TestMesh& target, const TestMesh& source, vtkUnstructuredGrid* sourceGrid)
{
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(sourceGrid);
  locator->BuildLocator();
  vtkNew<vtkIdList> ids;
  typename Intersector::Cell t;
  typename Intersector::Cell s;
  typename Intersector::Piece piece;
  Index pairs = 0;
  double box[6];
  for (Index c = 0; c < target.NumberOfCells(); ++c)
  {
    if (!Intersector::Prepare(target.View(), c, t))
      continue;
    Intersector::Bounds(t, box);
    locator->FindCellsWithinBounds(box, ids);
    for (vtkIdType id : *ids)
    {
      if (Intersector::Prepare(source.View(), id, s) && Intersector::Intersect(t, s, piece))
      {
        ++pairs;
      }
    }
  }
  return pairs;
}

/// Records the (target, source) pairs whose intersection has positive measure.
template <class Intersector>
struct TruePairs
{
  std::vector<std::pair<Index, Index>> Pairs;
  void operator()(const typename Intersector::Cell& t, const typename Intersector::Cell& s,
    const typename Intersector::Piece& piece)
  {
    if (Intersector::Measure(piece) > 0.0)
    {
      this->Pairs.emplace_back(t.Id, s.Id);
    }
  }
};

/**
 * The intersection kernel alone on the true pairs, in the order the front
 * found them: preparing both cells, the intersection and the local
 * integrals (the piece's moments, the mixed block, the target cell's mass
 * block once per cell), and nothing else: no search, no neighbours, no
 * failed tests, no sums into the global matrices.
 * The search time beyond this is the search overhead.
 */
template <class Intersector>
double KernelOnTruePairs(const TestMesh& target, const TestMesh& source, const double* u)
{
  constexpr int D = Intersector::Dimension;
  constexpr int N = D + 1;
  using P1 = mp::P1Space<D>;
  mp::BoxGridLocator locator(source.View());
  TruePairs<Intersector> found;
  mp::SearchStatistics stats;
  mp::AdvancingFrontSearch<Intersector>(target.View(), source.View(), locator, found, stats);
  typename Intersector::Cell t;
  typename Intersector::Cell s;
  typename Intersector::Piece piece;
  double sink = 0.0;
  const auto t0 = Clock::now();
  Index current = -1;
  double moments[N][N] = {};
  double mtt[N][N] = {};
  for (const auto& pair : found.Pairs)
  {
    if (pair.first != current)
    {
      if (current >= 0)
      {
        P1::MassFromMoments(t, moments, mtt); // the target cell's M_tt block
        sink += mtt[0][1];
      }
      current = pair.first;
      Intersector::Prepare(target.View(), current, t);
      std::fill(&moments[0][0], &moments[0][0] + N * N, 0.0);
    }
    Intersector::Prepare(source.View(), pair.second, s);
    Intersector::Intersect(t, s, piece);
    double o[D];
    double M[N][N];
    sink += Intersector::Moments(piece, o, M);
    double d[D];
    for (int a = 0; a < D; ++a)
    {
      d[a] = o[a] - t.X[0][a];
    }
    mp::AddShiftedMoments<N>(M, d, moments);
    double lt[N][N];
    double ls[N][N];
    P1::Basis(t, o, lt);
    P1::Basis(s, o, ls);
    double mts[N][N] = {};
    mp::AddMixedBlock<N, N, N>(lt, ls, M, mts);
    sink += mts[0][1] * u[s.Points[1]];
  }
  const double seconds = Since(t0);
  if (sink == 12345.678) // keeps the loop from being optimized away
  {
    std::printf(" ");
  }
  return seconds;
}

double Field(const double* x)
{
  return std::sin(3 * x[0]) * std::cos(2 * x[1]) + x[2];
}


/**
 * --peer LIB: libsupermesh (https://github.com/firedrakeproject/libsupermesh),
 * loaded at run time from its shared library through its C API, on the same
 * meshes: its tree intersection finder (candidate source cells of every
 * target cell from a quadtree/octree of bounding boxes), then its
 * triangle/tetrahedron clipper on every candidate, summing the measure of
 * the pieces (the check that both found the same overlap). That is the
 * intersection part of a supermesh projection only: no neighbours of ours,
 * no integrals, no assembly, no solve.
 */
struct Peer
{
  using SetInput = void (*)(long*, int*, long*, int*, long*, int*, long*, int*, double*, long*,
    double*, long*);
  using QueryOutput = void (*)(long*);
  using GetOutput = void (*)(long*, long*, long*, long*);
  using Intersect = void (*)(double*, double*, double*, int*);
  SetInput TreeSetInput = nullptr;
  QueryOutput TreeQuery = nullptr;
  GetOutput TreeGet = nullptr;
  Intersect Tris = nullptr;
  Intersect Tets = nullptr;

  bool Load(const std::string& library)
  {
    void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
    {
      std::fprintf(stderr, "--peer: cannot load %s: %s\n", library.c_str(), dlerror());
      return false;
    }
    this->TreeSetInput =
      reinterpret_cast<SetInput>(dlsym(handle, "libsupermesh_tree_intersection_finder_set_input"));
    this->TreeQuery = reinterpret_cast<QueryOutput>(
      dlsym(handle, "libsupermesh_tree_intersection_finder_query_output"));
    this->TreeGet =
      reinterpret_cast<GetOutput>(dlsym(handle, "libsupermesh_tree_intersection_finder_get_output"));
    this->Tris = reinterpret_cast<Intersect>(dlsym(handle, "libsupermesh_intersect_tris_real"));
    this->Tets = reinterpret_cast<Intersect>(dlsym(handle, "libsupermesh_intersect_tets_real"));
    if (!this->TreeSetInput || !this->TreeQuery || !this->TreeGet || !this->Tris || !this->Tets)
    {
      std::fprintf(stderr, "--peer: %s lacks libsupermesh's C API\n", library.c_str());
      return false;
    }
    return true;
  }

  /// Seconds for all intersections of target x source (one run); `measure`
  /// gets the summed measure of the pieces (inside the clock: a few flops
  /// per piece), `candidates` the finder's pairs, `pieces` the pairs whose
  /// intersection is not empty.
  double Run(const TestMesh& target, const TestMesh& source, double& measure, Index& candidates,
    Index& pieces) const
  {
    const int dim = target.Dimension;
    const int corners = dim + 1;
    auto positions = [dim](const TestMesh& m) {
      std::vector<double> x(static_cast<size_t>(dim * m.NumberOfPoints()));
      for (Index p = 0; p < m.NumberOfPoints(); ++p)
      {
        std::copy_n(&m.Points[3 * p], dim, &x[dim * p]);
      }
      return x;
    };
    auto elements = [](const TestMesh& m) { return std::vector<long>(m.Cells.begin(), m.Cells.end()); };
    // Its input layout (coordinates without the z of 2D meshes, element
    // lists as C longs; its C API numbers from 0) is prepared outside the clock.
    std::vector<double> xa = positions(target);
    std::vector<double> xb = positions(source);
    std::vector<long> ea = elements(target);
    std::vector<long> eb = elements(source);
    long na = target.NumberOfPoints();
    long nb = source.NumberOfPoints();
    long ca = target.NumberOfCells();
    long cb = source.NumberOfCells();
    int da = dim;
    int db = dim;
    int la = corners;
    int lb = corners;
    const auto t0 = Clock::now();
    this->TreeSetInput(&na, &da, &ca, &la, &nb, &db, &cb, &lb, xa.data(), ea.data(), xb.data(),
      eb.data());
    long total = 0;
    this->TreeQuery(&total);
    std::vector<long> indices(static_cast<size_t>(std::max(1L, total)));
    std::vector<long> start(static_cast<size_t>(ca + 1));
    this->TreeGet(&ca, &total, indices.data(), start.data());
    // Its clipper's output buffers: at most 22 triangles or 81 tetrahedra.
    std::vector<double> out(static_cast<size_t>(dim == 2 ? 22 * 6 : 81 * 12));
    double a[12];
    double b[12];
    double sum = 0;
    pieces = 0;
    for (long c = 0; c < ca; ++c)
    {
      for (int k = 0; k < corners; ++k)
      {
        std::copy_n(&xa[dim * target.Cells[corners * c + k]], dim, &a[dim * k]);
      }
      for (long i = start[c]; i < start[c + 1]; ++i)
      {
        const long s = indices[i];
        for (int k = 0; k < corners; ++k)
        {
          std::copy_n(&xb[dim * source.Cells[corners * s + k]], dim, &b[dim * k]);
        }
        int n = 0;
        (dim == 2 ? this->Tris : this->Tets)(a, b, out.data(), &n);
        pieces += n > 0 ? 1 : 0;
        for (int j = 0; j < n; ++j)
        {
          const double* x = &out[static_cast<size_t>(j) * corners * dim];
          if (dim == 2)
          {
            sum += 0.5 * std::abs((x[2] - x[0]) * (x[5] - x[1]) - (x[4] - x[0]) * (x[3] - x[1]));
          }
          else
          {
            double e[3][3];
            for (int r = 0; r < 3; ++r)
            {
              for (int q = 0; q < 3; ++q)
              {
                e[r][q] = x[3 * (r + 1) + q] - x[q];
              }
            }
            sum += std::abs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
              6.0;
          }
        }
      }
    }
    const double seconds = Since(t0);
    measure = sum;
    candidates = total;
    return seconds;
  }
};

/// --peer: the loaded peer, if any.
Peer ThePeer;
bool HavePeer = false;

/// --threads N[,M]: the threads of the filter in --filter-only runs (and
/// of the runs alternating with them; 0: none).
int FilterThreads = 1;
int FilterThreads2 = 0;
/// --runs: --filter-only times the filter and the peer this many times
/// each and keeps the best of each (the peak memory: the first run's).
int FilterRuns = 1;
/// --renumber auto|always|never: the filter's Renumbering.
int Renumbering = vtkMeshProjectionFilter::AUTOMATIC_RENUMBERING;

/**
 * Runs the whole VTK filter on the pair `runs` times on `threads` threads and
 * keeps the best time in `best`, with that run's stages, checks, renumbering
 * and counts in slot `slot` of `r` (and its intersections in `pairs`, when
 * given). With `peak`, each run starts from memory given back to the system
 * and `r.FilterPeak` gets the largest peak beyond what was resident before it
 * (MiB).
 */
void TimeFilter(vtkUnstructuredGrid* targetGrid, vtkUnstructuredGrid* sourceGrid, int threads,
  int runs, bool peak, int slot, double& best, Row& r, Index* pairs = nullptr)
{
  for (int run = 0; run < runs; ++run)
  {
    vtkNew<vtkMeshProjectionFilter> filter;
    filter->SetNumberOfThreads(threads);
    filter->SetRenumbering(Renumbering);
    filter->SetInputData(targetGrid);
    filter->SetSourceData(sourceGrid);
    double before = 0;
    if (peak)
    {
#if defined(__GLIBC__)
      malloc_trim(0);
#endif
      before = StatusMiB("VmRSS:");
      ResetPeakMemory();
    }
    const auto t0 = Clock::now();
    filter->Update();
    const double seconds = Since(t0);
    if (peak)
    {
      r.FilterPeak = std::max(r.FilterPeak, StatusMiB("VmHWM:") - before);
    }
    if (best >= 0 && seconds >= best)
    {
      continue;
    }
    best = seconds;
    const double stages[7] = { filter->GetInputTime(), filter->GetNeighborsTime(),
      filter->GetLocatorTime(), filter->GetSearchTime(), filter->GetAssemblyTime(),
      filter->GetSolveTime(), filter->GetOutputTime() };
    std::copy(stages, stages + 7, r.FilterStages[slot]);
    r.CheckTime[slot] = filter->GetCheckTime();
    r.RenumberTime[slot] = filter->GetRenumberTime();
    if (slot == 0) // (the counts printed are the first slot's runs')
    {
      r.Renumbered = filter->GetNumberOfRenumberedMeshes();
      r.Tests = filter->GetNumberOfIntersectionTests();
      r.Queries = filter->GetNumberOfLocatorQueries();
    }
    if (pairs)
    {
      *pairs = filter->GetNumberOfIntersections();
    }
  }
}

Row Measure(int dim, double n, double bruteMax, bool filterOnly)
{
  Row r{};
  r.Dim = dim;
  TestMesh target;
  TestMesh source;
  MakePair(dim, n, 7, target, source);
  dim = r.Dim = target.Dimension; // a file's mesh says its dimension
  r.TargetCells = target.NumberOfCells();
  r.SourceCells = source.NumberOfCells();
  r.InputSize = InputMemory(target) + InputMemory(source);
  std::vector<double> u(static_cast<size_t>(source.NumberOfPoints()));
  for (Index p = 0; p < source.NumberOfPoints(); ++p)
  {
    u[p] = Field(&source.Points[3 * p]);
  }

  if (filterOnly)
  {
    auto sourceGrid = ToVTK(source, &u);
    auto targetGrid = ToVTK(target, nullptr);
    r.VTKInputs = (targetGrid->GetActualMemorySize() + sourceGrid->GetActualMemorySize()) / 1024.0;
    r.FilterPeak = 0;
    // The filter's runs and the peer's alternate, so that both meet the same
    // spells of a shared host's load (their ratio is the measure). The
    // filter's peak memory is its first run's, before any of the peer's
    // (after them, the process's heap measured about 10% more).
    double firstPeak = 0;
    for (int run = 0; run < FilterRuns; ++run)
    {
      TimeFilter(targetGrid, sourceGrid, FilterThreads, 1, true, 0, r.Filter1, r, &r.Pairs);
      if (run == 0)
      {
        firstPeak = r.FilterPeak;
      }
      if (FilterThreads2 > 0)
      {
        TimeFilter(targetGrid, sourceGrid, FilterThreads2, 1, false, 1, r.Filter2, r);
      }
      if (HavePeer)
      {
        const double seconds = ThePeer.Run(target, source, r.PeerMeasure, r.PeerCandidates, r.PeerPieces);
        r.Peer = run == 0 ? seconds : std::min(r.Peer, seconds);
      }
    }
    r.FilterPeak = firstPeak;
    return r;
  }
  // The kernel, stage by stage (one thread), best of three runs; the peak
  // memory of the first.
  // Freed heap memory of earlier sizes would count as "before" and hide
  // the peak: give it back to the system first.
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  const double before = StatusMiB("VmRSS:");
  ResetPeakMemory();
  for (int run = 0; run < 3; ++run)
  {
    Row k = r;
    auto t0 = Clock::now();
    mp::BuildFaceNeighbors(target.View(false), target.Neighbors);
    mp::BuildFaceNeighbors(source.View(false), source.Neighbors);
    k.Neighbors = Since(t0);
    t0 = Clock::now();
    mp::BoxGridLocator locator(source.View());
    k.Seeding = Since(t0);
    mp::MortarOperator projector;
    mp::OperatorOptions single; // the field's right-hand side summed in the search, as the filter does
    single.Fields = u.data();
    single.FieldComponents = 1;
    projector.Build(target.View(), source.View(), &locator, single);
    std::vector<double> ut(static_cast<size_t>(target.NumberOfPoints()));
    t0 = Clock::now();
    projector.Apply(u.data(), 1, ut.data(), std::nan(""));
    k.Solve = Since(t0);
    k.Search = projector.GetTimings().Search;
    k.Assembly = projector.GetTimings().Assembly;
    k.Total = k.Neighbors + k.Seeding + k.Search + k.Assembly + k.Solve;
    k.Pairs = projector.GetStatistics().Pieces;
    if (run == 0)
    {
      r.PeakBeyondInputs = StatusMiB("VmHWM:") - before;
    }
    if (run == 0 || k.Total < r.Total)
    {
      k.PeakBeyondInputs = r.PeakBeyondInputs;
      r = k;
    }
  }

  Clock::time_point t0;
  r.KernelOnPairs = dim == 2
    ? KernelOnTruePairs<mp::TriangleIntersector>(target, source, u.data())
    : KernelOnTruePairs<mp::TetrahedronIntersector>(target, source, u.data());

  auto sourceGrid = ToVTK(source, &u);
  auto targetGrid = ToVTK(target, nullptr);
  // Brute force (quadratic: small sizes only).
  if (static_cast<double>(r.TargetCells) <= bruteMax)
  {
    mp::OperatorOptions brute; // as the front's run: the field summed in the search
    brute.Method = mp::SearchMethod::BruteForce;
    brute.Fields = u.data();
    brute.FieldComponents = 1;
    mp::MortarOperator b;
    t0 = Clock::now();
    b.Build(target.View(), source.View(), nullptr, brute);
    r.Brute = Since(t0);
  }
  // Locator-based search with the same intersector.
  t0 = Clock::now();
  const Index located = dim == 2
    ? LocatorSearch<mp::TriangleIntersector>(target, source, sourceGrid)
    : LocatorSearch<mp::TetrahedronIntersector>(target, source, sourceGrid);
  r.Locator = Since(t0);
  (void)located;
  // The whole VTK filter, 1 and 2 threads, and vtkResampleWithDataSet.
  // Best of three runs each: on a shared (virtual) machine a run can pay
  // for fresh memory pages or a busy neighbour that the others do not.
  for (int threads : { 1, 2 })
  {
    TimeFilter(targetGrid, sourceGrid, threads, 3, false, threads - 1,
      threads == 1 ? r.Filter1 : r.Filter2, r);
  }
  vtkNew<vtkResampleWithDataSet> resample;
  resample->SetInputData(targetGrid);
  resample->SetSourceData(sourceGrid);
  t0 = Clock::now();
  resample->Update();
  r.Resample = Since(t0);
  if (HavePeer)
  {
    r.Peer = ThePeer.Run(target, source, r.PeerMeasure, r.PeerCandidates, r.PeerPieces);
  }
  return r;
}

std::vector<double> ParseList(const char* text)
{
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    values.push_back(std::atof(item.c_str()));
  }
  return values;
}

const char* const FilterStageNames[7] = { "reading the inputs", "neighbours",
  "seeding (boundary-cell bins)", "search + intersections + integrals", "assembly", "solve",
  "writing the outputs" };

/// --peer: libsupermesh's time on the same meshes, against the filter's.
void PrintPeer(const Row& r, double filter)
{
  if (r.Peer < 0)
  {
    return;
  }
  std::printf("  %-34s %10.4f  (%lld candidates, %lld pairs with a piece, measure %.12g)\n",
    "libsupermesh intersections only", r.Peer, static_cast<long long>(r.PeerCandidates),
    static_cast<long long>(r.PeerPieces), r.PeerMeasure);
  std::printf("  %-34s %10.2fx\n", "VTK filter / libsupermesh", filter / r.Peer);
}

/// --filter-only: the VTK filter on the calling thread, stage by stage.
void PrintFilter(const Row& r)
{
  std::printf("\n%dD  target %lld cells, source %lld cells, %lld intersecting pairs\n", r.Dim,
    static_cast<long long>(r.TargetCells), static_cast<long long>(r.SourceCells),
    static_cast<long long>(r.Pairs));
  const std::string runs =
    FilterRuns > 1 ? "VTK filter (best of " + std::to_string(FilterRuns) + ")" : "VTK filter (one run)";
  std::printf("  %-34s %10.4f  (%.2f tests per pair, %lld locator queries)\n", runs.c_str(),
    r.Filter1, double(r.Tests) / std::max<Index>(1, r.Pairs), static_cast<long long>(r.Queries));
  for (int k = 0; k < 7; ++k)
  {
    std::printf("    %-32s %10.4f\n", FilterStageNames[k], r.FilterStages[0][k]);
    if (k == 0)
    {
      std::printf("      %-30s %10.4f\n", "of which id/offset checks", r.CheckTime[0]);
      std::printf("      %-30s %10.4f  (%d of 2 meshes)\n", "of which renumbering", r.RenumberTime[0],
        r.Renumbered);
    }
  }
  std::printf("  %-34s %10.1f MiB (inputs %.1f MiB, ratio %.2f)\n", "filter's peak memory beyond inputs",
    r.FilterPeak, r.VTKInputs, r.FilterPeak / r.VTKInputs);
  if (FilterThreads2 > 0)
  {
    // The runs alternating with those above, on the other number of threads.
    const std::string other = "VTK filter on " + std::to_string(FilterThreads2) + " threads";
    std::printf("  %-34s %10.4f  (%d against %d threads: %.2fx)\n", other.c_str(), r.Filter2,
      FilterThreads2, FilterThreads, r.Filter1 / r.Filter2);
    for (int k = 0; k < 7; ++k)
    {
      std::printf("    %-32s %10.4f\n", FilterStageNames[k], r.FilterStages[1][k]);
    }
  }
  PrintPeer(r, r.Filter1);
}

void Print(const Row& r)
{
  const double cells = static_cast<double>(r.TargetCells);
  std::printf("\n%dD  target %lld cells, source %lld cells, %lld intersecting pairs\n", r.Dim,
    static_cast<long long>(r.TargetCells), static_cast<long long>(r.SourceCells),
    static_cast<long long>(r.Pairs));
  std::printf("  %-34s %10s %12s\n", "stage (kernel, 1 thread)", "seconds", "us per cell");
  const std::pair<const char*, double> stages[] = { { "neighbours", r.Neighbors },
    { "seeding (locator build)", r.Seeding }, { "search + intersections + integrals", r.Search },
    { "assembly", r.Assembly },
    { "solve", r.Solve }, { "total", r.Total } };
  for (const auto& s : stages)
  {
    std::printf("  %-34s %10.4f %12.3f\n", s.first, s.second, 1e6 * s.second / cells);
  }
  std::printf("  pairs per second (search)          %10.3g\n", r.Pairs / r.Search);
  std::printf("  intersection kernel on true pairs  %10.4f  (search overhead %.0f%% of the search)\n",
    r.KernelOnPairs, 100.0 * (r.Search - r.KernelOnPairs) / r.Search);
  std::printf("  peak memory beyond inputs          %10.1f MiB (inputs %.1f MiB, ratio %.2f)\n",
    r.PeakBeyondInputs, r.InputSize, r.PeakBeyondInputs / r.InputSize);
  std::printf("  %-34s %10s %12s\n", "comparison", "seconds", "ratio");
  if (r.Brute >= 0)
  {
    std::printf("  %-34s %10.4f %11.1fx\n", "brute force / advancing front", r.Brute,
      r.Brute / (r.Search + r.Assembly));
  }
  std::printf("  %-34s %10.4f %11.2fx\n", "locator search / front search", r.Locator,
    r.Locator / r.Search);
  std::printf("  %-34s %10.4f\n", "VTK filter, 1 thread", r.Filter1);
  std::printf("  %-34s %10.4f %11.2fx\n", "VTK filter, 2 threads (speed-up)", r.Filter2,
    r.Filter1 / r.Filter2);
  std::printf("    %-32s %10s %10s\n", "VTK filter stages", "1 thread", "2 threads");
  for (int k = 0; k < 7; ++k)
  {
    std::printf("    %-32s %10.4f %10.4f\n", FilterStageNames[k], r.FilterStages[0][k],
      r.FilterStages[1][k]);
    if (k == 0)
    {
      std::printf("      %-30s %10.4f %10.4f\n", "of which id/offset checks", r.CheckTime[0],
        r.CheckTime[1]);
      std::printf("      %-30s %10.4f %10.4f  (%d of 2 meshes)\n", "of which renumbering",
        r.RenumberTime[0], r.RenumberTime[1], r.Renumbered);
    }
  }
  std::printf("  %-34s %10.4f %11.2fx\n", "Resample With Dataset / filter", r.Resample,
    r.Resample / r.Filter1);
  PrintPeer(r, r.Filter1);
}
} // namespace

int main(int argc, char* argv[])
{
  std::string dims = "23";
  std::vector<double> sizes = { 1e3, 1e4, 1e5, 1e6 };
  double bruteMax = 2e4;
  std::string csv;
  bool filterOnly = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--filter-only")
      filterOnly = true;
    else if (a == "--threads" && i + 1 < argc)
    {
      const std::string value = argv[++i];
      const size_t comma = value.find(',');
      FilterThreads = std::max(1, std::atoi(value.substr(0, comma).c_str()));
      FilterThreads2 =
        comma == std::string::npos ? 0 : std::max(1, std::atoi(value.substr(comma + 1).c_str()));
    }
    else if (a == "--runs" && i + 1 < argc)
      FilterRuns = std::max(1, std::atoi(argv[++i]));
    else if (a == "--dim" && i + 1 < argc)
      dims = argv[++i];
    else if (a == "--sizes" && i + 1 < argc)
      sizes = ParseList(argv[++i]);
    else if (a == "--brute-max" && i + 1 < argc)
      bruteMax = std::atof(argv[++i]);
    else if (a == "--csv" && i + 1 < argc)
      csv = argv[++i];
    else if (a == "--renumber" && i + 1 < argc)
    {
      const std::string m = argv[++i];
      Renumbering = m == "always" ? vtkMeshProjectionFilter::ALWAYS_RENUMBER
        : m == "never"            ? vtkMeshProjectionFilter::NEVER_RENUMBER
                                  : vtkMeshProjectionFilter::AUTOMATIC_RENUMBERING;
    }
    else if (a == "--peer" && i + 1 < argc)
    {
      HavePeer = ThePeer.Load(argv[++i]);
      if (!HavePeer)
      {
        return 1;
      }
    }
    else if (a == "--order" && i + 1 < argc)
      Order = argv[++i];
    else if (a == "--target" && i + 1 < argc)
      TargetFile = argv[++i];
    else if (a == "--source" && i + 1 < argc)
      SourceFile = argv[++i];
    else
    {
      std::fprintf(stderr,
        "usage: %s [--dim 2|3|23] [--sizes 1e3,1e4,...] [--brute-max N] [--csv FILE] "
        "[--filter-only [--threads N] [--runs N]] [--order asis|sorted|shuffled] "
        "[--renumber auto|always|never] [--target FILE.vtu --source FILE.vtu] [--peer LIBSUPERMESH.so]\n",
        argv[0]);
      return 2;
    }
  }
  if (!TargetFile.empty() || !SourceFile.empty())
  {
    if (TargetFile.empty() || SourceFile.empty())
    {
      std::fprintf(stderr, "--target and --source go together\n");
      return 2;
    }
    dims = "2"; // one run on the files' pair (its dimension is the files')
    sizes = { 0 };
  }
  std::vector<Row> rows;
  for (char d : dims)
  {
    for (double n : sizes)
    {
      rows.push_back(Measure(d - '0', n, bruteMax, filterOnly));
      if (filterOnly)
      {
        PrintFilter(rows.back());
      }
      else
      {
        Print(rows.back());
      }
      std::fflush(stdout);
    }
  }
  if (!csv.empty())
  {
    std::ofstream out(csv);
    out << "dim,target_cells,source_cells,pairs,neighbours,seeding,search,assembly,"
           "solve,total,peak_beyond_inputs_mib,input_mib,brute,locator,"
           "filter_1_thread,filter_2_threads,resample,kernel_on_true_pairs,filter_input,filter_neighbours,"
           "filter_locator,filter_search,filter_assembly,filter_solve,filter_output\n";
    for (const Row& r : rows)
    {
      out << r.Dim << ',' << r.TargetCells << ',' << r.SourceCells << ',' << r.Pairs << ','
          << r.Neighbors << ',' << r.Seeding << ',' << r.Search << ',' << r.Assembly << ','
          << r.Solve << ',' << r.Total << ',' << r.PeakBeyondInputs
          << ',' << r.InputSize << ',' << r.Brute << ',' << r.Locator << ',' << r.Filter1 << ','
          << r.Filter2 << ',' << r.Resample << ',' << r.KernelOnPairs;
      for (int k = 0; k < 7; ++k)
      {
        out << ',' << r.FilterStages[0][k];
      }
      out << '\n';
    }
  }
  return 0;
}
