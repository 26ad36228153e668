// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceGather.cxx
 * @brief MPIParts::GatherSource: each process gets, from all processes, the
 *        Source cells its part of Input needs, as one grid (Parts.h states
 *        the contract).
 *
 * The steps, each a function below, in the order they run:
 *  0. the datasets are checked (a corrupt one is an error on every process,
 *     not a read out of its arrays) and the processes agree;
 *  1. this process's part of Input is seen from afar: a Cover, a grid of
 *     bins over its bounds, each with the box of the grown cells' parts in
 *     it (finer than one bounding box, so that an L-shaped part does not
 *     ask for the Source cells in its notch);
 *  2. every process's Cover goes to every process;
 *  3. the processes agree on the fields they project (PieceArrays.h's
 *     rule over the processes with Source cells: one missing on some is
 *     kept with NaN there, one that differs is left out, each said), and
 *     on global ids for the Source's points;
 *  4. each Source cell goes, as a small grid of its own (a piece), to
 *     every process whose Cover it meets (with the neighbour layer, also
 *     to those whose Cover it meets grown by the LayerMargins);
 *  5. the pieces received are merged into one grid, points by global id.
 * Then the processes agree on the gathering's own failure.
 */
#include "Parallel/MPIParts.h"

#include "Parallel/CellCopier.h"
#include "Adapter/CompositeLeaves.h"
#include "Adapter/DataSetChecks.h"
#include "Adapter/FieldArrays.h"
#include "Adapter/Ghosts.h"
#include "Adapter/PieceArrays.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace mpvtk
{
namespace
{
/// The box of a cell's points.
Box CellBox(vtkDataSet* data, vtkIdType c, vtkIdList* ids)
{
  Box b = EmptyBox();
  data->GetCellPoints(c, ids);
  double x[3];
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
  {
    data->GetPoint(ids->GetId(k), x);
    Grow(b, x);
  }
  return b;
}

/**
 * The boxes of a dataset's cells: straight from an unstructured grid's cell
 * array and double points (no id list, no virtual call per point), else
 * through vtkDataSet's calls. One cell at a time, on one thread.
 */
class CellBoxes
{
public:
  explicit CellBoxes(vtkDataSet* data)
    : Data(data)
    , Grid(vtkUnstructuredGrid::SafeDownCast(data))
  {
    vtkPoints* points = this->Grid ? this->Grid->GetPoints() : nullptr;
    vtkDoubleArray* x = points ? vtkDoubleArray::SafeDownCast(points->GetData()) : nullptr;
    this->X =
      x && x->GetNumberOfComponents() == 3 && this->Grid->GetCells() ? x->GetPointer(0) : nullptr;
  }
  Box operator()(vtkIdType c)
  {
    if (!this->X)
    {
      return CellBox(this->Data, c, this->Ids);
    }
    Box b = EmptyBox();
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    this->Grid->GetCellPoints(c, npts, pts);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      Grow(b, this->X + 3 * pts[k]);
    }
    return b;
  }

private:
  vtkDataSet* Data;
  vtkUnstructuredGrid* Grid;
  const double* X = nullptr;
  vtkNew<vtkIdList> Ids;
};

/// The fields of Source the processes agreed on (PieceArrays.h), and its points' ids.
struct SourceFields
{
  /// This process's arrays of Source's points (0) and cells (1) that are
  /// kept, in the Source's order.
  std::vector<vtkDataArray*> Arrays[2];
  /// The rule's decision over the processes with Source cells.
  JoinedFields Joined;
  /// Per Source point, its global id.
  std::vector<long long> Key;
};

// 0. ---------------------------------------------------------------------------
/// The first failure of CheckDataSet on Source, then on Input's datasets
/// (empty when all are fine).
std::string CheckParts(vtkDataSet* source, vtkDataObject* input)
{
  std::string failed = CheckDataSet(source, "Source");
  for (vtkDataSet* leaf : DataSetsOf(input))
  {
    if (!failed.empty())
    {
      break;
    }
    failed = CheckDataSet(leaf, "Input");
  }
  return failed;
}

// 1. ---------------------------------------------------------------------------
/// The boxes of the cells of this process's part of Input (not those left
/// out: ghosts, empty cells), each grown by `reach` times its size (and a
/// hair more, so that cells that touch meet after rounding).
std::vector<Box> GrownCellBoxes(vtkDataObject* input, double reach)
{
  std::vector<Box> cells;
  for (vtkDataSet* leaf : DataSetsOf(input))
  {
    vtkUnsignedCharArray* ghosts = leaf->GetCellGhostArray();
    CellBoxes boxOf(leaf);
    for (vtkIdType c = 0; c < leaf->GetNumberOfCells(); ++c)
    {
      if (IsLeftOutGhost(ghosts, c) || leaf->GetCellType(c) == VTK_EMPTY_CELL)
      {
        continue;
      }
      Box b = boxOf(c);
      double size = 0;
      for (int d = 0; d < 3; ++d)
      {
        size = std::max(size, b[2 * d + 1] - b[2 * d]);
      }
      const double grow = reach * size + 1e-9 * size;
      for (int d = 0; d < 3; ++d)
      {
        b[2 * d] -= grow;
        b[2 * d + 1] += grow;
      }
      cells.push_back(b);
    }
  }
  return cells;
}

/// Adds the parts of box b inside the bins it reaches to those bins' boxes
/// (the bins tile the cover's bounds; the outer ones reach to infinity).
void AddToBins(Cover& cover, const Box& b)
{
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
  {
    cover.Range(d, b[2 * d], b[2 * d + 1], lo[d], hi[d]);
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        // The cell's part inside the bin (bins tile the bounds).
        const int at[3] = { i, j, k };
        Box part = b;
        for (int d = 0; d < 3; ++d)
        {
          const double a = cover.Bounds[2 * d];
          const double w = (cover.Bounds[2 * d + 1] - a) / cover.Bins[d];
          if (cover.Bins[d] > 1)
          {
            part[2 * d] = std::max(part[2 * d], at[d] == 0 ? -HUGE_VAL : a + w * at[d]);
            part[2 * d + 1] = std::min(
              part[2 * d + 1], at[d] == cover.Bins[d] - 1 ? HUGE_VAL : a + w * (at[d] + 1));
          }
        }
        Unite(cover.Boxes[(k * cover.Bins[1] + j) * cover.Bins[0] + i], part);
      }
    }
  }
}

/// The cover of the cells' boxes: 16 bins along each axis the bounds have
/// a width on (none without cells).
Cover CoverOf(const std::vector<Box>& cells)
{
  Cover cover;
  for (const Box& b : cells)
  {
    Unite(cover.Bounds, b);
  }
  if (cells.empty())
  {
    return cover;
  }
  for (int d = 0; d < 3; ++d)
  {
    cover.Bins[d] = cover.Bounds[2 * d + 1] > cover.Bounds[2 * d] ? 16 : 1;
  }
  cover.Boxes.assign(
    static_cast<size_t>(cover.Bins[0]) * cover.Bins[1] * cover.Bins[2], EmptyBox());
  for (const Box& b : cells)
  {
    AddToBins(cover, b);
  }
  return cover;
}

// 2. ---------------------------------------------------------------------------
/// Every process's cover, to every process (by rank).
std::vector<Cover> ShareCovers(MPIParts& parts, const Cover& mine)
{
  const int n = parts.Size();
  std::vector<Cover> covers(static_cast<size_t>(n));
  std::vector<char> packed;
  std::vector<double> head(mine.Bounds.begin(), mine.Bounds.end());
  for (int d = 0; d < 3; ++d)
  {
    head.push_back(mine.Bins[d]);
  }
  Append(packed, head.data(), head.size());
  for (const Box& b : mine.Boxes)
  {
    Append(packed, b.data(), 6);
  }
  std::vector<std::vector<char>> out(static_cast<size_t>(n), packed);
  std::vector<std::vector<char>> in = parts.AllToAll(out);
  for (int r = 0; r < n; ++r)
  {
    const std::vector<double> v = Read<double>(in[r]);
    if (v.size() < 9)
    {
      continue;
    }
    std::copy(v.begin(), v.begin() + 6, covers[r].Bounds.begin());
    for (int d = 0; d < 3; ++d)
    {
      covers[r].Bins[d] = static_cast<int>(v[6 + d]);
    }
    for (size_t at = 9; at + 6 <= v.size(); at += 6)
    {
      Box b;
      std::copy(v.begin() + at, v.begin() + at + 6, b.begin());
      covers[r].Boxes.push_back(b);
    }
  }
  return covers;
}

// 3. ---------------------------------------------------------------------------
/// What this process tells the others of its Source: whether it has cells,
/// whether its GlobalIds are usable (or it has no cells: then it does not
/// stand in the way), then one line per field (FieldsOfPiece: association,
/// type, components, name).
std::string FieldsText(vtkDataSet* source)
{
  vtkDataArray* global = source->GetPointData()->GetGlobalIds();
  const bool has = source->GetNumberOfCells() > 0;
  const bool usable = global && global->GetNumberOfComponents() == 1 &&
    global->GetNumberOfTuples() >= source->GetNumberOfPoints();
  std::string text = has ? "1" : "0";
  text += usable || !has ? "1\n" : "0\n";
  for (const PieceField& f : FieldsOfPiece(source))
  {
    text += std::to_string(f.Association) + "\t" + std::to_string(f.Type) + "\t" +
      std::to_string(f.Components) + "\t" + f.Name + "\n";
  }
  return text;
}

/// The fields of one FieldsText.
std::vector<PieceField> ReadFields(const std::string& t)
{
  std::vector<PieceField> fields;
  size_t at = t.find('\n') + 1;
  while (at > 0 && at < t.size())
  {
    const size_t end = t.find('\n', at);
    const std::string line = t.substr(at, end - at);
    const size_t a = line.find('\t');
    const size_t b = line.find('\t', a + 1);
    const size_t c = line.find('\t', b + 1);
    fields.push_back({ std::stoi(line.substr(0, a)), line.substr(c + 1),
      std::stoi(line.substr(a + 1, b - a - 1)), std::stoi(line.substr(b + 1, c - b - 1)) });
    at = end + 1;
  }
  return fields;
}

/// From every process's FieldsText: the rule (PieceArrays.h) over the
/// processes with Source cells (into `joined`), and whether all their
/// GlobalIds are usable.
bool ReadFieldsTexts(const std::vector<std::vector<char>>& texts, JoinedFields& joined)
{
  bool ownIds = true;
  std::vector<std::vector<PieceField>> pieces;
  std::vector<std::string> names;
  for (size_t r = 0; r < texts.size(); ++r)
  {
    const std::string t(texts[r].begin(), texts[r].end());
    if (t.size() < 2 || t[0] != '1')
    {
      ownIds = ownIds && (t.size() < 2 || t[1] == '1');
      continue;
    }
    ownIds = ownIds && t[1] == '1';
    pieces.push_back(ReadFields(t));
    names.push_back("process " + std::to_string(r));
  }
  joined = JoinPieceFields(pieces, names, "pieces");
  return ownIds;
}

/// The fields kept over the processes' Source (those with cells:
/// PieceArrays.h's rule); global ids of the Source's points: its own when
/// every process has them, else each process's numbering after those of
/// the processes before it.
SourceFields AgreeOnFields(MPIParts& parts, vtkDataSet* source)
{
  const int n = parts.Size();
  const vtkIdType np = source->GetNumberOfPoints();
  SourceFields fields;
  const std::string text = FieldsText(source);
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (int r = 0; r < n; ++r)
  {
    Append(out[r], text.data(), text.size());
  }
  std::vector<long long> counts(static_cast<size_t>(n));
  const long long mineCount = static_cast<long long>(np);
  parts.Controller()->AllGather(&mineCount, counts.data(), 1);
  long long offset = 0;
  for (int r = 0; r < parts.Rank(); ++r)
  {
    offset += counts[r];
  }
  const bool ownIds = ReadFieldsTexts(parts.AllToAll(out), fields.Joined);
  fields.Key.resize(static_cast<size_t>(np));
  vtkDataArray* global = source->GetPointData()->GetGlobalIds();
  for (vtkIdType p = 0; p < np; ++p)
  {
    fields.Key[p] = ownIds && global ? static_cast<long long>(global->GetTuple1(p)) : offset + p;
  }
  for (int a = 0; a < 2; ++a)
  {
    vtkDataSetAttributes* attributes = AttributesOf(source, a);
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* array = attributes->GetArray(i);
      if (array && array->GetName() && IsField(attributes, array) &&
        fields.Joined.Kept[a].count(array->GetName()))
      {
        fields.Arrays[a].push_back(array);
      }
    }
  }
  return fields;
}

// 4. ---------------------------------------------------------------------------
/// Calls f(c, box of c) for each Source cell c not left out (ghosts, empty cells).
template <class F>
void ForEachCellBox(vtkDataSet* source, const F& f)
{
  vtkUnsignedCharArray* ghosts = source->GetCellGhostArray();
  CellBoxes boxOf(source);
  for (vtkIdType c = 0; c < source->GetNumberOfCells(); ++c)
  {
    if (!IsLeftOutGhost(ghosts, c) && source->GetCellType(c) != VTK_EMPTY_CELL)
    {
      f(c, boxOf(c));
    }
  }
}

/// The largest extent of box b on any axis.
double SizeOf(const Box& b)
{
  return std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
}

/// Box b grown by `margin` on every side.
Box GrownBy(Box b, double margin)
{
  for (int d = 0; d < 3; ++d)
  {
    b[2 * d] -= margin;
    b[2 * d + 1] += margin;
  }
  return b;
}

/**
 * The neighbour layer's reach, two rings deep (a reconstruction may fit a
 * corner cell's gradient to the cells around its neighbours): per process
 * r, the margin m1 + m2, m1 the largest size (SizeOf) of the Source cells,
 * on any process, whose boxes meet r's Cover, m2 the largest size of those
 * meeting the Cover grown by m1 (0 when there is no layer; collective). A
 * cell N sharing a point x with such a cell C has x within C's box, whose
 * distance to the Cover is at most C's size per axis: N's box grown by m1
 * meets the Cover; a cell sharing a point with N lies within m1 + m2 of it.
 */
std::vector<double> LayerMargins(
  MPIParts& parts, vtkDataSet* source, const std::vector<Cover>& covers, bool layer)
{
  std::vector<double> margins(covers.size(), 0.0);
  if (!layer)
  {
    return margins;
  }
  for (int ring = 0; ring < 2; ++ring)
  {
    std::vector<double> mine(covers.size(), 0.0);
    ForEachCellBox(source, [&](vtkIdType, const Box& b) {
      for (size_t r = 0; r < covers.size(); ++r)
      {
        if (covers[r].Meets(margins[r] > 0.0 ? GrownBy(b, margins[r]) : b))
        {
          mine[r] = std::max(mine[r], SizeOf(b));
        }
      }
    });
    std::vector<double> largest(covers.size(), 0.0);
    parts.Controller()->AllReduce(
      mine.data(), largest.data(), static_cast<vtkIdType>(mine.size()), vtkCommunicator::MAX_OP);
    for (size_t r = 0; r < covers.size(); ++r)
    {
      margins[r] += largest[r] * (1 + 1e-9); // (cells that touch meet after rounding)
    }
  }
  return margins;
}

/// Per process, the Source cells (not left out) whose boxes meet its cover
/// (grown by its margin, LayerMargins).
std::vector<std::vector<vtkIdType>> CellsFor(
  vtkDataSet* source, const std::vector<Cover>& covers, const std::vector<double>& margins)
{
  std::vector<std::vector<vtkIdType>> toSend(covers.size());
  ForEachCellBox(source, [&](vtkIdType c, const Box& b) {
    for (size_t r = 0; r < covers.size(); ++r)
    {
      if (covers[r].Meets(margins[r] > 0.0 ? GrownBy(b, margins[r]) : b))
      {
        toSend[r].push_back(c);
      }
    }
  });
  return toSend;
}

/// Copies the tuples `from` of each array to new arrays of `to` (the same
/// names, types and component names).
void CopyTuples(const std::vector<vtkDataArray*>& arrays, const std::vector<vtkIdType>& from,
  vtkDataSetAttributes* to)
{
  for (vtkDataArray* array : arrays)
  {
    vtkSmartPointer<vtkDataArray> copy;
    copy.TakeReference(array->NewInstance());
    copy->SetName(array->GetName());
    copy->SetNumberOfComponents(array->GetNumberOfComponents());
    for (int k = 0; k < array->GetNumberOfComponents(); ++k)
    {
      if (array->GetComponentName(k))
      {
        copy->SetComponentName(k, array->GetComponentName(k));
      }
    }
    copy->SetNumberOfTuples(static_cast<vtkIdType>(from.size()));
    for (size_t i = 0; i < from.size(); ++i)
    {
      copy->SetTuple(static_cast<vtkIdType>(i), from[i], array);
    }
    to->AddArray(copy);
  }
}

/// The Source cells `cells` as a grid of their own: double points (in the
/// order the cells first use them), their global ids (as
/// vtkMeshProjectionGlobalIds), the agreed fields.
vtkSmartPointer<vtkUnstructuredGrid> PieceOf(
  vtkDataSet* source, const std::vector<vtkIdType>& cells, const SourceFields& fields)
{
  vtkNew<vtkUnstructuredGrid> piece;
  std::vector<vtkIdType> local(static_cast<size_t>(source->GetNumberOfPoints()), -1);
  std::vector<vtkIdType> points;
  auto idOf = [&](vtkIdType p) {
    vtkIdType& id = local[static_cast<size_t>(p)];
    if (id < 0)
    {
      id = static_cast<vtkIdType>(points.size());
      points.push_back(p);
    }
    return id;
  };
  bool polyhedra = false;
  for (vtkIdType c : cells)
  {
    polyhedra = polyhedra || source->GetCellType(c) == VTK_POLYHEDRON;
  }
  CellCopier copier(piece, polyhedra, static_cast<vtkIdType>(cells.size()));
  for (vtkIdType c : cells)
  {
    copier.Add(source, c, idOf);
  }
  copier.Finish();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  xyz->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  vtkNew<vtkIdTypeArray> global;
  global->SetName("vtkMeshProjectionGlobalIds");
  global->SetNumberOfValues(static_cast<vtkIdType>(points.size()));
  double x[3];
  for (size_t i = 0; i < points.size(); ++i)
  {
    source->GetPoint(points[i], x);
    xyz->SetPoint(static_cast<vtkIdType>(i), x);
    global->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(fields.Key[points[i]]));
  }
  piece->SetPoints(xyz);
  piece->GetPointData()->AddArray(global);
  CopyTuples(fields.Arrays[0], points, piece->GetPointData());
  CopyTuples(fields.Arrays[1], cells, piece->GetCellData());
  return vtkSmartPointer<vtkUnstructuredGrid>(piece.GetPointer());
}

/// Each process's piece to it; returns the pieces received, by process
/// (this process's own without marshalling). A piece that cannot be
/// packed or read sets `error` (the exchange still runs: the others wait
/// in it).
std::vector<vtkSmartPointer<vtkUnstructuredGrid>> ExchangePieces(MPIParts& parts,
  vtkDataSet* source, const std::vector<std::vector<vtkIdType>>& toSend, const SourceFields& fields,
  std::string& error)
{
  const int n = parts.Size();
  const int me = parts.Rank();
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  vtkSmartPointer<vtkUnstructuredGrid> own;
  for (int r = 0; r < n; ++r)
  {
    if (toSend[r].empty())
    {
      continue;
    }
    vtkSmartPointer<vtkUnstructuredGrid> piece = PieceOf(source, toSend[r], fields);
    if (r == me)
    {
      own = piece;
      continue;
    }
    vtkNew<vtkCharArray> bytes;
    if (!vtkCommunicator::MarshalDataObject(piece, bytes))
    {
      error = "the Source cells for process " + std::to_string(r) + " could not be packed";
    }
    Append(out[r], bytes->GetPointer(0), static_cast<size_t>(bytes->GetNumberOfValues()));
  }
  std::vector<std::vector<char>> in = parts.AllToAll(out);
  std::vector<vtkSmartPointer<vtkUnstructuredGrid>> pieces;
  for (int r = 0; r < n; ++r)
  {
    if (r == me)
    {
      if (own)
      {
        pieces.push_back(own);
      }
      continue;
    }
    if (in[r].empty())
    {
      continue;
    }
    vtkNew<vtkCharArray> bytes;
    bytes->SetArray(in[r].data(), static_cast<vtkIdType>(in[r].size()), 1);
    vtkNew<vtkUnstructuredGrid> piece;
    if (!vtkCommunicator::UnMarshalDataObject(bytes, piece))
    {
      error = "the Source cells from process " + std::to_string(r) + " could not be read";
      continue;
    }
    pieces.push_back(piece.GetPointer());
  }
  return pieces;
}

// 5. ---------------------------------------------------------------------------
/// The pieces as one grid, being made: its points merged by global id.
struct Merged
{
  vtkSmartPointer<vtkUnstructuredGrid> Grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  /// Per piece, per point: its point in Grid.
  std::vector<std::vector<vtkIdType>> NewId;
  vtkIdType Points = 0;
  vtkIdType Cells = 0;
};

/// Sets the merged points, one per global id in the order of the ids, with
/// those ids (returned, for GlobalIds). False when a piece came without ids.
bool MergePoints(const std::vector<vtkSmartPointer<vtkUnstructuredGrid>>& pieces, Merged& merged,
  vtkIdTypeArray* globalIds)
{
  std::vector<std::pair<long long, std::pair<size_t, vtkIdType>>> all;
  merged.NewId.resize(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    vtkDataArray* global = pieces[i]->GetPointData()->GetArray("vtkMeshProjectionGlobalIds");
    if (!global || global->GetNumberOfTuples() != pieces[i]->GetNumberOfPoints())
    {
      return false;
    }
    for (vtkIdType p = 0; p < pieces[i]->GetNumberOfPoints(); ++p)
    {
      all.push_back({ static_cast<long long>(global->GetTuple1(p)), { i, p } });
    }
    merged.NewId[i].resize(static_cast<size_t>(pieces[i]->GetNumberOfPoints()));
    merged.Cells += pieces[i]->GetNumberOfCells();
  }
  std::sort(all.begin(), all.end());
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  std::vector<std::pair<size_t, vtkIdType>> firstOf; // per merged point
  for (size_t k = 0; k < all.size(); ++k)
  {
    if (k == 0 || all[k].first != all[k - 1].first)
    {
      firstOf.push_back(all[k].second);
      globalIds->InsertNextValue(static_cast<vtkIdType>(all[k].first));
    }
    merged.NewId[all[k].second.first][all[k].second.second] =
      static_cast<vtkIdType>(firstOf.size() - 1);
  }
  xyz->SetNumberOfPoints(static_cast<vtkIdType>(firstOf.size()));
  for (size_t p = 0; p < firstOf.size(); ++p)
  {
    xyz->SetPoint(static_cast<vtkIdType>(p),
      pieces[firstOf[p].first]->GetPoints()->GetPoint(firstOf[p].second));
  }
  merged.Grid->SetPoints(xyz);
  merged.Points = static_cast<vtkIdType>(firstOf.size());
  return true;
}

/// Appends the pieces' cells, in the order of the pieces, to the merged grid.
void MergeCells(const std::vector<vtkSmartPointer<vtkUnstructuredGrid>>& pieces, Merged& merged)
{
  bool polyhedra = false;
  for (const auto& piece : pieces)
  {
    vtkUnsignedCharArray* types = piece->GetCellTypesArray();
    const unsigned char* t = types ? types->GetPointer(0) : nullptr;
    for (vtkIdType c = 0; t && c < types->GetNumberOfValues(); ++c)
    {
      polyhedra = polyhedra || t[c] == VTK_POLYHEDRON;
    }
  }
  CellCopier copier(merged.Grid, polyhedra, merged.Cells);
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    const std::vector<vtkIdType>& to = merged.NewId[i];
    for (vtkIdType c = 0; c < pieces[i]->GetNumberOfCells(); ++c)
    {
      copier.Add(pieces[i], c, [&to](vtkIdType p) { return to[p]; });
    }
  }
  copier.Finish();
}

/// The merged array of one kept field (a = 0: points, 1: cells), in its
/// joined type; NaN where a piece came without it when it has a `hole`,
/// else null when one did.
vtkSmartPointer<vtkDataArray> MergedArray(
  const std::vector<vtkSmartPointer<vtkUnstructuredGrid>>& pieces, const Merged& merged, int a,
  const PieceField& field, bool hole)
{
  const char* name = field.Name.c_str();
  vtkSmartPointer<vtkDataArray> array;
  array.TakeReference(vtkDataArray::CreateDataArray(field.Type));
  array->SetName(name);
  array->SetNumberOfComponents(field.Components);
  array->SetNumberOfTuples(a == 0 ? merged.Points : merged.Cells);
  if (hole)
  {
    // A point shared with a piece that has the field takes its value (the
    // pieces without it leave theirs as NaN).
    array->Fill(std::numeric_limits<double>::quiet_NaN());
  }
  vtkIdType at = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    vtkDataArray* from = mpvtk::AttributesOf(pieces[i], a)->GetArray(name);
    const vtkIdType count = a == 0 ? pieces[i]->GetNumberOfPoints() : pieces[i]->GetNumberOfCells();
    if (!from && !hole)
    {
      return nullptr;
    }
    for (vtkIdType k = 0; from && k < count; ++k)
    {
      array->SetTuple(a == 0 ? merged.NewId[i][k] : at + k, k, from);
    }
    at += a == 0 ? 0 : count;
  }
  return array;
}

/// Adds `array` to `to` with the component names and the active attributes
/// (scalars, vectors) that the Source's `own` gives its field of that name.
void AddLikeSource(vtkDataSetAttributes* to, vtkDataArray* array, vtkDataSetAttributes* own)
{
  const std::string name = array->GetName();
  if (vtkDataArray* original = own->GetArray(name.c_str()))
  {
    for (int k = 0; k < array->GetNumberOfComponents() && k < original->GetNumberOfComponents();
         ++k)
    {
      if (original->GetComponentName(k))
      {
        array->SetComponentName(k, original->GetComponentName(k));
      }
    }
  }
  to->AddArray(array);
  if (own->GetScalars() && own->GetScalars()->GetName() && name == own->GetScalars()->GetName())
  {
    to->SetActiveScalars(name.c_str());
  }
  if (own->GetVectors() && own->GetVectors()->GetName() && name == own->GetVectors()->GetName())
  {
    to->SetActiveVectors(name.c_str());
  }
}

/// The kept fields on the merged grid, in their joined types, by name;
/// `error` when a piece came without one that has no hole.
void MergeFields(const std::vector<vtkSmartPointer<vtkUnstructuredGrid>>& pieces,
  vtkDataSet* source, const SourceFields& fields, Merged& merged, std::string& error)
{
  for (int a = 0; a < 2; ++a)
  {
    const int association = a == 0 ? vtkDataObject::POINT : vtkDataObject::CELL;
    for (const auto& kept : fields.Joined.Kept[a])
    {
      vtkSmartPointer<vtkDataArray> array =
        MergedArray(pieces, merged, a, kept.second, fields.Joined.Holes[a].count(kept.first) > 0);
      if (!array)
      {
        error = "Source array '" + kept.first + "' is missing from the cells of a process";
        return;
      }
      AddLikeSource(
        merged.Grid->GetAttributes(association), array, source->GetAttributes(association));
    }
  }
}

/// Steps 1 to 5: the gathered Source (null with `error` on this process's
/// failure; the caller agrees on it).
vtkSmartPointer<vtkDataSet> Gather(MPIParts& parts, vtkDataSet* source, vtkDataObject* input,
  double reach, bool layer, std::string& error, JoinedFields& joined)
{
  const std::vector<Cover> covers = ShareCovers(parts, CoverOf(GrownCellBoxes(input, reach)));
  const SourceFields fields = AgreeOnFields(parts, source);
  joined = fields.Joined;
  const std::vector<double> margins = LayerMargins(parts, source, covers, layer);
  const std::vector<vtkSmartPointer<vtkUnstructuredGrid>> pieces =
    ExchangePieces(parts, source, CellsFor(source, covers, margins), fields, error);
  Merged merged;
  vtkNew<vtkIdTypeArray> globalIds;
  globalIds->SetName("GlobalIds");
  if (!MergePoints(pieces, merged, globalIds))
  {
    error = "Source cells arrived without their points' global ids";
    return nullptr;
  }
  MergeCells(pieces, merged);
  parts.Received = merged.Cells;
  MergeFields(pieces, source, fields, merged, error);
  if (!error.empty())
  {
    return nullptr;
  }
  merged.Grid->GetPointData()->SetGlobalIds(globalIds);
  return merged.Grid;
}
} // namespace

vtkSmartPointer<vtkDataSet> MPIParts::GatherSource(vtkDataSet* source, vtkDataObject* input,
  double reach, bool neighborLayer, std::string& error, JoinedFields& joined)
{
  // The checks run before any cell is read, and all processes learn of a
  // failure on any of them before the gathering's exchanges start.
  const Verdict checked = error.empty() ? Guarded("Checking the datasets",
                                            [&]() {
                                              const std::string why = CheckParts(source, input);
                                              return why.empty() ? Verdict() : Verdict::Fail(why);
                                            })
                                        : Verdict::Fail(error);
  Verdict all = this->Agree(checked);
  if (!all.Ok())
  {
    error = all.Message();
    return nullptr;
  }
  vtkSmartPointer<vtkDataSet> gathered =
    Gather(*this, source, input, reach, neighborLayer, error, joined);
  all = this->Agree(error.empty() ? Verdict() : Verdict::Fail(error));
  if (!all.Ok())
  {
    error = all.Message();
    return nullptr;
  }
  return gathered;
}
} // namespace mpvtk
