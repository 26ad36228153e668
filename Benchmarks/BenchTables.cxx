// SPDX-License-Identifier: BSD-3-Clause
// mesh-projection-bench's output: the table of each size (the kernel's
// stages and the comparisons, or with --filter-only the filter's stages),
// the peer's line, and the CSV file.
#include "MeshProjectionBench.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

namespace mpbench
{
namespace
{
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

/// --filter-only --resample: Resample With Dataset's best time, against the filter's.
void PrintResample(const Row& r)
{
  if (r.Resample < 0)
  {
    return;
  }
  std::printf("  %-34s %10.4f\n", "Resample With Dataset", r.Resample);
  std::printf("  %-34s %10.2fx\n", "VTK filter / Resample With Dataset", r.Filter1 / r.Resample);
}
} // namespace

/// --filter-only: the VTK filter on the calling thread, stage by stage.
void PrintFilter(const Row& r)
{
  std::printf("\n%dD  target %lld cells, source %lld cells, %lld intersecting pairs\n", r.Dim,
    static_cast<long long>(r.TargetCells), static_cast<long long>(r.SourceCells),
    static_cast<long long>(r.Pairs));
  const std::string runs = FilterRuns > 1
    ? "VTK filter (best of " + std::to_string(FilterRuns) + ")"
    : "VTK filter (one run)";
  std::printf("  %-34s %10.4f  (%.2f tests per pair, %lld locator queries)\n", runs.c_str(),
    r.Filter1, double(r.Tests) / std::max<Index>(1, r.Pairs), static_cast<long long>(r.Queries));
  for (int k = 0; k < 7; ++k)
  {
    std::printf("    %-32s %10.4f\n", FilterStageNames[k], r.FilterStages[0][k]);
    if (k == 0)
    {
      std::printf("      %-30s %10.4f\n", "of which id/offset checks", r.CheckTime[0]);
      std::printf("      %-30s %10.4f  (%d of 2 meshes)\n", "of which renumbering",
        r.RenumberTime[0], r.Renumbered);
    }
  }
  std::printf("  %-34s %10.1f MiB (inputs %.1f MiB, ratio %.2f)\n",
    "filter's peak memory beyond inputs", r.FilterPeak, r.VTKInputs, r.FilterPeak / r.VTKInputs);
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
  PrintResample(r);
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
    { "assembly", r.Assembly }, { "solve", r.Solve }, { "total", r.Total } };
  for (const auto& s : stages)
  {
    std::printf("  %-34s %10.4f %12.3f\n", s.first, s.second, 1e6 * s.second / cells);
  }
  std::printf("  pairs per second (search)          %10.3g\n", r.Pairs / r.Search);
  std::printf(
    "  intersection kernel on true pairs  %10.4f  (search overhead %.0f%% of the search)\n",
    r.KernelOnPairs, 100.0 * (r.Search - r.KernelOnPairs) / r.Search);
  std::printf("  peak memory beyond inputs          %10.1f MiB (inputs %.1f MiB, ratio %.2f)\n",
    r.PeakBeyondInputs, r.InputSize, r.PeakBeyondInputs / r.InputSize);
  std::printf("  %-34s %10s %12s\n", "comparison", "seconds", "ratio");
  if (r.Brute >= 0)
  {
    std::printf("  %-34s %10.4f %11.1fx\n", "brute force / advancing front", r.Brute,
      r.Brute / (r.Search + r.Assembly));
  }
  std::printf(
    "  %-34s %10.4f %11.2fx\n", "locator search / front search", r.Locator, r.Locator / r.Search);
  std::printf("  %-34s %10.4f\n", "VTK filter, 1 thread", r.Filter1);
  std::printf("  %-34s %10.4f %11.2fx\n", "VTK filter, 2 threads (speed-up)", r.Filter2,
    r.Filter1 / r.Filter2);
  std::printf("    %-32s %10s %10s\n", "VTK filter stages", "1 thread", "2 threads");
  for (int k = 0; k < 7; ++k)
  {
    std::printf(
      "    %-32s %10.4f %10.4f\n", FilterStageNames[k], r.FilterStages[0][k], r.FilterStages[1][k]);
    if (k == 0)
    {
      std::printf(
        "      %-30s %10.4f %10.4f\n", "of which id/offset checks", r.CheckTime[0], r.CheckTime[1]);
      std::printf("      %-30s %10.4f %10.4f  (%d of 2 meshes)\n", "of which renumbering",
        r.RenumberTime[0], r.RenumberTime[1], r.Renumbered);
    }
  }
  std::printf("  %-34s %10.4f %11.2fx\n", "Resample With Dataset / filter", r.Resample,
    r.Resample / r.Filter1);
  PrintPeer(r, r.Filter1);
}

void WriteCsv(const std::string& csv, const std::vector<Row>& rows)
{
  std::ofstream out(csv);
  out << "dim,target_cells,source_cells,pairs,neighbours,seeding,search,assembly,"
         "solve,total,peak_beyond_inputs_mib,input_mib,brute,locator,"
         "filter_1_thread,filter_2_threads,resample,kernel_on_true_pairs,filter_input,filter_"
         "neighbours,"
         "filter_locator,filter_search,filter_assembly,filter_solve,filter_output\n";
  for (const Row& r : rows)
  {
    out << r.Dim << ',' << r.TargetCells << ',' << r.SourceCells << ',' << r.Pairs << ','
        << r.Neighbors << ',' << r.Seeding << ',' << r.Search << ',' << r.Assembly << ',' << r.Solve
        << ',' << r.Total << ',' << r.PeakBeyondInputs << ',' << r.InputSize << ',' << r.Brute
        << ',' << r.Locator << ',' << r.Filter1 << ',' << r.Filter2 << ',' << r.Resample << ','
        << r.KernelOnPairs;
    for (int k = 0; k < 7; ++k)
    {
      out << ',' << r.FilterStages[0][k];
    }
    out << '\n';
  }
}
} // namespace mpbench
