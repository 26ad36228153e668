// SPDX-License-Identifier: BSD-3-Clause
// mesh-projection-clip3d: the tetrahedron clip alone
// (TetrahedronIntersector::Intersect), per intersecting pair, on a fixed
// pair of generated meshes; for measuring the clip's instructions and time
// before and after a change to it. Not a test: it prints one table.
//
//   mesh-projection-clip3d [--cells 1e5] [--seed 1] [--runs 5]
//
// The pair is mesh-projection-bench's 3D one of about --cells target cells
// (jittered cube grids of different resolutions, MakeGeneratedPair). The
// advancing front finds the pairs that meet, in its order; every cell is
// prepared once, then ClipPairs intersects those pairs, --runs times (the
// best time is printed). Its instructions, per pair, come from callgrind
// restricted to that function:
//
//   valgrind --tool=callgrind --toggle-collect='*ClipPairs*' \
//       build/bin/mesh-projection-clip3d --runs 1
//
// (callgrind_annotate's total divided by the pairs printed). The volume sum,
// the checksum of what feeds the front (touched faces, their seeds, the
// source faces) and a hash of the moments' bits let a change be checked
// against the numbers before it.
#include "GeneratedMeshes.h"

#include "Geometry/TetrahedronIntersector.h"
#include "Search/CandidateLocator.h"
#include "Search/PairSearch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace
{
using mp::Index;
using Tet = mp::TetrahedronIntersector;
using Clock = std::chrono::steady_clock;

/// The (target, source) pairs whose intersection has positive volume, in
/// the order the front meets them.
struct MeetingPairs
{
  std::vector<std::pair<Index, Index>> Pairs;
  void operator()(const Tet::Cell& t, const Tet::Cell& s, const Tet::Piece& piece)
  {
    if (Tet::Measure(piece) > 0.0)
    {
      this->Pairs.emplace_back(t.Id, s.Id);
    }
  }
};

/// Every cell of a mesh prepared (a cell of zero volume keeps Id -1).
std::vector<Tet::Cell> PrepareAll(const mptest::TestMesh& mesh)
{
  std::vector<Tet::Cell> cells(static_cast<size_t>(mesh.NumberOfCells()));
  for (Index c = 0; c < mesh.NumberOfCells(); ++c)
  {
    if (!Tet::Prepare(mesh.View(), c, cells[c]))
    {
      cells[c].Id = -1;
    }
  }
  return cells;
}

/// What one pass over the pairs gives: the volumes summed, the pairs that
/// met, and a checksum of the faces each piece gives the front.
struct Pass
{
  double Volume = 0.0;
  Index Met = 0;
  unsigned long long Faces = 0;
};

/// The clip of every pair (the function callgrind is restricted to).
__attribute__((noinline)) Pass ClipPairs(const std::vector<Tet::Cell>& target,
  const std::vector<Tet::Cell>& source, const std::vector<std::pair<Index, Index>>& pairs)
{
  Pass pass;
  Tet::Piece piece;
  for (const auto& pair : pairs)
  {
    const bool met = Tet::Intersect(target[pair.first], source[pair.second], piece);
    pass.Met += met ? 1 : 0;
    pass.Volume += Tet::Measure(piece);
    unsigned long long faces = piece.TouchedFaces | (piece.SourceFaces << 4);
    for (int k = 0; k < 4; ++k)
    {
      const bool touched = (piece.TouchedFaces >> k) & 1u;
      faces = faces * 7 + static_cast<unsigned>(touched ? piece.SeedFace[k] + 2 : 0);
    }
    pass.Faces = pass.Faces * 1000003ull + faces;
  }
  return pass;
}
/// A hash of the bits of every piece's moments (outside ClipPairs, so
/// that its instructions are the clip's): equal before and after a change
/// that keeps the moments bit for bit.
unsigned long long MomentsHash(const std::vector<Tet::Cell>& target,
  const std::vector<Tet::Cell>& source, const std::vector<std::pair<Index, Index>>& pairs)
{
  unsigned long long hash = 1469598103934665603ull;
  Tet::Piece piece;
  for (const auto& pair : pairs)
  {
    Tet::Intersect(target[pair.first], source[pair.second], piece);
    double origin[3];
    double M[4][4] = {};
    if (Tet::Moments(piece, origin, M) > 0.0)
    {
      for (const double x : { M[0][0], M[0][1], M[0][2], M[0][3], M[1][1], M[1][2], M[1][3],
             M[2][2], M[2][3], M[3][3], origin[0], origin[1], origin[2] })
      {
        unsigned long long bits;
        std::memcpy(&bits, &x, sizeof bits);
        hash = (hash ^ bits) * 1099511628211ull;
      }
    }
  }
  return hash;
}
} // namespace

int main(int argc, char** argv)
{
  double cells = 1e5;
  unsigned seed = 1;
  int runs = 5;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--cells" && i + 1 < argc)
      cells = std::atof(argv[++i]);
    else if (a == "--seed" && i + 1 < argc)
      seed = static_cast<unsigned>(std::atoi(argv[++i]));
    else if (a == "--runs" && i + 1 < argc)
      runs = std::max(1, std::atoi(argv[++i]));
    else
    {
      std::fprintf(stderr, "usage: %s [--cells 1e5] [--seed 1] [--runs 5]\n", argv[0]);
      return 1;
    }
  }
  // mesh-projection-bench's 3D pair (MakeGeneratedPair).
  const int k = std::max(2, static_cast<int>(std::lround(std::cbrt(cells / 6))));
  const mptest::TestMesh target = mptest::CubeMesh(k, k, k, 0.15, seed);
  const mptest::TestMesh source = mptest::CubeMesh(k + 1, k, k - 1, 0.15, seed + 1);
  mp::BoxGridLocator locator(source.View());
  MeetingPairs found;
  mp::SearchStatistics stats;
  mp::AdvancingFrontSearch<Tet>(target.View(), source.View(), locator, found, stats);
  const std::vector<Tet::Cell> t = PrepareAll(target);
  const std::vector<Tet::Cell> s = PrepareAll(source);

  double best = 1e300;
  Pass pass;
  for (int r = 0; r < runs; ++r)
  {
    const auto t0 = Clock::now();
    pass = ClipPairs(t, s, found.Pairs);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  const double n = static_cast<double>(found.Pairs.size());
  std::printf("target cells %lld, source cells %lld, pairs %lld (met %lld)\n",
    static_cast<long long>(target.NumberOfCells()), static_cast<long long>(source.NumberOfCells()),
    static_cast<long long>(found.Pairs.size()), static_cast<long long>(pass.Met));
  std::printf("clip: %.1f ns per pair (best of %d runs)\n", 1e9 * best / n, runs);
  std::printf("volume sum %.17g, faces checksum %016llx, moments hash %016llx\n", pass.Volume,
    pass.Faces, MomentsHash(t, s, found.Pairs));
  return 0;
}
