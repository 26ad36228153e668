// SPDX-License-Identifier: BSD-3-Clause
// The kernel's shape functions (Filters/Kernel/Geometry/NodalShapes.h)
// against VTK's own quadratic cells, type by type: the reference nodes equal
// GetParametricCoords bit for bit, and at 1,000 random points of the
// reference cell and up to 0.1 outside it the values equal
// InterpolateFunctions and the derivatives InterpolateDerivs to 1e-13
// (relative to the largest at the point, or 1).
//
// The pyramid's derivatives are the exception: VTK's (9.2)
// vtkQuadraticPyramid::InterpolationDerivs are not the derivatives of its
// own InterpolationFunctions (they differ from the functions' central
// differences by order 1 inside the cell; they agree on parts of the
// base only). The kernel takes VTK's functions and their true
// derivatives, so there the derivatives are checked against central
// differences of VTK's InterpolateFunctions (h = 1e-5, to 1e-8), and VTK's
// InterpolateDerivs' distance from those is printed, not asserted.
//
// A plain program: prints each type's largest differences, exits non-zero
// on a mismatch.
#include "Geometry/NodalShapes.h"

#include "vtkBiQuadraticQuad.h"
#include "vtkBiQuadraticQuadraticWedge.h"
#include "vtkNew.h"
#include "vtkNonLinearCell.h"
#include "vtkQuadraticEdge.h"
#include "vtkQuadraticHexahedron.h"
#include "vtkQuadraticPyramid.h"
#include "vtkQuadraticQuad.h"
#include "vtkQuadraticTetra.h"
#include "vtkQuadraticTriangle.h"
#include "vtkQuadraticWedge.h"
#include "vtkSmartPointer.h"
#include "vtkTriQuadraticHexahedron.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace
{
struct Case
{
  mp::NodalType Type;
  vtkSmartPointer<vtkNonLinearCell> Cell;
  const char* Name;
};

/// A random reference point: each coordinate in [-0.1, 1.1], simplices and
/// wedges kept to their triangle (widened by 0.1), pyramids below 0.9.
void RandomPoint(mp::NodalType type, std::mt19937& rng, double* xi)
{
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  const int d = mp::NodalCellDimension(type);
  for (;;)
  {
    xi[0] = xi[1] = xi[2] = 0.0;
    for (int a = 0; a < d; ++a)
    {
      xi[a] = u(rng);
    }
    const bool simplex = type == mp::NodalType::Triangle6 || type == mp::NodalType::Tetra10;
    const bool wedge = type == mp::NodalType::Wedge15 || type == mp::NodalType::Wedge18;
    const double sum = simplex ? xi[0] + xi[1] + xi[2] : (wedge ? xi[0] + xi[1] : 0.0);
    if (sum <= 1.1 && !(type == mp::NodalType::Pyramid13 && xi[2] > 0.9))
    {
      return;
    }
  }
}

/// The central difference (h = 1e-5) of VTK's function n % count in
/// direction n / count at xi: VTK's derivative layout.
double DifferenceOfVTK(const Case& c, const double* xi, int n)
{
  const int count = c.Cell->GetNumberOfPoints();
  const int a = n / count;
  const double h = 1e-5;
  double plus[3] = { xi[0], xi[1], xi[2] };
  double minus[3] = { xi[0], xi[1], xi[2] };
  plus[a] += h;
  minus[a] -= h;
  double Wp[mp::MaxNodalNodes];
  double Wm[mp::MaxNodalNodes];
  c.Cell->InterpolateFunctions(plus, Wp);
  c.Cell->InterpolateFunctions(minus, Wm);
  return (Wp[n % count] - Wm[n % count]) / (2.0 * h);
}

/// Compares one type; returns whether it matched.
bool Compare(const Case& c, std::mt19937& rng)
{
  const int count = mp::NodalNodeCount(c.Type);
  const int d = mp::NodalCellDimension(c.Type);
  bool ok = c.Cell->GetNumberOfPoints() == count && c.Cell->GetCellDimension() == d;
  // The reference nodes, bit for bit.
  std::vector<double> nodes(3 * count);
  mp::NodalReferenceNodes(c.Type, nodes.data());
  const double* vtkNodes = c.Cell->GetParametricCoords();
  for (int i = 0; ok && i < 3 * count; ++i)
  {
    ok = nodes[i] == vtkNodes[i];
  }
  if (!ok)
  {
    std::printf("%s: nodes or counts differ from VTK's\n", c.Name);
    return false;
  }
  // The pyramid's derivatives against VTK's functions' differences.
  const bool differences = c.Type == mp::NodalType::Pyramid13;
  const double bound = differences ? 1e-8 : 1e-13;
  double vtkSlope = 0.0;
  double worstValue = 0.0;
  double worstSlope = 0.0;
  for (int k = 0; k < 1000; ++k)
  {
    double xi[3];
    RandomPoint(c.Type, rng, xi);
    double N[mp::MaxNodalNodes];
    double dN[mp::MaxNodalNodes * 3];
    mp::NodalValues(c.Type, xi, N);
    mp::NodalDerivatives(c.Type, xi, dN);
    double W[mp::MaxNodalNodes];
    double dW[mp::MaxNodalNodes * 3]; // VTK's: direction after direction
    c.Cell->InterpolateFunctions(xi, W);
    c.Cell->InterpolateDerivs(xi, dW);
    if (differences)
    {
      for (int n = 0; n < count * 3; ++n)
      {
        vtkSlope = std::max(vtkSlope, std::abs(dW[n] - DifferenceOfVTK(c, xi, n)));
      }
      for (int n = 0; n < count * 3; ++n)
      {
        dW[n] = DifferenceOfVTK(c, xi, n);
      }
    }
    double valueScale = 1.0;
    double slopeScale = 1.0;
    for (int n = 0; n < count; ++n)
    {
      valueScale = std::max(valueScale, std::abs(W[n]));
      for (int a = 0; a < d; ++a)
      {
        slopeScale = std::max(slopeScale, std::abs(dW[a * count + n]));
      }
    }
    for (int n = 0; n < count; ++n)
    {
      worstValue = std::max(worstValue, std::abs(N[n] - W[n]) / valueScale);
      for (int a = 0; a < d; ++a)
      {
        worstSlope = std::max(worstSlope, std::abs(dN[n * 3 + a] - dW[a * count + n]) / slopeScale);
      }
    }
  }
  std::printf("%-32s values %.3g derivatives %.3g", c.Name, worstValue, worstSlope);
  if (differences)
  {
    std::printf(
      " (against central differences; VTK's InterpolateDerivs differ from them by %.3g)", vtkSlope);
  }
  std::printf("\n");
  return worstValue <= 1e-13 && worstSlope <= bound;
}
} // namespace

int main()
{
  const Case cases[] = {
    { mp::NodalType::Edge3, vtkSmartPointer<vtkQuadraticEdge>::New(), "vtkQuadraticEdge" },
    { mp::NodalType::Triangle6, vtkSmartPointer<vtkQuadraticTriangle>::New(),
      "vtkQuadraticTriangle" },
    { mp::NodalType::Quad8, vtkSmartPointer<vtkQuadraticQuad>::New(), "vtkQuadraticQuad" },
    { mp::NodalType::Quad9, vtkSmartPointer<vtkBiQuadraticQuad>::New(), "vtkBiQuadraticQuad" },
    { mp::NodalType::Tetra10, vtkSmartPointer<vtkQuadraticTetra>::New(), "vtkQuadraticTetra" },
    { mp::NodalType::Hexa20, vtkSmartPointer<vtkQuadraticHexahedron>::New(),
      "vtkQuadraticHexahedron" },
    { mp::NodalType::Hexa27, vtkSmartPointer<vtkTriQuadraticHexahedron>::New(),
      "vtkTriQuadraticHexahedron" },
    { mp::NodalType::Wedge15, vtkSmartPointer<vtkQuadraticWedge>::New(), "vtkQuadraticWedge" },
    { mp::NodalType::Wedge18, vtkSmartPointer<vtkBiQuadraticQuadraticWedge>::New(),
      "vtkBiQuadraticQuadraticWedge" },
    { mp::NodalType::Pyramid13, vtkSmartPointer<vtkQuadraticPyramid>::New(),
      "vtkQuadraticPyramid" },
  };
  std::mt19937 rng(54);
  bool ok = true;
  for (const Case& c : cases)
  {
    ok = Compare(c, rng) && ok;
  }
  std::printf(ok ? "NodalShapes equal VTK's functions\n" : "NodalShapes differ from VTK's\n");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
