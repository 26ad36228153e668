// SPDX-License-Identifier: BSD-3-Clause
// vtkMeshProjectionFilter on the 3D sample pair (tetrahedral meshes of an
// L-shaped prism with a hole): exactness, conservation, complete coverage,
// the intersection polyhedra, advancing front == brute force; then an image
// of a slice through the source field beside the same slice of the
// projected field.
#include "MeshProjectionTestUtilities.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkCutter.h"
#include "vtkDoubleArray.h"
#include "vtkPlane.h"
#include "vtkPolyData.h"

#include <set>
#include <utility>

int TestMeshProjectionFilter3D(int argc, char* argv[])
{
  int failures = 0;
  auto source = mptest::ReadSample("lshape3d_source.vtu");
  auto target = mptest::ReadSample("lshape3d_target.vtu");
  MP_CHECK(source->GetNumberOfCells() > 8000 && target->GetNumberOfCells() > 2000);

  vtkNew<vtkMeshProjectionFilter> filter;
  filter->SetInputData(target);
  filter->SetSourceData(source);
  filter->OutputIntersectionsOn();
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetUnstructuredGridOutput();
  vtkPointData* pd = out->GetPointData();
  vtkDataArray* linear = pd->GetArray("Linear");
  vtkDataArray* velocity = pd->GetArray("Velocity");
  vtkDataArray* smooth = pd->GetArray("Smooth");
  MP_CHECK(linear && velocity && smooth && pd->GetArray("TargetId"));
  if (!linear || !velocity || !smooth)
  {
    return EXIT_FAILURE;
  }

  double worst = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    worst = std::max(
      worst, std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2])));
    worst = std::max(worst, std::fabs(velocity->GetComponent(i, 0) + (x[1] - 1.5)));
    worst = std::max(worst, std::fabs(velocity->GetComponent(i, 2) - 0.3));
  }
  std::cout << "3D linear fields: max error " << worst << std::endl;
  MP_CHECK(worst < 1e-12);

  for (const char* name : { "Smooth", "Linear" })
  {
    const double is = mptest::Integral(source, source->GetPointData()->GetArray(name));
    const double it = mptest::Integral(out, pd->GetArray(name));
    std::cout << name << ": integral source " << is << " target " << it << std::endl;
    MP_CHECK(std::fabs(is - it) <= 1e-13 * std::fabs(is));
  }
  MP_CHECK(std::fabs(filter->GetCoveredMeasure() - 6.5) < 1e-12);
  vtkDataArray* covered = out->GetCellData()->GetArray("CoveredFraction");
  for (vtkIdType c = 0; covered && c < out->GetNumberOfCells(); ++c)
  {
    MP_CHECK(std::fabs(covered->GetComponent(c, 0) - 1.0) < 1e-12);
  }

  // Output 2: the polyhedra as tetrahedra; output 1 (2D polygons) stays empty.
  auto* polyhedra = vtkUnstructuredGrid::SafeDownCast(filter->GetOutputDataObject(2));
  auto* polygons = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(1));
  MP_CHECK(polygons && polygons->GetNumberOfCells() == 0);
  MP_CHECK(polyhedra && polyhedra->GetNumberOfCells() >= filter->GetNumberOfIntersections());
  std::set<std::pair<vtkIdType, vtkIdType>> frontPairs;
  if (polyhedra)
  {
    vtkDataArray* volume = polyhedra->GetCellData()->GetArray("Volume");
    vtkDataArray* tids = polyhedra->GetCellData()->GetArray("TargetCellId");
    vtkDataArray* sids = polyhedra->GetCellData()->GetArray("SourceCellId");
    MP_CHECK(volume && tids && sids);
    double total = 0;
    for (vtkIdType c = 0; volume && tids && sids && c < volume->GetNumberOfTuples(); ++c)
    {
      total += volume->GetComponent(c, 0);
      frontPairs.emplace(tids->GetComponent(c, 0), sids->GetComponent(c, 0));
    }
    MP_CHECK(std::fabs(total - 6.5) < 1e-12);
    MP_CHECK(std::fabs(mptest::Measure(polyhedra) - 6.5) < 1e-11);
    MP_CHECK(vtkIdType(frontPairs.size()) == filter->GetNumberOfIntersections());
  }
  std::cout << "advancing front: " << filter->GetNumberOfIntersections() << " pairs, "
            << filter->GetNumberOfIntersectionTests() << " tests, "
            << filter->GetNumberOfLocatorQueries() << " locator queries" << std::endl;
  // Linear work: a bounded number of tests per pair (the halo of a cell's
  // neighbours is larger in 3D), far below the brute force's n * m.
  MP_CHECK(filter->GetNumberOfIntersectionTests() < 12 * filter->GetNumberOfIntersections());
  MP_CHECK(filter->GetNumberOfIntersectionTests() <
    source->GetNumberOfCells() * target->GetNumberOfCells() / 20);

  vtkNew<vtkMeshProjectionFilter> brute;
  brute->SetInputData(target);
  brute->SetSourceData(source);
  brute->SetSearchMethodToBruteForce();
  brute->OutputIntersectionsOn();
  brute->Update();
  MP_CHECK(brute->GetNumberOfIntersections() == filter->GetNumberOfIntersections());
  auto* brutePolyhedra = vtkUnstructuredGrid::SafeDownCast(brute->GetOutputDataObject(2));
  std::set<std::pair<vtkIdType, vtkIdType>> brutePairs;
  for (vtkIdType c = 0; brutePolyhedra && c < brutePolyhedra->GetNumberOfCells(); ++c)
  {
    brutePairs.emplace(brutePolyhedra->GetCellData()->GetArray("TargetCellId")->GetComponent(c, 0),
      brutePolyhedra->GetCellData()->GetArray("SourceCellId")->GetComponent(c, 0));
  }
  MP_CHECK(brutePairs == frontPairs);
  vtkDataArray* bruteSmooth =
    brute->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth");
  for (vtkIdType i = 0; bruteSmooth && i < out->GetNumberOfPoints(); ++i)
  {
    MP_CHECK(std::fabs(bruteSmooth->GetComponent(i, 0) - smooth->GetComponent(i, 0)) < 1e-13);
  }

  // The picture: the slice z = 0.55 of the source field (left) and of the
  // projected field (right), same colours, seen from above.
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0, 0, 0.55);
  plane->SetNormal(0, 0, 1);
  vtkNew<vtkCutter> sourceCut;
  sourceCut->SetInputData(source);
  sourceCut->SetCutFunction(plane);
  sourceCut->Update();
  vtkNew<vtkCutter> targetCut;
  targetCut->SetInputData(out);
  targetCut->SetCutFunction(plane);
  targetCut->Update();
  const int image = mptest::SideBySideImageTest(
    argc, argv, sourceCut->GetOutput(), targetCut->GetOutput(), "Smooth");
  MP_CHECK(image != vtkRegressionTester::FAILED);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
