// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ClipBench2D.cxx
 * @brief mesh-projection-clip2d: the 2D clip and its moments alone, per
 *        intersecting pair, with warm caches.
 *
 * Not a test. It makes the 2D pair of jittered grids that
 * mesh-projection-bench makes (about --cells target cells), finds the
 * meeting pairs with the advancing front (in its order), prepares every
 * cell of both meshes once, and then runs TriangleIntersector::Intersect
 * and Moments over the pairs in blocks of --block pairs, each block
 * --repeat times in a row, so that all but its first pass find the cells in
 * cache. It prints the time per pair of those later passes (best of the
 * blocks' sums over --runs runs). Instructions, which the machine's load
 * does not change, come from callgrind restricted to the passes (every
 * pass does the same work; the program prints the divisor):
 *
 *   mesh-projection-clip2d [--cells N] [--block B] [--repeat R] [--runs K] [--seed S]
 *   valgrind --tool=callgrind --toggle-collect='*ClipBlock*' \
 *     mesh-projection-clip2d --cells 1e5 --repeat 2 --runs 1
 */
#include "GeneratedMeshes.h"

#include "Geometry/TriangleIntersector.h"
#include "Search/CandidateLocator.h"
#include "Search/PairSearch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace
{
using mp::Index;
using mp::TriangleIntersector;
using Clock = std::chrono::steady_clock;

/// The meeting pairs as the front visits them.
struct PairList
{
  std::vector<std::pair<Index, Index>> Pairs;
  void operator()(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s,
    const TriangleIntersector::Piece&)
  {
    this->Pairs.emplace_back(t.Id, s.Id);
  }
};

/// Every cell of `mesh` prepared (a degenerate one left with Id -1).
std::vector<TriangleIntersector::Cell> PrepareAll(const mptest::TestMesh& mesh)
{
  std::vector<TriangleIntersector::Cell> cells(static_cast<size_t>(mesh.NumberOfCells()));
  const mp::MeshView view = mesh.View(false);
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    if (!TriangleIntersector::Prepare(view, c, cells[c]))
    {
      cells[c].Id = -1;
    }
  }
  return cells;
}

/// What one pass over a block computes, kept so that none of it is dropped.
struct Sums
{
  double Area = 0.0;
  double Moment = 0.0;
  unsigned Faces = 0;
};

/// Intersect and Moments over pairs [begin, end).
__attribute__((noinline)) void ClipBlock(const std::vector<TriangleIntersector::Cell>& targets,
  const std::vector<TriangleIntersector::Cell>& sources, const std::pair<Index, Index>* begin,
  const std::pair<Index, Index>* end, Sums& sums)
{
  TriangleIntersector::Piece piece;
  for (const std::pair<Index, Index>* p = begin; p != end; ++p)
  {
    if (!TriangleIntersector::Intersect(targets[p->first], sources[p->second], piece))
    {
      continue;
    }
    double o[2];
    double M[3][3];
    sums.Area += TriangleIntersector::Moments(piece, o, M);
    sums.Moment += M[1][2];
    sums.Faces += piece.TouchedFaces ^ (piece.SourceFaces << 3);
  }
}

struct Options
{
  double Cells = 1e6;
  int Block = 4096;
  int Repeat = 8;
  int Runs = 3;
  unsigned Seed = 1;
};

Options Parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--cells")
    {
      o.Cells = std::atof(value);
    }
    else if (key == "--block")
    {
      o.Block = std::max(1, std::atoi(value));
    }
    else if (key == "--repeat")
    {
      o.Repeat = std::max(2, std::atoi(value));
    }
    else if (key == "--runs")
    {
      o.Runs = std::max(1, std::atoi(value));
    }
    else if (key == "--seed")
    {
      o.Seed = static_cast<unsigned>(std::atoi(value));
    }
    else
    {
      std::fprintf(
        stderr, "usage: %s [--cells N] [--block B] [--repeat R] [--runs K] [--seed S]\n", argv[0]);
      std::exit(2);
    }
  }
  return o;
}
} // namespace

int main(int argc, char** argv)
{
  const Options options = Parse(argc, argv);
  // The pair of mesh-projection-bench's 2D generated meshes.
  const int k = std::max(2, static_cast<int>(std::lround(std::sqrt(options.Cells / 2))));
  const mptest::TestMesh target = mptest::GridMesh(k, k, 0.25, options.Seed);
  const mptest::TestMesh source = mptest::GridMesh(k + 3, k - 1, 0.25, options.Seed + 1);
  PairList list;
  {
    mp::BoxGridLocator locator(source.View());
    mp::SearchStatistics stats;
    mp::AdvancingFrontSearch<TriangleIntersector>(
      target.View(), source.View(), locator, list, stats);
  }
  const std::vector<TriangleIntersector::Cell> targets = PrepareAll(target);
  const std::vector<TriangleIntersector::Cell> sources = PrepareAll(source);
  const auto* pairs = list.Pairs.data();
  const size_t n = list.Pairs.size();
  double best = 1e300;
  Sums sums;
  for (int run = 0; run < options.Runs; ++run)
  {
    double warm = 0.0;
    for (size_t b = 0; b < n; b += static_cast<size_t>(options.Block))
    {
      const size_t e = std::min(n, b + static_cast<size_t>(options.Block));
      ClipBlock(targets, sources, pairs + b, pairs + e, sums); // brings the block's cells in
      const Clock::time_point start = Clock::now();
      for (int r = 1; r < options.Repeat; ++r)
      {
        ClipBlock(targets, sources, pairs + b, pairs + e, sums);
      }
      warm += std::chrono::duration<double>(Clock::now() - start).count();
    }
    best = std::min(best, warm);
  }
  std::printf("target cells %lld, source cells %lld, meeting pairs %zu\n",
    static_cast<long long>(target.NumberOfCells()), static_cast<long long>(source.NumberOfCells()),
    n);
  std::printf("clip + moments, warm: %.1f ns per pair (best of %d runs)\n",
    1e9 * best / (static_cast<double>(n) * (options.Repeat - 1)), options.Runs);
  std::printf("callgrind's instructions per pair: Ir of ClipBlock / %.0f\n",
    static_cast<double>(n) * options.Repeat * options.Runs);
  std::printf("checksum: area %.15g, moment %.6g, faces %u\n",
    sums.Area / (options.Runs * options.Repeat), sums.Moment, sums.Faces);
  return 0;
}
