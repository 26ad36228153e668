// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/SourceSide.h"

#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"

#include "Parallel/Parts.h"
#include "Projection/Composite.h"
#include "Projection/Fingerprint.h"
#include "Projection/Labels.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/Shape.h"
#include "Projection/Statistics.h"

namespace mpvtk
{
bool SourceSide::AnyTransfer(const Settings& settings) const
{
  return (this->Fields[PointArrays].Any() && settings.PointDataTarget != 0) ||
    (this->Fields[CellArrays].Any() && settings.CellDataTarget != 0);
}

namespace
{
/// Hands PieceArrays.h's decision to the fields' stage, which says its
/// warnings for the arrays selected (SourceFields.h): the fields with a
/// hole, the warnings by name (the blocks' first, then the processes').
void KeepJoined(const JoinedFields& joined, SourceSide& side)
{
  for (int association = 0; association < 2; ++association)
  {
    GatheredFields& g = side.Fields[association];
    g.Holes.insert(joined.Holes[association].begin(), joined.Holes[association].end());
    for (const auto& warning : joined.Warnings[association])
    {
      g.PieceWarnings.push_back(warning);
    }
  }
}
} // namespace

Verdict PrepareSourceMesh(vtkDataObject* sourceObject, vtkDataObject* input,
  const Settings& settings, vtkDataArraySelection* const selections[2], Parts& parts,
  Messages& messages, Statistics& stats, SourceSide& side)
{
  std::string note;
  std::string failed;
  JoinedFields blocks; // fields that differ between a composite's blocks
  vtkSmartPointer<vtkDataSet> source;
  const Verdict appended = Guarded("Reading Source", [&]() {
    source = AppendedSource(sourceObject, note, failed, blocks);
    return Verdict();
  });
  if (!appended.Ok())
  {
    failed = appended.Why; // (agreed in the gathering)
  }
  if (!note.empty())
  {
    messages.WarnOnce("note/" + note, note); // once, not at every step
  }
  if (failed.empty() && !source)
  {
    failed = std::string("Source is a ") + sourceObject->GetClassName() +
      ": a dataset or a composite dataset is needed.";
  }
  // On several processes, the labels of this process's piece before it
  // gathers (every process then knows the whole Source's labels: Labels.h).
  if (!parts.Whole())
  {
    ListPieceLabels(source, selections, settings, side.Fields);
  }
  // Each process gets the Source cells its part of Input needs, from all.
  const double reach = input && settings.SurfaceReach > 0 ? settings.SurfaceReach : 0.0;
  // (With a reconstruction of cell data or tangent arrays, and the cells around them.)
  JoinedFields pieces; // fields that differ between the processes' pieces
  // (Decided on the pieces, which make the whole Source, not on what each gathers.)
  ShareCurvedUnrefinable(
    parts, failed.empty() ? source : nullptr, settings.CurvedCellSubdivision, side.Mesh);
  source =
    parts.GatherSource(source, input, reach, settings.GathersNeighborLayer(), failed, pieces);
  KeepJoined(blocks, side);
  KeepJoined(pieces, side);
  if (!failed.empty())
  {
    return Verdict::Fail(failed);
  }
  side.Data = source;
  side.Composite = vtkCompositeDataSet::SafeDownCast(sourceObject) != nullptr;
  side.Mesh.SetOrdering(settings.Renumbering);
  side.Mesh.SetCurvedLevel(settings.CurvedCellSubdivision);
  const Verdict wrapped = parts.Agree(Guarded("Checking Source", [&]() {
    const std::string why = side.Mesh.Wrap(source, "Source");
    stats.Check += side.Mesh.CheckSeconds();
    stats.Renumber += side.Mesh.OrderSeconds();
    return why.empty() ? Verdict() : Verdict::Fail(why);
  }));
  if (!wrapped.Ok())
  {
    return wrapped;
  }
  WarnLeftOut(side.Mesh, "Source", messages);
  if (side.Mesh.Dimension() == 2 && !side.Mesh.View().IsSurfaceMesh())
  {
    // A planar Source in its own plane's coordinates until a leaf picks the
    // frame both meshes share: its cells' areas (extensive densities) are
    // then true areas in any plane, not those of its shadow on z = 0.
    side.Mesh.UseFrame(side.Mesh.OwnPlane());
  }
  Fingerprint print;
  print.Add(side.Mesh);
  side.Print = print.Hash;
  return Verdict();
}
} // namespace mpvtk
