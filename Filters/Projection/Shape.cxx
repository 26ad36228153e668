// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Shape.h"

#include "vtkDataSet.h"

#include "Parallel/Parts.h"
#include "Projection/Agreement.h"
#include "Projection/Leaf.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/SimplexMesh.h"

#include "Mesh/PlaneFrame.h"
#include "Transfer/BernsteinForm.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace mpvtk
{
namespace
{
/// Input of a higher dimension than Source: refused (the same words on one process or several).
std::string HigherDimensionError(const std::string& role, int target, int source)
{
  return role + " is a " + std::to_string(target) + "D mesh but Source is " +
    std::to_string(source) +
    "D: values go to a mesh of the same dimension, or from a volume mesh (2D or 3D) to a surface "
    "or curve inside it (a trace), not to a mesh of a higher dimension.";
}

/**
 * 2D: sees both meshes in the frame of Input's plane (of Source's when
 * Input has no cells); a Source in a parallel plane is projected onto it,
 * with a `warning`. Returns an error when the planes are not parallel.
 */
std::string UseOnePlane(SimplexMesh& target, SimplexMesh& source, std::string& warning)
{
  const bool sourceOnly = target.View().NumberOfCells == 0;
  const mp::PlaneFrame& frame = sourceOnly ? source.OwnPlane() : target.OwnPlane();
  const mp::PlaneFrame& other = sourceOnly ? target.OwnPlane() : source.OwnPlane();
  std::ostringstream text;
  if (target.View().NumberOfCells > 0 && source.View().NumberOfCells > 0)
  {
    if (!frame.IsParallel(other))
    {
      const double* n = frame.GetNormal();
      const double* m = other.GetNormal();
      text << "Input and Source lie in planes that are not parallel (normals (" << n[0] << ", "
           << n[1] << ", " << n[2] << ") and (" << m[0] << ", " << m[1] << ", " << m[2]
           << ")): 2D meshes must lie in one plane.";
      return text.str();
    }
    if (std::fabs(frame.Offset() - other.Offset()) > std::max(frame.Tolerance(), other.Tolerance()))
    {
      if (frame.IsIdentity())
      {
        text << "Source lies in the plane z = " << source.OwnPlane().Offset()
             << ", Input in z = " << target.OwnPlane().Offset()
             << "; the meshes are compared in x and y only.";
      }
      else
      {
        text << "Source lies in a plane parallel to Input's, "
             << std::fabs(frame.Offset() - other.Offset())
             << " away; it is projected onto Input's plane.";
      }
      warning = text.str();
    }
  }
  target.UseFrame(frame);
  source.UseFrame(frame);
  return std::string();
}

/// What the serial filter decides from the whole meshes, decided from every process's parts.
std::string AgreeOnShape(Parts& parts, SimplexMesh& target, SimplexMesh& source,
  const std::string& role, bool& trace, bool& planar, bool& secondOrder)
{
  // Each process sees only its parts of the meshes. What the serial filter
  // decides from the whole meshes is decided here from every process's
  // parts, gathered (each process's values in its own slot of a sum):
  // - a trace (a surface or curve inside a volume): a process without
  //   Input or Source cells cannot tell one; it takes the others' word and
  //   their dimensions, so that every process makes the same outputs;
  // - a 2D leaf lies in one plane only when every process's parts of each
  //   mesh lie in one and the same plane (each process's may be flat in a
  //   plane of its own: separate sheets, split by blocks); else the leaf is
  //   a surface everywhere, as in the serial run;
  // - second-order Input cells on any process: every process then solves
  //   its point data alike (the solves and the fringe are collective).
  constexpr int PerMesh = 7; // has cells, dimension, normal, offset, tolerance
  constexpr int Width = 2 + 2 * PerMesh;
  const int size = parts.Size();
  std::vector<double> all(static_cast<size_t>(size) * Width, 0.0);
  double* mine = all.data() + static_cast<size_t>(parts.Rank()) * Width;
  SimplexMesh* meshes[2] = { &target, &source };
  mine[0] = trace ? 1.0 : 0.0;
  mine[Width - 1] = target.View().Nodal ? 1.0 : 0.0;
  for (int m = 0; m < 2; ++m)
  {
    double* at = mine + 1 + PerMesh * m;
    const mp::PlaneFrame& plane = meshes[m]->OwnPlane();
    at[0] = meshes[m]->View().NumberOfCells > 0 ? 1.0 : 0.0;
    at[1] = meshes[m]->Dimension();
    std::copy(plane.GetNormal(), plane.GetNormal() + 3, at + 2);
    at[5] = plane.Offset();
    at[6] = plane.Tolerance();
  }
  parts.Sum(all.data(), static_cast<int>(all.size()));
  bool anyTrace = false;
  int dimension[2] = { 0, 0 }; // of each mesh's cells, where a process has some
  for (int p = 0; p < size; ++p)
  {
    const double* at = all.data() + static_cast<size_t>(p) * Width;
    anyTrace = anyTrace || at[0] != 0.0;
    secondOrder = secondOrder || at[Width - 1] != 0.0;
    for (int m = 0; m < 2; ++m)
    {
      if (at[1 + PerMesh * m] != 0.0)
      {
        dimension[m] = std::max(dimension[m], static_cast<int>(at[2 + PerMesh * m]));
      }
    }
  }
  // A mesh without cells here takes the dimension its cells have elsewhere
  // (a curve leaf is one on every process, not a planar leaf where a
  // process has no cells).
  for (int m = 0; m < 2; ++m)
  {
    if (meshes[m]->View().NumberOfCells == 0 && dimension[m] > 0)
    {
      meshes[m]->SetDimension(dimension[m]);
    }
  }
  // (Of different dimensions where no process holds cells of both, e.g.
  // a surface entirely outside the volume: a trace too, as in serial.)
  const bool differ = dimension[0] > 0 && dimension[1] > 0 && dimension[0] != dimension[1];
  if ((anyTrace || differ) && !trace)
  {
    if (target.View().NumberOfCells > 0 && source.View().NumberOfCells > 0)
    {
      return role + " and Source have cells of the same dimension on process " +
        std::to_string(parts.Rank()) +
        " but not on others: each mesh's cells must be of one "
        "dimension on every process.";
    }
    if (dimension[0] > dimension[1])
    {
      return HigherDimensionError(role, dimension[0], dimension[1]);
    }
    trace = true;
    planar = true; // (as for a trace on one process: never a surface leaf)
  }
  if (trace || !planar || target.Dimension() != 2)
  {
    return std::string();
  }
  // Planes: the same when parallel (PlaneFrame's test) and within the
  // larger tolerance of each other.
  auto same = [](const double* a, const double* b) {
    const double* n = a + 2;
    const double* k = b + 2;
    if (!mp::PlaneFrame::AreParallel(n, k))
    {
      return false;
    }
    const bool flipped = n[0] * k[0] + n[1] * k[1] + n[2] * k[2] < 0.0;
    return std::fabs(a[5] - (flipped ? -b[5] : b[5])) <= std::max(a[6], b[6]);
  };
  for (int m = 0; m < 2 && planar; ++m)
  {
    const double* first = nullptr;
    for (int p = 0; p < size && planar; ++p)
    {
      const double* at = all.data() + static_cast<size_t>(p) * Width + 1 + PerMesh * m;
      if (at[0] == 0.0)
      {
        continue;
      }
      planar = first ? same(first, at) : true;
      first = first ? first : at;
    }
  }
  return std::string();
}

/// An empty mesh takes the dimension of the other one; says so on one process.
void DimensionOfEmpty(SimplexMesh& target, SimplexMesh& source, vtkDataSet* targetData,
  vtkDataSet* sourceData, const std::string& role, Parts& parts, Messages& messages)
{
  const vtkIdType targetCells = target.View().NumberOfCells;
  const vtkIdType sourceCells = source.View().NumberOfCells;
  vtkDataSet* empty = targetCells == 0 ? targetData : sourceData;
  // (On several processes a part may well be empty: not worth a warning.)
  if (parts.Whole())
  {
    messages.Warn((targetCells == 0 ? role : std::string("Source")) +
      (empty->GetNumberOfCells() == 0 ? " has no cells"
                                      : " has no cells to project with (all are ghost cells, or of "
                                        "a lower dimension)") +
      ": every projected point is invalid.");
  }
  int d = std::max(targetCells ? target.Dimension() : 0, sourceCells ? source.Dimension() : 0);
  d = d > 0 ? d : 2;
  target.SetDimension(d);
  if (sourceCells == 0)
  {
    source.SetDimension(d);
  }
}

/// Meshes of different dimensions: a surface or curve inside a volume (a trace), or an error.
std::string TraceOrError(
  const SimplexMesh& target, const SimplexMesh& source, const std::string& role)
{
  if (target.Dimension() > source.Dimension())
  {
    return HigherDimensionError(role, target.Dimension(), source.Dimension());
  }
  if (source.Surface())
  {
    return role +
      " is a curve but Source a surface in 3D: a curve takes values from curves, "
      "from a 2D mesh in its plane or from a 3D mesh, not from a curved surface.";
  }
  return std::string();
}

/// A trace's frames: a surface in space, or a curve in a planar Source's plane.
std::string UseTraceFrames(SimplexMesh& target, SimplexMesh& source, const std::string& role)
{
  if (target.Dimension() == 2)
  {
    target.UseAsSurface(); // its facets in space, planar or not
    return std::string();
  }
  if (source.Dimension() != 2)
  {
    return std::string();
  }
  // A curve in a planar Source: in the Source's plane.
  const mp::PlaneFrame& plane = source.OwnPlane();
  const mp::MeshView& curve = target.View();
  double off = 0.0;
  for (mp::Index p = 0; p < curve.NumberOfPoints; ++p)
  {
    off = std::max(off, std::fabs(plane.Distance(curve.Point(p))));
  }
  // (A process without Source cells has no plane of its own to check
  // against: on several processes the others check theirs.)
  if (source.View().NumberOfCells > 0 && !(off <= std::max(plane.Tolerance(), 1e-12)))
  {
    std::ostringstream why;
    why << role << " is a curve that leaves the plane of the 2D Source (by up to " << off
        << "): a curve takes values from a 2D mesh only in its plane.";
    return why.str();
  }
  target.UseFrameAsOwn(plane);
  source.UseFrame(plane);
  return std::string();
}

/// A curve, or a surface in 3D: both meshes as they are, facets meeting as the settings say.
std::string UseSurfaces(SimplexMesh& target, SimplexMesh& source, const Settings& settings)
{
  if (!std::isfinite(settings.SurfaceReach) || !std::isfinite(settings.MaximumNormalAngle))
  {
    return "SurfaceReach and MaximumNormalAngle must be numbers (they are " +
      std::to_string(settings.SurfaceReach) + " and " +
      std::to_string(settings.MaximumNormalAngle) + ").";
  }
  target.UseAsSurface();
  source.UseAsSurface();
  const double pi = 3.14159265358979323846;
  target.SetSurfaceContact(settings.SurfaceReach,
    std::cos(settings.MaximumNormalAngle * pi / 180.0), settings.NormalOrientation);
  return std::string();
}
} // namespace

void ShareCurvedUnrefinable(Parts& parts, vtkDataSet* data, int asked, SimplexMesh& mesh)
{
  if (asked <= 1 || parts.Whole())
  {
    return;
  }
  // (A collective sum: no exception may leave this process out of it; a
  // part that cannot be counted fails when it is wrapped, agreed.)
  double count = 0.0;
  try
  {
    count = static_cast<double>(SimplexMesh::CurvedUnrefinableCells(data));
  }
  catch (...)
  {
    count = 0.0;
  }
  parts.Sum(&count, 1);
  mesh.SetWholeCurvedUnrefinable(static_cast<vtkIdType>(count));
}

void WarnLeftOut(const SimplexMesh& mesh, const std::string& role, Messages& messages)
{
  if (mesh.UnrefinedCurvedCells() > 0)
  {
    messages.WarnOnce("unrefined/" + role,
      role + ": CurvedCellSubdivision is " + std::to_string(mesh.GetCurvedLevel()) + ", but " +
        std::to_string(mesh.UnrefinedCurvedCells()) +
        " curved cells are not split finer: hexahedra, wedges and pyramids are not (a mesh "
        "with curved ones keeps the split on its nodes throughout), and a cell whose finer "
        "split folds keeps the split on its nodes (slivers between it and refined neighbours "
        "count as uncovered or covered twice).");
  }
  if (mesh.LowerDimensionalCells() == 0)
  {
    return;
  }
  const int d = mesh.Dimension();
  messages.WarnOnce("lower/" + role, // once per filter, not per step
    role + ": " + std::to_string(mesh.LowerDimensionalCells()) +
      " cells of lower dimension than its " + std::to_string(d) + "D cells (vertices" +
      (d >= 2 ? ", lines" : "") + (d == 3 ? ", faces" : "") +
      ") are left out of the projection (their cell values are invalid).");
}

namespace
{
/// DecideShape's part on this process alone, up to and with the Shape round.
Verdict ShapeHere(LeafContext& ctx, LeafAgreement& agreement)
{
  SimplexMesh& target = ctx.Target;
  SimplexMesh& source = ctx.Source.Mesh;
  LeafShape& shape = ctx.Shape;
  const vtkIdType targetCells = target.View().NumberOfCells;
  const vtkIdType sourceCells = source.View().NumberOfCells;
  shape = LeafShape();
  if (targetCells == 0 || sourceCells == 0)
  {
    DimensionOfEmpty(
      target, source, ctx.TargetData, ctx.Source.Data, ctx.Role, ctx.Processes, ctx.Say);
  }
  else if (target.Dimension() != source.Dimension())
  {
    const std::string why = TraceOrError(target, source, ctx.Role);
    if (!why.empty())
    {
      return agreement.End(Verdict::Fail(why));
    }
    shape.Trace = true;
  }
  // A 2D leaf is a surface in 3D when either mesh leaves one plane; on
  // several processes when it does on any (a process whose parts happen to
  // be planar, e.g. one face of a box, projects as the serial run does).
  shape.Planar = shape.Trace || target.Dimension() != 2 || !(target.Surface() || source.Surface());
  const Verdict elsewhere = agreement.At(LeafAgreement::Shape, &shape.Planar);
  return elsewhere.Ok() ? elsewhere : agreement.End(elsewhere, true);
}

/// The meshes put in the frames of the agreed shape (this process alone).
std::string UseFrames(LeafContext& ctx)
{
  SimplexMesh& target = ctx.Target;
  SimplexMesh& source = ctx.Source.Mesh;
  LeafShape& shape = ctx.Shape;
  if (shape.Trace)
  {
    return UseTraceFrames(target, source, ctx.Role);
  }
  if (target.Dimension() == 1 || (target.Dimension() == 2 && !shape.Planar))
  {
    return UseSurfaces(target, source, ctx.Options);
  }
  return target.Dimension() == 2 ? UseOnePlane(target, source, shape.PlaneWarning) : std::string();
}
} // namespace

Verdict DecideShape(LeafContext& ctx, LeafAgreement& agreement)
{
  // The steps of this process alone run through agreement.Local (an
  // exception there is this process's failure, agreed at the next round);
  // the sums between them are collective, where every process is (an
  // exception inside one ends the run: the filter's Parts::Abandon).
  const Verdict here =
    agreement.Local("Deciding the shape", [&]() { return ShapeHere(ctx, agreement); });
  if (!here.Ok())
  {
    return here;
  }
  // The rest of what one process sees in the whole meshes (every process
  // here passed the round above; on one process nothing changes).
  const std::string why = AgreeOnShape(ctx.Processes, ctx.Target, ctx.Source.Mesh, ctx.Role,
    ctx.Shape.Trace, ctx.Shape.Planar, ctx.Shape.SecondOrder);
  if (!why.empty())
  {
    return agreement.End(Verdict::Fail(why));
  }
  if (ctx.Shape.SecondOrder)
  {
    // Whether some part has a signed form (serendipity cells, pyramids:
    // BernsteinForm.h), whose lumped and bounded values every process then
    // treats alike (ApplyOptions::Signed).
    bool unsigned_ = !mp::BernsteinForm::HasSigned(ctx.Target.View());
    ctx.Processes.Agree(Verdict(), &unsigned_);
    ctx.Shape.Signed = !unsigned_;
  }
  return agreement.Local("Deciding the shape", [&]() {
    if (ctx.Shape.SecondOrder)
    {
      ctx.Target.UseNodalSpace(); // (this part may have no second-order cell)
    }
    const std::string framed = UseFrames(ctx);
    return framed.empty() ? Verdict() : Verdict::Fail(framed);
  });
}
} // namespace mpvtk
