// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Boxes.h
 * @brief Axis-aligned boxes, as the processes tell each other where their
 *        parts are: a process's Input seen from afar (Cover) for the
 *        gathering of Source, a process's points' bounds for finding the
 *        points it shares (not public, not wrapped).
 *
 * A box is closed: boxes that touch meet, a point on a face is inside. An
 * empty box has min > max on every axis and meets nothing.
 */
#ifndef MeshProjection_Parallel_Boxes_h
#define MeshProjection_Parallel_Boxes_h

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace mpvtk
{
using Box = std::array<double, 6>; // xmin, xmax, ymin, ymax, zmin, zmax

/// The box that holds nothing (any Grow or Unite replaces it).
inline Box EmptyBox()
{
  const double big = std::numeric_limits<double>::max();
  return { big, -big, big, -big, big, -big };
}

/// b := the box of b and the point x.
inline void Grow(Box& b, const double* x)
{
  for (int d = 0; d < 3; ++d)
  {
    b[2 * d] = std::min(b[2 * d], x[d]);
    b[2 * d + 1] = std::max(b[2 * d + 1], x[d]);
  }
}

/// a := the box of a and b.
inline void Unite(Box& a, const Box& b)
{
  for (int d = 0; d < 3; ++d)
  {
    a[2 * d] = std::min(a[2 * d], b[2 * d]);
    a[2 * d + 1] = std::max(a[2 * d + 1], b[2 * d + 1]);
  }
}

/// Whether boxes a and b share a point.
inline bool Meet(const Box& a, const Box& b)
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

/// Whether the point x is in the box b.
inline bool Inside(const Box& b, const double* x)
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
} // namespace mpvtk

#endif
