// SPDX-License-Identifier: BSD-3-Clause
// What the files of mesh-projection-bench share (see MeshProjectionBench.cxx
// for the program and its options): the clock, the command line's settings,
// one size's measurements (Row), the meshes (BenchMeshes.cxx) and the tables
// (BenchTables.cxx).
#ifndef MeshProjectionBench_h
#define MeshProjectionBench_h

#include "GeneratedMeshes.h"

#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <string>
#include <vector>

namespace mpbench
{
using mp::Index;
using mptest::TestMesh;
using Clock = std::chrono::steady_clock;

/// Seconds since `t`.
inline double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// --order: how the cells and points of both meshes are numbered.
extern std::string Order;
/// --target/--source: meshes read from files instead of generated.
extern std::string TargetFile;
extern std::string SourceFile;
/// --threads N[,M]: the threads of the filter in --filter-only runs (and
/// of the runs alternating with them; 0: none).
extern int FilterThreads;
extern int FilterThreads2;
/// --runs: --filter-only times the filter and the peer this many times
/// each and keeps the best of each (the peak memory: the first run's).
extern int FilterRuns;

/// One size's measurements: the kernel's stages, the comparisons, the
/// filter's stages (-1: not measured).
struct Row
{
  int Dim;
  Index TargetCells;
  Index SourceCells;
  double Neighbors, Seeding, Search, Assembly, Solve, Total;
  Index Pairs;
  double PeakBeyondInputs, InputSize;
  double Brute = -1, Locator = -1, Filter1 = -1, Filter2 = -1, Resample = -1;
  double Peer = -1;       ///< --peer: libsupermesh's intersections, seconds
  double PeerMeasure = 0; ///< --peer: the summed measure of its pieces
  Index PeerCandidates = 0, PeerPieces = 0;
  double FilterPeak = -1;    ///< --filter-only: the filter's peak memory beyond its inputs, MiB
  double VTKInputs = 0;      ///< --filter-only: the two vtkUnstructuredGrids, MiB
  double KernelOnPairs = -1; ///< intersection kernel alone on the true pairs
  Index Tests = 0;           ///< --filter-only: intersection tests
  Index Queries = 0;         ///< --filter-only: locator queries
  /// The VTK filter's own stages (vtkMeshProjectionFilter::Get*Time) on 1
  /// and 2 threads: input, neighbours, locator, search, assembly, solve, output.
  double FilterStages[2][7] = {};
  double CheckTime[2] = {};    ///< of the filter's input stage: the id and offset checks
  double RenumberTime[2] = {}; ///< of the filter's input stage: renumbering along space
  int Renumbered = 0;          ///< meshes the filter renumbered
};

/// A pair of non-matching meshes with about n target cells: generated
/// (MakeGeneratedPair), or read from --target and --source; renumbered as
/// --order says.
void MakePair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source);
/// A pair of non-matching jittered grids with about n target cells.
void MakeGeneratedPair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source);
/// `m` as a vtkUnstructuredGrid of triangles or tetrahedra, with `field`
/// (when given) as its point array "u".
vtkSmartPointer<vtkUnstructuredGrid> ToVTK(const TestMesh& m, const std::vector<double>* field);

/// The table of one size: the kernel's stages and the comparisons.
void Print(const Row& r);
/// --filter-only: the VTK filter on the calling thread, stage by stage.
void PrintFilter(const Row& r);
/// --csv: one line per size.
void WriteCsv(const std::string& file, const std::vector<Row>& rows);
} // namespace mpbench

#endif
