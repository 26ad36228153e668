// SPDX-License-Identifier: BSD-3-Clause
// The plane frames of planar meshes (2D meshes anywhere in 3D): a general
// plane is fitted and mapped there and back, a point off the plane is
// refused, the same plane in any number of tasks, axis planes pick
// coordinates.
#include "Mesh/PlaneFrame.h"
#include "GeneratedMeshes.h"
#include "Threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using mp::Index;
using mptest::TestMesh;

namespace
{
/// The points of `m` moved by a fixed rotation (about z by 0.7, then about
/// x by 1.1, then about y by 0.4) and the translation (0.3, -2, 5).
void RotateIntoAGeneralPlane(TestMesh& m)
{
  mptest::Move3D(m, 0.7, 1.1, 1.0, 0.3, -2.0, 5.0);
  const double c = std::cos(0.4);
  const double s = std::sin(0.4);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    double* x = &m.Points[3 * p];
    const double a = c * x[0] + s * x[2];
    const double b = -s * x[0] + c * x[2];
    x[0] = a;
    x[2] = b;
  }
}

/// A planar triangle mesh seen in 3D.
mp::MeshView Surface(const TestMesh& m)
{
  mp::MeshView v = m.View(false);
  v.CellDimension = 2;
  v.SpaceDimension = 3;
  return v;
}

/// ToPlane then ToSpace gives every point back; the frame is an isometry
/// (the cells keep their areas).
void ExpectRoundTrip(
  const mp::PlaneFrame& frame, const TestMesh& m, double tolerance, const std::string& what)
{
  std::vector<double> uv;
  frame.ToPlane(Surface(m), uv);
  ASSERT_EQ(uv.size(), m.Points.size()) << what;
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    EXPECT_EQ(uv[3 * p + 2], 0.0) << what;
    double x[3];
    frame.ToSpace(&uv[3 * p], x);
    for (int d = 0; d < 3; ++d)
    {
      ASSERT_NEAR(x[d], m.Points[3 * p + d], tolerance) << what << " point " << p;
    }
    EXPECT_NEAR(frame.Distance(&m.Points[3 * p]), 0.0, tolerance) << what << " point " << p;
  }
  TestMesh flat = m;
  flat.Points = uv;
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    const double* a = &m.Points[3 * m.Cells[3 * c]];
    const double* b = &m.Points[3 * m.Cells[3 * c + 1]];
    const double* e = &m.Points[3 * m.Cells[3 * c + 2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { e[0] - a[0], e[1] - a[1], e[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    ASSERT_NEAR(flat.CellArea(c), area, 1e-12) << what << " cell " << c;
  }
}
} // namespace

// Plane frames: a general plane is fitted and mapped there and back; a
// point off the plane is refused; axis planes pick coordinates.
TEST(PlaneFrame, GeneralPlaneRoundTrip)
{
  TestMesh m = mptest::GridMesh(6, 5, 0.25, 131, -1.0, 0.5, 2.0, 2.5);
  RotateIntoAGeneralPlane(m);
  mp::PlaneFrame frame;
  double deviation = -1;
  double size = -1;
  ASSERT_TRUE(frame.Fit(Surface(m), deviation, size));
  EXPECT_LE(deviation, 1e-9 * size);
  EXPECT_GT(size, 1.0);
  EXPECT_FALSE(frame.IsAxisAligned());
  EXPECT_FALSE(frame.IsIdentity());
  const double* n = frame.GetNormal();
  EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-15);
  ExpectRoundTrip(frame, m, 1e-12, "general plane");
  // A parallel plane is parallel; the frame of another mesh of the same
  // plane is too.
  TestMesh other = mptest::GridMesh(4, 7, 0.2, 132, 0.0, 0.0, 1.0, 1.0);
  RotateIntoAGeneralPlane(other);
  mp::PlaneFrame otherFrame;
  ASSERT_TRUE(otherFrame.Fit(Surface(other), deviation, size));
  EXPECT_TRUE(frame.IsParallel(otherFrame));
  EXPECT_NEAR(std::fabs(otherFrame.Offset()), std::fabs(frame.Offset()), 1e-12);
}

TEST(PlaneFrame, PointOffThePlaneIsRejected)
{
  TestMesh m = mptest::GridMesh(6, 5, 0.25, 133);
  RotateIntoAGeneralPlane(m);
  // Lift an interior point (the grid's point (3, 2)) off the plane.
  Index lifted = -1;
  double best = 1e300;
  const TestMesh flat = mptest::GridMesh(6, 5, 0.25, 133);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    const double dx = flat.Points[3 * p] - 0.5;
    const double dy = flat.Points[3 * p + 1] - 0.4;
    if (dx * dx + dy * dy < best)
    {
      best = dx * dx + dy * dy;
      lifted = p;
    }
  }
  ASSERT_GE(lifted, 0);
  mp::PlaneFrame frame;
  double deviation = 0;
  double size = 0;
  ASSERT_TRUE(frame.Fit(Surface(m), deviation, size));
  const double* n = frame.GetNormal();
  const double normal[3] = { n[0], n[1], n[2] };
  for (int d = 0; d < 3; ++d)
  {
    m.Points[3 * lifted + d] += 1e-3 * normal[d];
  }
  EXPECT_FALSE(frame.Fit(Surface(m), deviation, size));
  EXPECT_GT(deviation, 1e-9 * size);
  EXPECT_LT(deviation, 2e-3);
}

TEST(PlaneFrame, TheSamePlaneInAnyNumberOfTasks)
{
  // A tilted plane of 2 x 230^2 triangles (over 300,000 corners: blocks
  // of the corners' box and sum in several tasks): 1, 2 and 3 tasks give
  // the same frame bit for bit, its origin the corners' mean.
  TestMesh m = mptest::GridMesh(230, 230, 0.25, 71);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    double* x = &m.Points[3 * p];
    x[2] = 0.3 * x[0] - 0.2 * x[1] + 5.0;
  }
  const mp::MeshView view = Surface(m);
  ASSERT_GT(view.NumberOfCells * 3, Index(8) << 15);
  double mean[3] = { 0, 0, 0 };
  for (Index i = 0; i < 3 * view.NumberOfCells; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      mean[d] += view.Point(view.Corner(i))[d];
    }
  }
  mp::PlaneFrame serial;
  double deviation = -1;
  double size = -1;
  ASSERT_TRUE(serial.Fit(view, deviation, size));
  EXPECT_FALSE(serial.IsAxisAligned());
  const double zero[3] = { 0, 0, 0 };
  double origin[3];
  serial.ToSpace(zero, origin);
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(origin[d], mean[d] / (3.0 * view.NumberOfCells), 1e-12) << d;
  }
  std::vector<double> uv;
  serial.ToPlane(view, uv);
  for (int tasks : { 2, 3 })
  {
    mp::PlaneFrame frame;
    double otherDeviation = -1;
    double otherSize = -1;
    ASSERT_TRUE(frame.Fit(view, otherDeviation, otherSize, mptest::ThreadRunner(tasks)));
    EXPECT_EQ(otherDeviation, deviation) << tasks;
    EXPECT_EQ(otherSize, size) << tasks;
    EXPECT_EQ(frame.Offset(), serial.Offset()) << tasks;
    EXPECT_EQ(frame.Tolerance(), serial.Tolerance()) << tasks;
    std::vector<double> other;
    frame.ToPlane(view, other);
    EXPECT_TRUE(other == uv) << tasks; // origin and axes bit for bit
  }
}

TEST(PlaneFrame, AxisPlanes)
{
  // z = 0.75: the identity (the points' x, y are used in place).
  TestMesh z = mptest::GridMesh(5, 4, 0.25, 134);
  for (Index p = 0; p < z.NumberOfPoints(); ++p)
  {
    z.Points[3 * p + 2] = 0.75;
  }
  mp::PlaneFrame frame;
  double deviation = -1;
  double size = -1;
  ASSERT_TRUE(frame.Fit(Surface(z), deviation, size));
  EXPECT_EQ(deviation, 0.0);
  EXPECT_TRUE(frame.IsIdentity());
  EXPECT_TRUE(frame.IsAxisAligned());
  EXPECT_EQ(frame.Offset(), 0.75);
  ExpectRoundTrip(frame, z, 0.0, "z = 0.75");
  std::vector<double> uv;
  frame.ToPlane(Surface(z), uv);
  for (Index p = 0; p < z.NumberOfPoints(); ++p)
  {
    EXPECT_EQ(uv[3 * p], z.Points[3 * p]);
    EXPECT_EQ(uv[3 * p + 1], z.Points[3 * p + 1]);
  }
  // Every corner at one z takes a short way (one pass); the same mesh with
  // one corner 1e-13 above the others takes the general fit, and both give
  // the same frame.
  TestMesh nearly = z;
  nearly.Points[3 * 7 + 2] += 1e-13;
  mp::PlaneFrame general;
  double generalDeviation = -1;
  ASSERT_TRUE(general.Fit(Surface(nearly), generalDeviation, size));
  EXPECT_GT(generalDeviation, 0.0);
  EXPECT_TRUE(general.IsIdentity());
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_EQ(frame.GetNormal()[d], general.GetNormal()[d]) << d;
  }
  EXPECT_NEAR(frame.Offset(), general.Offset(), 1e-13);
  EXPECT_NEAR(frame.Tolerance(), general.Tolerance(), 1e-22);
  std::vector<double> generalUV;
  general.ToPlane(Surface(z), generalUV);
  EXPECT_EQ(uv, generalUV);

  // x = -2.5 (the grid's x, y become y, z): axis aligned, not the identity.
  TestMesh x = mptest::GridMesh(5, 4, 0.25, 135);
  for (Index p = 0; p < x.NumberOfPoints(); ++p)
  {
    double* q = &x.Points[3 * p];
    q[2] = q[1];
    q[1] = q[0];
    q[0] = -2.5;
  }
  ASSERT_TRUE(frame.Fit(Surface(x), deviation, size));
  EXPECT_EQ(deviation, 0.0);
  EXPECT_TRUE(frame.IsAxisAligned());
  EXPECT_FALSE(frame.IsIdentity());
  EXPECT_EQ(std::fabs(frame.GetNormal()[0]), 1.0);
  ExpectRoundTrip(frame, x, 0.0, "x = -2.5");

  // A mesh without cells: z = 0.
  TestMesh empty;
  ASSERT_TRUE(frame.Fit(Surface(empty), deviation, size));
  EXPECT_TRUE(frame.IsIdentity());
}
