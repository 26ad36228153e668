// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ClipByPlane.h
 * @brief The reference clipper: a tetrahedron cut by one plane, kept as at
 *        most three tetrahedra (private to TetrahedronIntersector and its
 *        tests).
 *
 * TetrahedronIntersector clips a tetrahedron by the four face planes of the
 * other one. VertexGraph.h does it as one convex polyhedron; when that
 * cannot go on (capacity, or a face walk that does not close), the clip is
 * done again here, plane after plane, on tetrahedra: the part of a
 * tetrahedron on the inner side of a plane is one tetrahedron (one corner
 * inside) or a prism split into three (two or three inside). Slower, but
 * with no capacity limit and no face walk that could fail. The corners of the source tetrahedron take their exactly classified sides
 * (FaceSides.h), so the clip never disagrees with the classification.
 */
#ifndef MeshProjection_Kernel_ClipByPlane_h
#define MeshProjection_Kernel_ClipByPlane_h

#include "Mesh/Vec3.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace clipping
{
/// Six times the signed volume of (a, b, c, d).
inline double SixVolume(const double* a, const double* b, const double* c, const double* d)
{
  Vec u, v, w, n;
  Sub(b, a, u);
  Sub(c, a, v);
  Sub(d, a, w);
  Cross(v, w, n);
  return Dot(u, n);
}

/// A tetrahedron during clipping: each vertex knows the target planes it lies on.
struct ClipTet
{
  double X[4][3];
  unsigned OnPlane[4];
  int Original[4]; ///< corner of the source tetrahedron this vertex is, or -1
  double Volume;   ///< six times the volume, > 0 (orientation dropped)
};

/// Where the segment from p (inside, dp >= 0) to q (outside, dq < 0) crosses the plane.
inline void Crossing(const ClipTet& t, int p, int q, const double d[4], unsigned bit, double* x,
  unsigned& on, int& original)
{
  if (d[p] == 0.0)
  {
    std::copy(t.X[p], t.X[p] + 3, x);
    on = t.OnPlane[p] | bit;
    original = t.Original[p];
    return;
  }
  original = -1;
  const double u = d[p] / (d[p] - d[q]);
  for (int c = 0; c < 3; ++c)
  {
    x[c] = t.X[p][c] + u * (t.X[q][c] - t.X[p][c]);
  }
  on = (t.OnPlane[p] & t.OnPlane[q]) | bit;
}

/// A vertex under construction: position, planes it lies on, source corner.
struct Vertex
{
  double X[3];
  unsigned On;
  int Original;
};

inline void Emit(
  ClipTet* out, int& n, const Vertex& a, const Vertex& b, const Vertex& c, const Vertex& e)
{
  const double six = SixVolume(a.X, b.X, c.X, e.X);
  if (six == 0.0)
  {
    return; // collapsed by a vertex lying on the plane
  }
  ClipTet& t = out[n++];
  t.Volume = std::fabs(six);
  const Vertex* vs[4] = { &a, &b, &c, &e };
  for (int v = 0; v < 4; ++v)
  {
    std::copy(vs[v]->X, vs[v]->X + 3, t.X[v]);
    t.OnPlane[v] = vs[v]->On;
    t.Original[v] = vs[v]->Original;
  }
}

/**
 * Keeps the part of `t` where normal . (x - origin) >= 0, as at most three
 * tetrahedra appended to out. Vertices on the plane get `bit`. Corners of
 * the source tetrahedron use their exactly classified distances `exact`;
 * vertices already known to lie on the plane use 0.
 */
inline void ClipByPlane(const ClipTet& t, const double* normal, const double* origin, unsigned bit,
  const double exact[4], ClipTet* out, int& n)
{
  double d[4];
  int in[4];
  int outside[4];
  int nin = 0;
  int nout = 0;
  for (int v = 0; v < 4; ++v)
  {
    if (t.Original[v] >= 0)
    {
      d[v] = exact[t.Original[v]];
    }
    else if (t.OnPlane[v] & bit)
    {
      d[v] = 0.0;
    }
    else
    {
      Vec r;
      Sub(t.X[v], origin, r);
      d[v] = Dot(normal, r);
    }
    if (d[v] >= 0.0)
    {
      in[nin++] = v;
    }
    else
    {
      outside[nout++] = v;
    }
  }
  if (nout == 0)
  {
    ClipTet& c = out[n++];
    c = t;
    for (int v = 0; v < 4; ++v)
    {
      if (d[v] == 0.0)
      {
        c.OnPlane[v] |= bit;
      }
    }
    return;
  }
  if (nin == 0)
  {
    return;
  }
  auto corner = [&](int v) {
    Vertex x;
    std::copy(t.X[v], t.X[v] + 3, x.X);
    x.On = t.OnPlane[v] | (d[v] == 0.0 ? bit : 0u);
    x.Original = t.Original[v];
    return x;
  };
  auto cut = [&](int p, int q) {
    Vertex x;
    Crossing(t, p, q, d, bit, x.X, x.On, x.Original);
    return x;
  };
  if (nin == 1)
  {
    const int a = in[0];
    Emit(out, n, corner(a), cut(a, outside[0]), cut(a, outside[1]), cut(a, outside[2]));
    return;
  }
  // Two or three corners inside: a prism p0 p1 p2 / q0 q1 q2 between the
  // inside face (or edge) and the cut, split into three tetrahedra
  // (p0,p1,p2,q0), (p1,p2,q0,q1), (p2,q0,q1,q2).
  Vertex p[3];
  Vertex q[3];
  if (nin == 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      p[k] = corner(in[k]);
      q[k] = cut(in[k], outside[0]);
    }
  }
  else // two inside (a, b): the wedge (a, ac, ad) / (b, bc, bd)
  {
    p[0] = corner(in[0]);
    p[1] = cut(in[0], outside[0]);
    p[2] = cut(in[0], outside[1]);
    q[0] = corner(in[1]);
    q[1] = cut(in[1], outside[0]);
    q[2] = cut(in[1], outside[1]);
  }
  Emit(out, n, p[0], p[1], p[2], q[0]);
  Emit(out, n, p[1], p[2], q[0], q[1]);
  Emit(out, n, p[2], q[0], q[1], q[2]);
}
} // namespace clipping
} // namespace mp

#endif
