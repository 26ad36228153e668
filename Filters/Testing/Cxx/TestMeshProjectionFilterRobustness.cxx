// SPDX-License-Identifier: BSD-3-Clause
// Hostile but meaningful inputs: ghost cells (in Source and Input),
// duplicate and unused points, zero-measure and inverted cells (triangles
// and tetrahedra), a folded source, and the same meshes translated by
// 10^6 or scaled by 10^-6 and 10^6 (2D and 3D). Each has an exact expected
// outcome or is compared with the plain run.
#include "MeshProjectionTestUtilities.h"
#include "vtkDataArraySelection.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataSetAttributes.h"
#include "vtkExecutive.h"
#include "vtkIdList.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace
{
struct Result
{
  vtkSmartPointer<vtkUnstructuredGrid> Output;
  vtkIdType Pieces = 0;
  std::string Warnings;
  bool Error = false;
};

Result Project(vtkUnstructuredGrid* target, vtkUnstructuredGrid* source, int threads = 0)
{
  vtkNew<vtkMeshProjectionFilter> filter;
  filter->SetNumberOfThreads(threads);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->GetCellDataArraySelection()->DisableArray("Region"); // the samples' integer label
  filter->SetInputData(target);
  filter->SetSourceData(source);
  filter->Update();
  Result r;
  r.Output = filter->GetUnstructuredGridOutput();
  r.Pieces = filter->GetNumberOfIntersections();
  r.Warnings = observer->GetWarning() ? observer->GetWarningMessage() : "";
  r.Error = observer->GetError();
  return r;
}

/// A copy of `grid` with every point mapped by f.
vtkSmartPointer<vtkUnstructuredGrid> Mapped(
  vtkUnstructuredGrid* grid, const std::function<void(double*)>& f)
{
  auto copy = vtkSmartPointer<vtkUnstructuredGrid>::New();
  copy->DeepCopy(grid);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    double x[3];
    copy->GetPoint(i, x);
    f(x);
    copy->GetPoints()->SetPoint(i, x);
  }
  return copy;
}

/// The largest difference of array `name` between two results, over the
/// points valid in both; -1 when the masks differ.
double Difference(const Result& a, const Result& b, const char* name, double scale = 1)
{
  vtkDataArray* ua = a.Output->GetPointData()->GetArray(name);
  vtkDataArray* ub = b.Output->GetPointData()->GetArray(name);
  vtkDataArray* ma = a.Output->GetPointData()->GetArray("vtkValidPointMask");
  vtkDataArray* mb = b.Output->GetPointData()->GetArray("vtkValidPointMask");
  if (!ua || !ub || !ma || !mb || ua->GetNumberOfTuples() != ub->GetNumberOfTuples())
  {
    return -1;
  }
  double worst = 0;
  for (vtkIdType i = 0; i < ua->GetNumberOfTuples(); ++i)
  {
    if (ma->GetComponent(i, 0) != mb->GetComponent(i, 0))
    {
      return -1;
    }
    if (ma->GetComponent(i, 0))
    {
      worst = std::max(worst, std::fabs(ua->GetComponent(i, 0) - scale * ub->GetComponent(i, 0)));
    }
  }
  return worst;
}

/// The largest error of the projected `Linear` = 1 + 2x - 3y + z/2 (the 3D
/// sample's) over the points valid in `r`; their number in `valid`.
double LinearError3D(const Result& r, vtkIdType* valid)
{
  vtkDataArray* linear = r.Output->GetPointData()->GetArray("Linear");
  vtkDataArray* mask = r.Output->GetPointData()->GetArray("vtkValidPointMask");
  *valid = 0;
  if (!linear || !mask)
  {
    return 1e300;
  }
  double worst = 0;
  for (vtkIdType i = 0; i < linear->GetNumberOfTuples(); ++i)
  {
    if (mask->GetComponent(i, 0))
    {
      double x[3];
      r.Output->GetPoint(i, x);
      ++*valid;
      worst = std::max(
        worst, std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2])));
    }
  }
  return worst;
}

/// |∫ Smooth over the target - ∫ Smooth over the source| / |∫ Smooth over the
/// source|; `target` gives the cells (the output's point ids must match it).
double ConservationError(vtkUnstructuredGrid* target, const Result& r, vtkUnstructuredGrid* source)
{
  vtkDataArray* projected = r.Output->GetPointData()->GetArray("Smooth");
  if (!projected)
  {
    return 1e300;
  }
  const double is = mptest::Integral(source, source->GetPointData()->GetArray("Smooth"));
  return std::fabs(mptest::Integral(target, projected) - is) / std::fabs(is);
}
/// The mean x of the corners of triangle c (its points left in `ids`).
double CenterX(vtkUnstructuredGrid* grid, vtkIdType c, vtkIdList* ids)
{
  grid->GetCellPoints(c, ids);
  double cx = 0;
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
  {
    cx += grid->GetPoint(ids->GetId(k))[0] / ids->GetNumberOfIds();
  }
  return cx;
}

/**
 * A copy of `grid` in which every other cell uses copies of its points (the
 * points and their data appended once more): the same geometry and fields,
 * but the mesh falls apart topologically.
 */
vtkSmartPointer<vtkUnstructuredGrid> SplitEveryOtherCell(vtkUnstructuredGrid* grid)
{
  auto split = vtkSmartPointer<vtkUnstructuredGrid>::New();
  split->DeepCopy(grid);
  const vtkIdType n = grid->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    split->GetPoints()->InsertNextPoint(grid->GetPoint(i));
  }
  for (int a = 0; a < split->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* u = split->GetPointData()->GetArray(a);
    for (vtkIdType i = 0; i < n; ++i)
    {
      u->InsertNextTuple(u->GetTuple(i));
    }
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < split->GetNumberOfCells(); c += 2)
  {
    split->GetCellPoints(c, ids);
    std::vector<vtkIdType> shifted(static_cast<size_t>(ids->GetNumberOfIds()));
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      shifted[k] = ids->GetId(k) + n;
    }
    split->ReplaceCell(c, ids->GetNumberOfIds(), shifted.data());
  }
  return split;
}

/// Ghost cells are left out: marking the source cells of the right arm
/// (x > 1) as duplicates equals removing them.
bool CheckSourceGhostCells(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> ghosted;
  ghosted->DeepCopy(source);
  vtkNew<vtkUnstructuredGrid> removed;
  removed->SetPoints(source->GetPoints());
  removed->GetPointData()->ShallowCopy(source->GetPointData());
  const vtkSmartPointer<vtkUnsignedCharArray> ghosts =
    mptest::GhostArray(source->GetNumberOfCells());
  vtkNew<vtkIdList> ids;
  vtkIdType ghostCount = 0;
  for (vtkIdType c = 0; c < source->GetNumberOfCells(); ++c)
  {
    const bool ghost = CenterX(source, c, ids) > 1.0;
    ghosts->SetValue(c, ghost ? vtkDataSetAttributes::DUPLICATECELL : 0);
    ghostCount += ghost;
    if (!ghost)
    {
      removed->InsertNextCell(VTK_TRIANGLE, ids);
    }
  }
  ghosted->GetCellData()->AddArray(ghosts);
  const Result withGhosts = Project(target, ghosted);
  const Result without = Project(target, removed);
  MP_CHECK(ghostCount > 500);
  MP_CHECK(withGhosts.Warnings.find("Ghost cells") != std::string::npos);
  MP_CHECK(withGhosts.Pieces == without.Pieces);
  const double d = Difference(withGhosts, without, "Smooth");
  MP_CHECK(d >= 0 && d < 1e-12);
  return failures == 0;
}

/// Target ghost cells: no coverage, and points only they use are invalid.
bool CheckTargetGhostCell(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> targetGhosted;
  targetGhosted->DeepCopy(target);
  const vtkSmartPointer<vtkUnsignedCharArray> tghosts =
    mptest::GhostArray(target->GetNumberOfCells());
  tghosts->SetValue(0, vtkDataSetAttributes::DUPLICATECELL);
  targetGhosted->GetCellData()->AddArray(tghosts);
  const Result tg = Project(targetGhosted, source);
  MP_CHECK(tg.Output->GetCellData()->GetArray("CoveredFraction")->GetComponent(0, 0) == 0);
  MP_CHECK(tg.Output->GetCellData()->GetArray("CoveredFraction")->GetComponent(1, 0) > 0.999);
  return failures == 0;
}

/// A whole region of target ghost cells (the right arm, x > 1): the points
/// only ghost cells use are invalid (mask 0, NaN); those an owned cell
/// uses are valid, with the linear field exact (its support is covered).
bool CheckTargetGhostRegion(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> targetArm;
  targetArm->DeepCopy(target);
  const vtkSmartPointer<vtkUnsignedCharArray> armGhosts =
    mptest::GhostArray(target->GetNumberOfCells());
  std::vector<char> owned(target->GetNumberOfPoints(), 0);
  vtkNew<vtkIdList> ids;
  vtkIdType armCount = 0;
  for (vtkIdType c = 0; c < target->GetNumberOfCells(); ++c)
  {
    const double cx = CenterX(target, c, ids);
    armGhosts->SetValue(c, cx > 1.0 ? vtkDataSetAttributes::DUPLICATECELL : 0);
    armCount += cx > 1.0;
    for (vtkIdType k = 0; cx <= 1.0 && k < 3; ++k)
    {
      owned[ids->GetId(k)] = 1;
    }
  }
  targetArm->GetCellData()->AddArray(armGhosts);
  const Result arm = Project(targetArm, source);
  MP_CHECK(!arm.Error);
  const std::string expected = "Ghost cells (Input: " + std::to_string(armCount) + ", Source: 0)";
  MP_CHECK(arm.Warnings.find(expected) != std::string::npos);
  vtkDataArray* mask = arm.Output->GetPointData()->GetArray("vtkValidPointMask");
  vtkDataArray* linear = arm.Output->GetPointData()->GetArray("Linear");
  vtkDataArray* covered = arm.Output->GetCellData()->GetArray("CoveredFraction");
  MP_CHECK(mask && linear && covered);
  vtkIdType ghostOnly = 0;
  for (vtkIdType i = 0; mask && linear && i < target->GetNumberOfPoints(); ++i)
  {
    MP_CHECK(mask->GetComponent(i, 0) == owned[i]);
    if (owned[i])
    {
      double x[3];
      target->GetPoint(i, x);
      MP_CHECK(std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1])) < 1e-12);
    }
    else
    {
      ++ghostOnly;
      MP_CHECK(std::isnan(linear->GetComponent(i, 0)));
    }
  }
  std::cout << "target ghost cells: " << armCount << ", points only they use: " << ghostOnly
            << std::endl;
  MP_CHECK(armCount > 300 && ghostOnly > 100);
  for (vtkIdType c = 0; covered && c < target->GetNumberOfCells(); ++c)
  {
    const double fraction = armGhosts->GetValue(c) ? 0.0 : 1.0;
    MP_CHECK(std::fabs(covered->GetComponent(c, 0) - fraction) < 1e-12);
  }
  return failures == 0;
}

/// Duplicate points: half of the cells use copies of their points, so the
/// mesh falls apart topologically; the result must not change.
bool CheckDuplicatePoints(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const Result& plain)
{
  int failures = 0;
  auto split = SplitEveryOtherCell(source);
  const Result r = Project(target, split);
  MP_CHECK(!r.Error);
  MP_CHECK(r.Pieces == plain.Pieces);
  const double d = Difference(r, plain, "Smooth");
  MP_CHECK(d >= 0 && d < 1e-12);
  return failures == 0;
}

/// Unused target points: invalid (NaN); the others unchanged.
bool CheckUnusedTargetPoints(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const Result& plain)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> extra;
  extra->DeepCopy(target);
  for (int k = 0; k < 4; ++k)
  {
    extra->GetPoints()->InsertNextPoint(0.5 + k, 7.0, 0.0);
  }
  extra->GetPointData()->Initialize();
  const Result r = Project(extra, source);
  vtkDataArray* mask = r.Output->GetPointData()->GetArray("vtkValidPointMask");
  vtkDataArray* smooth = r.Output->GetPointData()->GetArray("Smooth");
  vtkDataArray* ref = plain.Output->GetPointData()->GetArray("Smooth");
  for (vtkIdType i = 0; mask && smooth && i < extra->GetNumberOfPoints(); ++i)
  {
    if (i < target->GetNumberOfPoints())
    {
      MP_CHECK(mask->GetComponent(i, 0) == 1);
      MP_CHECK(std::fabs(smooth->GetComponent(i, 0) - ref->GetComponent(i, 0)) < 1e-13);
    }
    else
    {
      MP_CHECK(mask->GetComponent(i, 0) == 0 && std::isnan(smooth->GetComponent(i, 0)));
    }
  }
  return failures == 0;
}

/// A zero-area source cell is ignored with a warning.
bool CheckZeroAreaCell(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const Result& plain)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> flat;
  flat->DeepCopy(source);
  const vtkIdType p = flat->GetPoints()->InsertNextPoint(0.2, 0.2, 0);
  const vtkIdType q = flat->GetPoints()->InsertNextPoint(0.3, 0.3, 0);
  const vtkIdType r = flat->GetPoints()->InsertNextPoint(0.4, 0.4, 0);
  for (int a = 0; a < flat->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* u = flat->GetPointData()->GetArray(a);
    for (int k = 0; k < 3; ++k)
    {
      u->InsertNextTuple(u->GetTuple(0));
    }
  }
  vtkIdType ids[3] = { p, q, r };
  flat->InsertNextCell(VTK_TRIANGLE, 3, ids);
  const Result res = Project(target, flat);
  MP_CHECK(res.Warnings.find("zero area") != std::string::npos);
  const double d = Difference(res, plain, "Smooth");
  MP_CHECK(d >= 0 && d < 1e-13);
  return failures == 0;
}

/// Inverted cells (every other source triangle listed clockwise) are the
/// same geometry: nothing changes.
bool CheckInvertedTriangles(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const Result& plain)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> flipped;
  flipped->DeepCopy(source);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < flipped->GetNumberOfCells(); c += 2)
  {
    flipped->GetCellPoints(c, ids);
    vtkIdType reversed[3] = { ids->GetId(0), ids->GetId(2), ids->GetId(1) };
    flipped->ReplaceCell(c, 3, reversed);
  }
  const Result r = Project(target, flipped);
  MP_CHECK(!r.Error && r.Warnings.empty() && r.Pieces == plain.Pieces);
  const double d = Difference(r, plain, "Smooth");
  MP_CHECK(d >= 0 && d < 1e-13);
  return failures == 0;
}

/// An empty Input: a warning and an empty, well-formed output.
bool CheckEmptyInput(vtkUnstructuredGrid* source)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> empty;
  const Result r = Project(empty, source);
  MP_CHECK(!r.Error && r.Warnings.find("Input has no cells") != std::string::npos);
  MP_CHECK(r.Output->GetNumberOfPoints() == 0);
  MP_CHECK(r.Output->GetPointData()->GetArray("vtkValidPointMask") != nullptr);
  return failures == 0;
}

/// A Source without point arrays: a warning; mask and coverage still computed.
bool CheckSourceWithoutPointArrays(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> bare;
  bare->DeepCopy(source);
  bare->GetPointData()->Initialize();
  const Result r = Project(target, bare);
  MP_CHECK(!r.Error && r.Warnings.find("no arrays to project") != std::string::npos);
  vtkDataArray* mask = r.Output->GetPointData()->GetArray("vtkValidPointMask");
  MP_CHECK(mask && mask->GetRange()[0] == 1);
  MP_CHECK(r.Output->GetCellData()->GetArray("CoveredFraction") != nullptr);
  return failures == 0;
}

/// A Source whose only point array is not projected (vtkGhostType, or a
/// mask from an earlier projection): the same warning, no projected
/// arrays, the mask computed.
bool CheckOnlyArrayNotProjected(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const char* only)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> bare;
  bare->DeepCopy(source);
  bare->GetPointData()->Initialize();
  vtkNew<vtkUnsignedCharArray> flags;
  flags->SetName(only);
  flags->SetNumberOfValues(bare->GetNumberOfPoints());
  flags->Fill(0);
  bare->GetPointData()->AddArray(flags);
  const Result r = Project(target, bare);
  MP_CHECK(!r.Error && r.Warnings.find("Source has no arrays to project") != std::string::npos);
  MP_CHECK(r.Warnings.find("holds integers") == std::string::npos);
  vtkPointData* pd = r.Output->GetPointData();
  MP_CHECK(pd->GetNumberOfArrays() == 2 && pd->GetArray("TargetId")); // and the mask
  vtkDataArray* mask = pd->GetArray("vtkValidPointMask");
  MP_CHECK(mask && mask->GetRange()[0] == 1);
  return failures == 0;
}

/// A folded source (cells given twice) is flagged.
bool CheckFoldedSource(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> folded;
  folded->DeepCopy(source);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < 10; ++c)
  {
    source->GetCellPoints(c, ids);
    folded->InsertNextCell(VTK_TRIANGLE, ids);
  }
  const Result r = Project(target, folded);
  MP_CHECK(r.Warnings.find("covered more than once") != std::string::npos);
  return failures == 0;
}

/// Zero-volume tetrahedra (four points in a plane z = const), one in each
/// mesh: ignored with a warning. The source one changes nothing; the
/// target one's own points are invalid, the others as before.
bool CheckZeroVolumeTetrahedra(const vtkSmartPointer<vtkUnstructuredGrid>& source3,
  const vtkSmartPointer<vtkUnstructuredGrid>& target3, const Result& base)
{
  int failures = 0;
  vtkIdType valid = 0;
  auto flatCell = [](vtkUnstructuredGrid* grid, double x, double y, double z) {
    const double corners[4][3] = { { x, y, z }, { x + 0.2, y, z }, { x, y + 0.2, z },
      { x + 0.1, y + 0.1, z } };
    vtkIdType tet[4];
    for (int k = 0; k < 4; ++k)
    {
      tet[k] = grid->GetPoints()->InsertNextPoint(corners[k]);
    }
    for (int a = 0; a < grid->GetPointData()->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* u = grid->GetPointData()->GetArray(a);
      for (int k = 0; k < 4; ++k)
      {
        u->InsertNextTuple(u->GetTuple(0));
      }
    }
    grid->InsertNextCell(VTK_TETRA, 4, tet);
  };
  vtkNew<vtkUnstructuredGrid> flatSource;
  flatSource->DeepCopy(source3);
  flatCell(flatSource, 0.2, 0.2, 0.3);
  vtkNew<vtkUnstructuredGrid> flatTarget;
  flatTarget->DeepCopy(target3);
  flatCell(flatTarget, 2.0, 0.5, 0.5);
  const Result flat = Project(flatTarget, flatSource);
  MP_CHECK(!flat.Error);
  MP_CHECK(flat.Warnings.find("Cells of zero volume (Input: 1, Source: 1) were ignored") !=
    std::string::npos);
  MP_CHECK(flat.Pieces == base.Pieces);
  MP_CHECK(LinearError3D(flat, &valid) < 1e-12 && valid == target3->GetNumberOfPoints());
  vtkDataArray* mask = flat.Output->GetPointData()->GetArray("vtkValidPointMask");
  vtkDataArray* smooth = flat.Output->GetPointData()->GetArray("Smooth");
  vtkDataArray* ref = base.Output->GetPointData()->GetArray("Smooth");
  for (vtkIdType i = 0; mask && smooth && ref && i < flatTarget->GetNumberOfPoints(); ++i)
  {
    if (i < target3->GetNumberOfPoints())
    {
      MP_CHECK(mask->GetComponent(i, 0) == 1);
      MP_CHECK(std::fabs(smooth->GetComponent(i, 0) - ref->GetComponent(i, 0)) < 1e-13);
    }
    else
    {
      MP_CHECK(mask->GetComponent(i, 0) == 0 && std::isnan(smooth->GetComponent(i, 0)));
    }
  }
  std::cout << "3D zero-volume cells: linear error " << LinearError3D(flat, &valid)
            << ", conservation error " << ConservationError(target3, flat, source3) << std::endl;
  MP_CHECK(ConservationError(target3, flat, source3) < 1e-13);
  return failures == 0;
}

/// Inverted tetrahedra (two corners swapped in every other cell), in the
/// source and in the target: the same geometry, no warning, same result.
bool CheckInvertedTetrahedra(const vtkSmartPointer<vtkUnstructuredGrid>& source3,
  const vtkSmartPointer<vtkUnstructuredGrid>& target3, const Result& base)
{
  int failures = 0;
  vtkIdType valid = 0;
  vtkNew<vtkIdList> ids;
  auto inverted = [&ids](vtkUnstructuredGrid* grid) {
    auto copy = vtkSmartPointer<vtkUnstructuredGrid>::New();
    copy->DeepCopy(grid);
    for (vtkIdType c = 0; c < copy->GetNumberOfCells(); c += 2)
    {
      copy->GetCellPoints(c, ids);
      vtkIdType swapped[4] = { ids->GetId(0), ids->GetId(2), ids->GetId(1), ids->GetId(3) };
      copy->ReplaceCell(c, 4, swapped);
    }
    return copy;
  };
  for (int which = 0; which < 2; ++which)
  {
    auto t = which == 0 ? target3 : inverted(target3);
    auto s = which == 0 ? inverted(source3) : source3;
    const Result r = Project(t, s);
    MP_CHECK(!r.Error && r.Warnings.empty() && r.Pieces == base.Pieces);
    const double d = Difference(r, base, "Smooth");
    MP_CHECK(d >= 0 && d < 1e-13);
    std::cout << "3D inverted " << (which == 0 ? "source" : "target") << " cells: linear error "
              << LinearError3D(r, &valid) << ", conservation error " << ConservationError(t, r, s)
              << ", max change " << d << std::endl;
    MP_CHECK(LinearError3D(r, &valid) < 1e-12 && valid == target3->GetNumberOfPoints());
    MP_CHECK(ConservationError(t, r, s) < 1e-13);
  }
  return failures == 0;
}

/// Duplicate points: every other source tetrahedron uses copies of its
/// points, so the mesh falls apart topologically; the result must not
/// change.
bool CheckDuplicatePoints3D(const vtkSmartPointer<vtkUnstructuredGrid>& source3,
  const vtkSmartPointer<vtkUnstructuredGrid>& target3, const Result& base)
{
  int failures = 0;
  vtkIdType valid = 0;
  auto split = SplitEveryOtherCell(source3);
  const Result r = Project(target3, split);
  const double d = Difference(r, base, "Smooth");
  std::cout << "3D duplicate points: " << r.Pieces << " pieces (" << base.Pieces
            << " before), linear error " << LinearError3D(r, &valid) << ", conservation error "
            << ConservationError(target3, r, split) << ", max change " << d << std::endl;
  MP_CHECK(!r.Error && r.Warnings.empty() && r.Pieces == base.Pieces);
  MP_CHECK(d >= 0 && d < 1e-13);
  MP_CHECK(LinearError3D(r, &valid) < 1e-12 && valid == target3->GetNumberOfPoints());
  MP_CHECK(ConservationError(target3, r, split) < 1e-13);
  return failures == 0;
}

/// Threads (NumberOfThreads, the filter's own STDThread scope) on sample pair `pair`: the same
/// pieces and values as one thread; the application's backend is left as it was.
bool CheckThreads(const char* pair)
{
  int failures = 0;
  auto s = mptest::ReadSample(std::string(pair) + "_source.vtu");
  auto t = mptest::ReadSample(std::string(pair) + "_target.vtu");
  const std::string backend = vtkSMPTools::GetBackend();
  const Result one = Project(t, s, 1);
  const Result two = Project(t, s, 2);
  MP_CHECK(vtkSMPTools::GetBackend() == backend);
  MP_CHECK(one.Pieces == two.Pieces && !two.Error);
  const double d = Difference(one, two, "Smooth");
  std::cout << pair << " on 2 threads: " << two.Pieces << " pieces, max change " << d << std::endl;
  MP_CHECK(d >= 0 && d < 1e-13);
  return failures == 0;
}

/// Sample pair `pair` moved: scaling changes nothing but the scale, and a
/// translation by 10^6 only what rounding the translated input itself does
/// (coordinates near 10^6 carry ~1e-10 absolute, cells are ~0.04 wide).
bool CheckMovedMeshes(const char* pair)
{
  int failures = 0;
  auto s = mptest::ReadSample(std::string(pair) + "_source.vtu");
  auto t = mptest::ReadSample(std::string(pair) + "_target.vtu");
  const Result base = Project(t, s);
  for (double factor : { 1e-6, 1e6 })
  {
    auto scale = [factor](double* x) {
      for (int d = 0; d < 3; ++d)
        x[d] *= factor;
    };
    const Result r = Project(Mapped(t, scale), Mapped(s, scale));
    MP_CHECK(!r.Error && r.Pieces == base.Pieces);
    const double d = Difference(r, base, "Smooth");
    std::cout << pair << " scaled by " << factor << ": " << r.Pieces << " pieces, max change " << d
              << std::endl;
    MP_CHECK(d >= 0 && d < 1e-12);
    MP_CHECK(std::fabs(Difference(r, base, "Linear")) < 1e-11);
  }
  auto shift = [](double* x) {
    x[0] += 1e6;
    x[1] -= 1e6;
    x[2] += 1e6;
  };
  const Result r = Project(Mapped(t, shift), Mapped(s, shift));
  const double d = Difference(r, base, "Smooth");
  std::cout << pair << " translated by 1e6: " << r.Pieces << " pieces (" << base.Pieces
            << " before), max change " << d << std::endl;
  MP_CHECK(!r.Error && r.Pieces == base.Pieces);
  MP_CHECK(d >= 0 && d < 1e-8);
  return failures == 0;
}

} // namespace

int TestMeshProjectionFilterRobustness(int, char*[])
{
  int failures = 0;
  auto source = mptest::ReadSample("lshape_source.vtu");
  auto target = mptest::ReadSample("lshape_target.vtu");
  const Result plain = Project(target, source);
  MP_CHECK(!plain.Error && plain.Warnings.empty());

  MP_CASE(CheckSourceGhostCells(source, target));
  MP_CASE(CheckTargetGhostCell(source, target));
  MP_CASE(CheckTargetGhostRegion(source, target));
  MP_CASE(CheckDuplicatePoints(source, target, plain));
  MP_CASE(CheckUnusedTargetPoints(source, target, plain));
  MP_CASE(CheckZeroAreaCell(source, target, plain));
  MP_CASE(CheckInvertedTriangles(source, target, plain));
  MP_CASE(CheckEmptyInput(source));
  MP_CASE(CheckSourceWithoutPointArrays(source, target));
  for (const char* only : { vtkDataSetAttributes::GhostArrayName(), "vtkValidPointMask" })
  {
    MP_CASE(CheckOnlyArrayNotProjected(source, target, only));
  }
  MP_CASE(CheckFoldedSource(source, target));

  // 3D: zero-volume and inverted tetrahedra, duplicate points, each compared with the plain run.
  auto source3 = mptest::ReadSample("lshape3d_source.vtu");
  auto target3 = mptest::ReadSample("lshape3d_target.vtu");
  const Result base = Project(target3, source3);
  MP_CHECK(!base.Error && base.Warnings.empty());
  vtkIdType valid = 0;
  MP_CHECK(LinearError3D(base, &valid) < 1e-12 && valid == target3->GetNumberOfPoints());
  MP_CASE(CheckZeroVolumeTetrahedra(source3, target3, base));
  MP_CASE(CheckInvertedTetrahedra(source3, target3, base));
  MP_CASE(CheckDuplicatePoints3D(source3, target3, base));

  for (const char* pair : { "lshape", "lshape3d" })
  {
    MP_CASE(CheckThreads(pair));
  }
  for (const char* pair : { "lshape", "lshape3d" })
  {
    MP_CASE(CheckMovedMeshes(pair));
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
