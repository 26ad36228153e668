// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MPIParts.h
 * @brief The processes of an MPI run, as the filter asks of them (Parts.h):
 *        installed by vtkPMeshProjectionFilter while it runs on several
 *        processes (not public, not wrapped).
 *
 * Each process holds a part of Input and a part of Source. The collectives
 * (Agree, Or, Sum, Union, SumByKey, AllToAll, Swap: MPIParts.cxx) are the
 * only way the processes meet; on them rest the three things that make
 * the parts one projection:
 *  - GatherSource (SourceGather.cxx): each process gets the Source cells
 *    its part of Input needs, from all processes, as one grid;
 *  - ShareTarget, Hooks, Complete (SharedPoints.cxx): the points a process
 *    shares with others, and the solver's sums over them, so that the
 *    solve is one global system and a shared point has one value, bit for
 *    bit, everywhere;
 *  - SolveGathered (GatheredSolve.cxx): the solver's fallback, the whole
 *    system solved on process 0.
 *
 * Every collective is called by all processes in the same order; a
 * process's failure reaches the others through Agree, never by one
 * process leaving a collective the others wait in.
 */
#ifndef MeshProjection_Parallel_MPIParts_h
#define MeshProjection_Parallel_MPIParts_h

#include "Parallel/Boxes.h"
#include "Parallel/Marshal.h"
#include "Parallel/Parts.h"

#include "Transfer/CsrMatrix.h"

#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

class vtkDataSet;
class vtkMPICommunicator;
class vtkMultiProcessController;

namespace mpvtk
{
/**
 * What ShareTarget learnt of a dataset's points (SharedTarget::Points):
 * per neighbour (ascending ranks) the points shared with it, in an order
 * both agree on; per point the lowest process that has it (Owner), its
 * first copy here (Representative: points of one process at one place, or
 * with one global id, as a ghost cells generator may leave them, are one
 * point; RowSharing::Copies holds the rows of those with copies) and its
 * global identity (its GlobalIds value, given or made).
 */
struct PointSharing
{
  std::vector<int> Neighbours;
  std::vector<std::vector<vtkIdType>> Shared;
  std::vector<int> Owner;
  std::vector<vtkIdType> Representative;
  std::vector<long long> GlobalOf;
};

class MPIParts final : public Parts
{
public:
  /// `controller` runs on MPI (its communicator is a vtkMPICommunicator).
  explicit MPIParts(vtkMultiProcessController* controller);
  int Rank() const override { return this->Me; }
  int Size() const override { return this->N; }
  double SentBytes() const override { return this->Sent; }
  vtkMultiProcessController* Controller() const { return this->C; }
  /// Source cells this process received in the last GatherSource (its own included).
  vtkIdType Received = 0;

  // The collectives (MPIParts.cxx).
  Verdict Agree(const Verdict& mine, bool* flag = nullptr) override;
  void Abandon(const std::string& why) override;
  void Or(std::vector<char>& flags) override;
  void Sum(double* values, int count) override;
  void Minimum(double* values, int count) override;
  std::vector<unsigned int> Union(const std::vector<unsigned int>& values) override;
  std::vector<double> UnionOfValues(const std::vector<double>& values) override;
  /// Each entry is summed on the process its key hashes to, which answers
  /// every entry: the sums are the same, bit for bit, on any run.
  std::vector<double> SumByKey(
    const std::vector<long long>& keys, int width, const std::vector<double>& values) override;
  /// Every process sends out[r] to process r; returns what each sent here
  /// (out[Rank()] is moved there). Messages of any size (cut below MPI's
  /// int counts).
  std::vector<std::vector<char>> AllToAll(std::vector<std::vector<char>>& out);
  /// Sends send[k] to ranks[k] and receives recv[k] (sizes known) from it:
  /// between neighbours only, each pair calling it alike.
  void Swap(const std::vector<int>& ranks, std::vector<std::vector<double>>& send,
    std::vector<std::vector<double>>& recv);
  /// Every process's box (`mine` here), by rank.
  std::vector<Box> GatherBoxes(const Box& mine);
  /**
   * Which rows this process shares with each other process, in an order
   * both agree on (the lower process asks): to each higher process r this
   * process sends the keys (`keyBytes` each, written by `key`) of the rows
   * `asks(r)` lists (rows it may share with r: e.g. inside r's box); r
   * answers which it has (`find`: its row of a key, or -1). Returns, per
   * process, the rows shared with it, in the order asked.
   */
  std::vector<std::vector<mp::Index>> MatchRows(size_t keyBytes,
    const std::function<std::vector<mp::Index>(int)>& asks,
    const std::function<void(mp::Index, char*)>& key,
    const std::function<mp::Index(const char*)>& find);

  /// See Parts::GatherSource (SourceGather.cxx).
  vtkSmartPointer<vtkDataSet> GatherSource(vtkDataSet* source, vtkDataObject* input, double reach,
    bool neighborLayer, std::string& error, JoinedFields& joined) override;

  // The shared points (SharedPoints.cxx).
  SharedTarget ShareTarget(vtkDataSet* target) override;
  mp::SolverHooks Hooks(const SharedTarget& shared, bool points, mp::Index rows,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) override;
  /// The fringe's halo of a shared dataset (TargetHalo.cxx): see Parts::Halo.
  mp::FringeHalo Halo(const SharedTarget& shared, const mp::MeshView& target,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) override;

  /**
   * The rows of a distributed system as its hooks see them: which rows
   * this process shares with which others, which it counts, and each row's
   * global id. One for the target's points (Hooks), one for the fringe's
   * extended rows (Halo).
   */
  struct RowSharing
  {
    std::vector<int> Neighbours; ///< ascending ranks
    std::vector<std::vector<mp::Index>>
      Rows; ///< per neighbour, the rows shared with it, in an order both agree on
    std::vector<mp::Index> SharedRows; ///< distinct, ascending
    std::vector<std::vector<mp::Index>>
      Copies; ///< rows of one point, ascending, first the rows' representative
    std::vector<char> Counted;
    std::vector<long long> RowGlobal;
  };
  /// The hooks' Exchange: completes the shared rows of v (rows x width) with
  /// the parts' sum, in the order of their processes (the same value
  /// everywhere, bit for bit), or with their minimum.
  void Complete(const RowSharing& rows, double* v, int width, bool minimum);

private:
  // ShareTarget's steps (SharedPoints.cxx).
  /// Each point's identity (its global id, or its coordinates x) and its
  /// Representative in `points`: the first point of this process with that
  /// identity. (`index`: each identity's first point.)
  using PointIndex = std::unordered_map<PointKey, vtkIdType, PointKeyHash>;
  static std::vector<PointKey> KeyPoints(vtkDataSet* target, const std::vector<double>& x,
    bool useIds, PointIndex& index, PointSharing& points);
  /// Per process, the points this process shares with it, in an order
  /// both agree on (MatchRows among the points inside the other's bounds).
  std::vector<std::vector<vtkIdType>> FindShared(const std::vector<double>& x, const Box& bounds,
    const std::vector<PointKey>& keys, const PointIndex& index, size_t width,
    const PointSharing& points);
  /// Neighbours, Shared and Owner of `points` from the points shared per process.
  void SetNeighbours(
    const std::vector<std::vector<vtkIdType>>& shared, vtkIdType count, PointSharing& points);
  /// Global ids made (no usable GlobalIds on some process), into
  /// points.GlobalOf: each process numbers the points it owns after those
  /// of the processes before it; the others learn them from their owner.
  /// (Not given to the dataset: its cells other than simplices are split
  /// by its own point ids, as the serial run splits them, not by these,
  /// whose order at a border between pieces is not the serial one.)
  void NumberPoints(vtkIdType count, PointSharing& points);
  /// The rows of the system over a shared dataset's points (row f: point dataSetPoint(f)).
  std::shared_ptr<RowSharing> PointRows(const PointSharing& points, mp::Index rows,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) const;

  /// The hooks' Direct: the system's parts gathered on process 0, solved
  /// there, each process's rows sent back (GatheredSolve.cxx).
  bool SolveGathered(const RowSharing& rows, const mp::CsrMatrix& A, const double* B, double* X,
    int c, const std::vector<char>& converged);
  /// The hooks (sums, exchanges, the direct fallback) over `rows`, which they hold.
  mp::SolverHooks HooksOver(std::shared_ptr<const RowSharing> rows);
  // The halo's steps (TargetHalo.cxx).
  /// The other processes' cells within `reach` of this part's box, with
  /// their points, as ghost cells and points of `halo` (`boxes`: every
  /// process's box of its points; `points`: this part's rows); per ghost
  /// point, its global id.
  std::vector<long long> ReceiveHaloCells(const mp::MeshView& target, const RowSharing& points,
    const std::vector<Box>& boxes, double reach, mp::FringeHalo& halo);
  /// The extended rows' sharing, found by global ids among the rows
  /// inside each other process's box grown by `reach`.
  std::shared_ptr<RowSharing> ShareHaloRows(const mp::MeshView& target, const RowSharing& points,
    const mp::FringeHalo& halo, const std::vector<long long>& ghostIds,
    const std::vector<Box>& boxes, double reach);

  vtkMultiProcessController* C;
  vtkMPICommunicator* Mpi;
  int Me;
  int N;
  double Sent = 0;
};
} // namespace mpvtk

#endif
