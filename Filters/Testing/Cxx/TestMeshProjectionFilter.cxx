// SPDX-License-Identifier: BSD-3-Clause
// vtkMeshProjectionFilter on the sample L-shape with a hole: numbers first
// (exactness, conservation, coverage, advancing front == brute force), then
// an image of the source field beside the projected field.
#include "MeshProjectionTestUtilities.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkPolyData.h"

int TestMeshProjectionFilter(int argc, char* argv[])
{
  int failures = 0;
  auto source = mptest::ReadSample("lshape_source.vtu");
  auto target = mptest::ReadSample("lshape_target.vtu");
  MP_CHECK(source->GetNumberOfCells() > 3000 && target->GetNumberOfCells() > 2000);

  vtkNew<vtkMeshProjectionFilter> filter;
  MP_CHECK(filter->GetSearchMethod() == vtkMeshProjectionFilter::ADVANCING_FRONT);
  MP_CHECK(!filter->GetOutputIntersections());
  MP_CHECK(filter->GetFillWithNaN() && filter->GetFillValue() == 0);
  filter->SetInputData(target);
  filter->SetSourceData(source);
  filter->OutputIntersectionsOn();
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetUnstructuredGridOutput();
  vtkPointData* pd = out->GetPointData();

  // Every source array arrives as double with its components; Input's own array stays.
  vtkDataArray* smooth = pd->GetArray("Smooth");
  vtkDataArray* linear = pd->GetArray("Linear");
  vtkDataArray* velocity = pd->GetArray("Velocity");
  MP_CHECK(smooth && linear && velocity && pd->GetArray("TargetId"));
  if (!smooth || !linear || !velocity)
  {
    return EXIT_FAILURE;
  }
  MP_CHECK(vtkDoubleArray::SafeDownCast(smooth) != nullptr);
  MP_CHECK(velocity->GetNumberOfComponents() == 3);
  MP_CHECK(out->GetNumberOfPoints() == target->GetNumberOfPoints());
  MP_CHECK(out->GetNumberOfCells() == target->GetNumberOfCells());

  // The same domain: every point valid, every cell fully covered.
  vtkDataArray* mask = pd->GetArray("vtkValidPointMask");
  vtkDataArray* covered = out->GetCellData()->GetArray("CoveredFraction");
  MP_CHECK(mask && covered);
  for (vtkIdType i = 0; mask && i < out->GetNumberOfPoints(); ++i)
  {
    MP_CHECK(mask->GetComponent(i, 0) == 1);
  }
  for (vtkIdType c = 0; covered && c < out->GetNumberOfCells(); ++c)
  {
    MP_CHECK(std::fabs(covered->GetComponent(c, 0) - 1.0) < 1e-12);
  }

  // Linear fields are reproduced exactly, the rotation field too.
  double worst = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    worst = std::max(worst, std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1])));
    worst = std::max(worst, std::fabs(velocity->GetComponent(i, 0) + (x[1] - 1)));
    worst = std::max(worst, std::fabs(velocity->GetComponent(i, 1) - (x[0] - 1)));
  }
  std::cout << "linear fields: max error " << worst << std::endl;
  MP_CHECK(worst < 1e-12);

  // Integrals are conserved.
  for (const char* name : { "Smooth", "Linear" })
  {
    const double is = mptest::Integral(source, source->GetPointData()->GetArray(name));
    const double it = mptest::Integral(out, pd->GetArray(name));
    std::cout << name << ": integral source " << is << " target " << it << std::endl;
    MP_CHECK(std::fabs(is - it) <= 1e-13 * std::fabs(is));
  }

  // The intersection polygons tile the target.
  vtkPolyData* polygons = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(1));
  MP_CHECK(polygons && polygons->GetNumberOfCells() == filter->GetNumberOfIntersections());
  if (polygons)
  {
    vtkDataArray* area = polygons->GetCellData()->GetArray("Area");
    MP_CHECK(area && polygons->GetCellData()->GetArray("SourceCellId") &&
      polygons->GetCellData()->GetArray("TargetCellId"));
    double total = 0;
    for (vtkIdType c = 0; area && c < area->GetNumberOfTuples(); ++c)
    {
      total += area->GetComponent(c, 0);
    }
    MP_CHECK(std::fabs(total - mptest::Measure(target)) < 1e-12);
    MP_CHECK(std::fabs(filter->GetCoveredMeasure() - 2.91) < 1e-12);
  }
  // Linear work: far fewer tests than the brute force's n * m.
  std::cout << "advancing front: " << filter->GetNumberOfIntersections() << " pieces, "
            << filter->GetNumberOfIntersectionTests() << " tests, "
            << filter->GetNumberOfLocatorQueries() << " locator queries" << std::endl;
  MP_CHECK(filter->GetNumberOfIntersectionTests() < 4 * filter->GetNumberOfIntersections());

  // The brute force finds the same pieces and the same projection.
  vtkNew<vtkMeshProjectionFilter> brute;
  brute->SetInputData(target);
  brute->SetSourceData(source);
  brute->SetSearchMethodToBruteForce();
  brute->Update();
  MP_CHECK(brute->GetNumberOfIntersections() == filter->GetNumberOfIntersections());
  MP_CHECK(brute->GetNumberOfIntersectionTests() ==
    source->GetNumberOfCells() * target->GetNumberOfCells());
  vtkDataArray* bruteSmooth =
    brute->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth");
  for (vtkIdType i = 0; bruteSmooth && i < out->GetNumberOfPoints(); ++i)
  {
    MP_CHECK(std::fabs(bruteSmooth->GetComponent(i, 0) - smooth->GetComponent(i, 0)) < 1e-13);
  }

  // The picture: source field (left) and projected field (right), same colours.
  const int image = mptest::SideBySideImageTest(argc, argv, source, out, "Smooth");
  MP_CHECK(image != vtkRegressionTester::FAILED);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
