// SPDX-License-Identifier: BSD-3-Clause
// mesh-projection-bench --peer: libsupermesh's intersections, timed on the
// same meshes as the filter.
#ifndef BenchPeer_h
#define BenchPeer_h

#include "MeshProjectionBench.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace mpbench
{
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
  using SetInput = void (*)(
    long*, int*, long*, int*, long*, int*, long*, int*, double*, long*, double*, long*);
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
    this->TreeGet = reinterpret_cast<GetOutput>(
      dlsym(handle, "libsupermesh_tree_intersection_finder_get_output"));
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
    auto elements = [](const TestMesh& m) {
      return std::vector<long>(m.Cells.begin(), m.Cells.end());
    };
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
    this->TreeSetInput(
      &na, &da, &ca, &la, &nb, &db, &cb, &lb, xa.data(), ea.data(), xb.data(), eb.data());
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
} // namespace mpbench

#endif
