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
// --resample adds ParaView's Resample With Dataset to those alternating runs.
// --order asis|sorted|shuffled renumbers both meshes first, --renumber sets
// the filter's Renumbering, --target/--source read a pair of .vtu files
// instead (one run), and --peer LIB times libsupermesh's intersections on
// the same meshes (see Peer below).
// Timings are wall-clock seconds, the best of three runs for the kernel's
// stages and the filter's, one run for the others; ratios, not absolute
// seconds, carry the comparison.
#include "MeshProjectionBench.h"
#include "BenchPeer.h"

#include "Search/PairSearch.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/MortarOperator.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"

#include "vtkIdList.h"
#include "vtkMeshProjectionFilter.h"
#include "vtkNew.h"
#include "vtkResampleWithDataSet.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <algorithm>
#include <chrono>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

// The command line's settings the other files read (MeshProjectionBench.h).
namespace mpbench
{
std::string Order = "asis";
std::string TargetFile;
std::string SourceFile;
int FilterThreads = 1;
int FilterThreads2 = 0;
int FilterRuns = 1;
} // namespace mpbench

using namespace mpbench;

namespace
{
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
/// --peer: the loaded peer, if any.
Peer ThePeer;
bool HavePeer = false;

/// --renumber auto|always|never: the filter's Renumbering.
int Renumbering = vtkMeshProjectionFilter::AUTOMATIC_RENUMBERING;
/// --resample: --filter-only also times Resample With Dataset.
bool WithResample = false;

/// Seconds of one run of ParaView's Resample With Dataset
/// (vtkResampleWithDataSet, its probe: the source's point data at the
/// target's points) on the pair.
double TimeResample(vtkUnstructuredGrid* targetGrid, vtkUnstructuredGrid* sourceGrid)
{
  vtkNew<vtkResampleWithDataSet> resample;
  resample->SetInputData(targetGrid);
  resample->SetSourceData(sourceGrid);
  const auto t0 = Clock::now();
  resample->Update();
  return Since(t0);
}

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
    if (!HavePeer)
    {
      // Only the peer reads these copies: give them back, so that a pair near
      // the machine's memory (10^8 cells) fits.
      target = TestMesh();
      source = TestMesh();
      std::vector<double>().swap(u);
    }
    // The filter's runs and the peer's alternate, so that both meet the same
    // spells of a shared host's load (their ratio is the measure). The
    // filter's peak memory is its first run's, before any of the peer's
    // (after them, the heap measured about 10% more): only that run starts
    // from memory given back to the system; the later ones, like the peer's
    // and a filter run again in one session, find the heap as left.
    double firstPeak = 0;
    for (int run = 0; run < FilterRuns; ++run)
    {
      TimeFilter(targetGrid, sourceGrid, FilterThreads, 1, run == 0, 0, r.Filter1, r, &r.Pairs);
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
        const double seconds =
          ThePeer.Run(target, source, r.PeerMeasure, r.PeerCandidates, r.PeerPieces);
        r.Peer = run == 0 ? seconds : std::min(r.Peer, seconds);
      }
      if (WithResample)
      {
        const double seconds = TimeResample(targetGrid, sourceGrid);
        r.Resample = run == 0 ? seconds : std::min(r.Resample, seconds);
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
    mp::OperatorOptions
      single; // the field's right-hand side summed in the search, as the filter does
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
  r.Resample = TimeResample(targetGrid, sourceGrid);
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
    else if (a == "--resample")
      WithResample = true;
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
        "[--filter-only [--threads N] [--runs N] [--resample]] [--order asis|sorted|shuffled] "
        "[--renumber auto|always|never] [--target FILE.vtu --source FILE.vtu] [--peer "
        "LIBSUPERMESH.so]\n",
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
    WriteCsv(csv, rows);
  }
  return 0;
}
