// SPDX-License-Identifier: BSD-3-Clause
// Coverage-guided fuzzing (libFuzzer, with AddressSanitizer and
// UndefinedBehaviorSanitizer) of the kernel's geometry: the triangle and
// tetrahedron intersectors and the advancing front against the brute force.
//
// The first byte chooses the case; the rest are coordinates. Coordinates
// come either as raw doubles (NaN, infinities, huge and tiny values
// included) or as small integers on a lattice, which makes shared vertices,
// vertices on edges and faces, collinear edges and coplanar faces common.
// Any broken invariant aborts, which libFuzzer reports with the input.
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Mesh/CellNeighbors.h"
#include "Search/CandidateLocator.h"
#include "Search/PairSearch.h"
#include "Search/SearchStatistics.h"
#include "Transfer/MortarAssembler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <vector>

namespace
{
[[noreturn]] void Fail(const char* what)
{
  std::fprintf(stderr, "invariant broken: %s\n", what);
  std::abort();
}

struct Reader
{
  const uint8_t* Data;
  size_t Size;
  bool Lattice;
  double Next()
  {
    if (this->Lattice)
    {
      const int v = this->Size ? static_cast<int8_t>(*this->Data) : 0;
      if (this->Size)
      {
        ++this->Data;
        --this->Size;
      }
      return (v % 16) / 4.0; // quarter steps in [-3.75, 3.75]
    }
    double v = 0.0;
    const size_t n = std::min(this->Size, sizeof(double));
    std::memcpy(&v, this->Data, n);
    this->Data += n;
    this->Size -= n;
    return v;
  }
};

template <class Intersector>
struct Pair
{
  std::vector<double> Points;
  std::vector<mp::Index> Cells;
  mp::MeshView View;
  typename Intersector::Cell A;
  typename Intersector::Cell B;
  bool Ok = false;

  explicit Pair(Reader& in)
  {
    constexpr int n = Intersector::Corners;
    for (int k = 0; k < 2 * n; ++k)
    {
      const double x = in.Next();
      const double y = in.Next();
      const double z = Intersector::Dimension == 3 ? in.Next() : 0.0;
      this->Points.insert(this->Points.end(), { x, y, z });
      this->Cells.push_back(k);
    }
    this->View.CellDimension = Intersector::Dimension;
    this->View.SpaceDimension = Intersector::Dimension;
    this->View.Points = this->Points.data();
    this->View.NumberOfPoints = 2 * n;
    this->View.Connectivity = this->Cells.data();
    this->View.NumberOfCells = 2;
    this->Ok =
      Intersector::Prepare(this->View, 0, this->A) && Intersector::Prepare(this->View, 1, this->B);
  }
};

bool Finite(const double* x, int n)
{
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(x[i]))
      return false;
  return true;
}

/// Coordinates 0 or of magnitude in [1e-100, 1e100]: the range in which the
/// exact predicates cannot underflow or overflow (the filter rejects others).
bool InRange(const std::vector<double>& x)
{
  for (double v : x)
  {
    const double a = std::fabs(v);
    if (a != 0.0 && (a < 1e-100 || a > 1e100))
      return false;
  }
  return true;
}

/// Checks a pair in both orders: symmetric measure, bounded by both cells.
template <class Intersector>
void CheckPair(Reader& in)
{
  Pair<Intersector> p(in);
  if (!p.Ok || !Finite(p.Points.data(), static_cast<int>(p.Points.size())) || !InRange(p.Points))
  {
    return;
  }
  // The decisions are exact for any cells, but constructed points (edge and
  // face crossings) carry rounding relative to the coordinates: measures are
  // only checked on cells that are not thinner than 1e-9 of their size, and
  // with a slack for that rounding. A crossing is off by about u |x| (u the
  // rounding unit, |x| the largest coordinate), which moves the piece's
  // boundary by that much at up to 12 vertices: its measure by up to about
  // 12 u |x| size^(d-1) (the slack: 64 u |x| size^(d-1)). Far from the
  // origin (coordinates 10^10 times the cells' size, as the fuzzer makes)
  // that exceeds 1e-9 of a thin cell's measure.
  double largest = 0;
  for (double v : p.Points)
    largest = std::max(largest, std::fabs(v));
  double sizes = 0;
  double condition = 0; // the larger size^d / measure of the two cells
  for (const auto* c : { &p.A, &p.B })
  {
    double size = 0;
    for (int i = 0; i < Intersector::Corners; ++i)
      for (int j = 0; j < i; ++j)
      {
        double d2 = 0;
        for (int k = 0; k < Intersector::Dimension; ++k)
          d2 += (c->X[i][k] - c->X[j][k]) * (c->X[i][k] - c->X[j][k]);
        size = std::max(size, std::sqrt(d2));
      }
    if (!(c->Measure > 1e-9 * std::pow(size, Intersector::Dimension)))
    {
      return;
    }
    sizes = std::max(sizes, size);
    condition = std::max(condition, std::pow(size, Intersector::Dimension) / c->Measure);
  }
  const double slack =
    64 * mp::RoundingUnit * largest * std::pow(sizes, Intersector::Dimension - 1);
  typename Intersector::Piece ab;
  typename Intersector::Piece ba;
  const bool metAB = Intersector::Intersect(p.A, p.B, ab);
  const bool metBA = Intersector::Intersect(p.B, p.A, ba);
  const double mAB = metAB ? Intersector::Measure(ab) : 0.0;
  const double mBA = metBA ? Intersector::Measure(ba) : 0.0;
  const double smaller = std::min(p.A.Measure, p.B.Measure);
  if (!(mAB >= 0.0) || !(mBA >= 0.0))
  {
    Fail("negative or NaN measure");
  }
  if (mAB > smaller * (1 + 1e-9) + slack || mBA > smaller * (1 + 1e-9) + slack)
  {
    Fail("intersection larger than a cell");
  }
  // Rounding in the intersection points: relative to the cells' scale.
  const double tolerance = 1e-9 * std::max(p.A.Measure, p.B.Measure) + 2 * slack;
  if (std::fabs(mAB - mBA) > tolerance)
  {
    Fail("measure not symmetric");
  }
  if (metAB)
  {
    double mts[Intersector::Corners][Intersector::Corners] = {};
    double mtt[Intersector::Corners][Intersector::Corners] = {};
    using P1 = mp::P1Space<Intersector::Dimension>;
    const double m = mp::AddPieceBlocks<Intersector, P1, P1>(ab, p.A, p.B, mts, mtt);
    double sum = 0;
    for (auto& row : mts)
      for (double v : row)
        sum += v;
    // Partition of unity: the mortar entries add up to the piece's measure.
    // The basis functions are barycentric coordinates, whose rounding grows
    // as a cell thins: about u size^d / measure of each value (the cells let
    // through above, down to 1e-9 thin, reach 1e-8), hence that slack.
    const double conditioned = 64 * mp::RoundingUnit * condition * m;
    if (std::fabs(sum - m) > 1e-9 * std::max(m, smaller) + conditioned + 1e-300)
    {
      Fail("mortar entries do not add up to the measure");
    }
  }
}

/// Records every pair a search visits, with the piece's measure.
template <class Intersector>
struct Recorder
{
  std::vector<std::tuple<mp::Index, mp::Index, double>> Pairs;
  void operator()(const typename Intersector::Cell& t, const typename Intersector::Cell& s,
    const typename Intersector::Piece& p)
  {
    this->Pairs.emplace_back(t.Id, s.Id, Intersector::Measure(p));
  }
};

/// The front on the two meshes must find the brute force's pairs exactly.
template <class Intersector>
void CompareSearches(std::vector<double> (&points)[2], std::vector<mp::Index> (&cells)[2])
{
  constexpr int d = Intersector::Dimension;
  mp::MeshView views[2];
  std::vector<mp::NeighborId> neighbors[2];
  for (int m = 0; m < 2; ++m)
  {
    if (!Finite(points[m].data(), static_cast<int>(points[m].size())))
      return;
    views[m].CellDimension = d;
    views[m].SpaceDimension = d;
    views[m].Points = points[m].data();
    views[m].NumberOfPoints = static_cast<mp::Index>(points[m].size() / 3);
    views[m].Connectivity = cells[m].data();
    views[m].NumberOfCells = static_cast<mp::Index>(cells[m].size() / (d + 1));
    mp::BuildFaceNeighbors(views[m], neighbors[m]);
    views[m].Neighbors = neighbors[m].data();
  }
  Recorder<Intersector> front;
  Recorder<Intersector> brute;
  mp::SearchStatistics stats;
  mp::BoxGridLocator locator(views[1]);
  mp::AdvancingFrontSearch<Intersector>(views[0], views[1], locator, front, stats);
  mp::BruteForceSearch<Intersector>(views[0], views[1], brute, stats);
  std::sort(front.Pairs.begin(), front.Pairs.end());
  std::sort(brute.Pairs.begin(), brute.Pairs.end());
  if (front.Pairs != brute.Pairs)
  {
    Fail("advancing front and brute force differ");
  }
}

/// Small jittered grids of the unit square from the input (triangles).
void CheckSearch(Reader& in)
{
  const int nx = 1 + (in.Size ? in.Data[0] % 4 : 0);
  const int ny = 1 + (in.Size > 1 ? in.Data[1] % 4 : 0);
  std::vector<double> points[2];
  std::vector<mp::Index> cells[2];
  for (int m = 0; m < 2; ++m)
  {
    const int sx = nx + m;
    const int sy = ny + 2 * m;
    for (int j = 0; j <= sy; ++j)
      for (int i = 0; i <= sx; ++i)
      {
        const double jx = (i > 0 && i < sx) ? 0.2 * std::tanh(in.Next()) : 0.0;
        const double jy = (j > 0 && j < sy) ? 0.2 * std::tanh(in.Next()) : 0.0;
        points[m].insert(points[m].end(), { (i + jx) / sx, (j + jy) / sy, 0.0 });
      }
    for (int j = 0; j < sy; ++j)
      for (int i = 0; i < sx; ++i)
      {
        const mp::Index a = j * (sx + 1) + i;
        const mp::Index b = a + 1;
        const mp::Index c = a + sx + 2;
        const mp::Index d = a + sx + 1;
        if ((i + j + m) % 2)
          cells[m].insert(cells[m].end(), { a, b, c, a, c, d });
        else
          cells[m].insert(cells[m].end(), { a, b, d, b, c, d });
      }
  }
  CompareSearches<mp::TriangleIntersector>(points, cells);
}

/// Small jittered lattices of the unit cube from the input, six Kuhn
/// tetrahedra per box (the jitter may fold a mesh: such inputs are skipped,
/// a source that overlaps itself being outside what the front promises).
void CheckSearch3D(Reader& in)
{
  // Few cells (target 6-12, source 24-48): the brute force under the
  // sanitizers stays cheap, so the fuzzer tries many inputs.
  const int nx = 1 + (in.Size > 3 ? in.Data[3] % 2 : 0);
  const int ny = 1 + (in.Size > 4 ? in.Data[4] % 2 : 0);
  std::vector<double> points[2];
  std::vector<mp::Index> cells[2];
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (int m = 0; m < 2; ++m)
  {
    const int n[3] = { m == 0 ? nx : 2, m == 0 ? 1 : ny, m == 0 ? 1 : 2 };
    auto id = [&](int i, int j, int k) { return mp::Index((k * (n[1] + 1) + j) * (n[0] + 1) + i); };
    for (int k = 0; k <= n[2]; ++k)
      for (int j = 0; j <= n[1]; ++j)
        for (int i = 0; i <= n[0]; ++i)
        {
          const int ijk[3] = { i, j, k };
          bool interior = true;
          for (int a = 0; a < 3; ++a)
            interior = interior && ijk[a] > 0 && ijk[a] < n[a];
          for (int a = 0; a < 3; ++a)
          {
            const double jitter = interior ? 0.15 * std::tanh(in.Next()) : 0.0;
            points[m].push_back((ijk[a] + jitter) / n[a]);
          }
        }
    double volume = 0.0;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          for (const auto& p : perms)
          {
            int c[3] = { i, j, k };
            mp::Index corner[4];
            corner[0] = id(c[0], c[1], c[2]);
            for (int step = 0; step < 3; ++step)
            {
              ++c[p[step]];
              corner[step + 1] = id(c[0], c[1], c[2]);
            }
            cells[m].insert(cells[m].end(), corner, corner + 4);
            const double* x0 = &points[m][3 * corner[0]];
            double e[3][3];
            for (int r = 0; r < 3; ++r)
              for (int a = 0; a < 3; ++a)
                e[r][a] = points[m][3 * corner[r + 1] + a] - x0[a];
            volume += std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                        e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                        e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
              6.0;
          }
    if (!(std::fabs(volume - 1.0) < 1e-9))
    {
      return; // folded (or non-finite): the cells overlap
    }
  }
  CompareSearches<mp::TetrahedronIntersector>(points, cells);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size < 2)
  {
    return 0;
  }
  Reader in{ data + 1, size - 1, (data[0] & 1) != 0 };
  switch ((data[0] >> 1) % 3)
  {
    case 0:
      CheckPair<mp::TriangleIntersector>(in);
      break;
    case 1:
      CheckPair<mp::TetrahedronIntersector>(in);
      break;
    default:
      // The front against the brute force, in 2D or (one input in four) 3D.
      if (in.Size > 2 && in.Data[2] % 4 == 1)
        CheckSearch3D(in);
      else
        CheckSearch(in);
      break;
  }
  return 0;
}
