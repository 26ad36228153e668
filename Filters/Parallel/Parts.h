// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Parts.h
 * @brief The seam between the filter and its processes: what an execution
 *        asks of them, with the serial answer as the default (not public,
 *        not wrapped).
 *
 * vtkMeshProjectionFilter always runs through a Parts. On one process it is
 * SerialParts: every collective is the identity (this process is all of
 * them), so the serial code reads as the distributed one without a branch.
 * vtkPMeshProjectionFilter installs MPIParts (Parallel/MPIParts.h) while it
 * runs on several processes: the local machinery (search, pieces, local
 * blocks) then runs unchanged on each process's part of Input and the
 * Source cells that part needs, and the solve is one global system.
 *
 * Every method but the queries is collective: all processes call it, in the
 * same order.
 */
#ifndef MeshProjection_Parallel_Parts_h
#define MeshProjection_Parallel_Parts_h

#include "Adapter/PieceArrays.h"     // JoinedFields
#include "Transfer/BlockCG.h"        // SolverHooks
#include "Transfer/MortarOperator.h" // FringeHalo

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <algorithm>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
/// How a step of an execution ended, on this process or, once agreed, on all.
enum class Outcome
{
  Done,   ///< went through
  Failed, ///< an error: the reason says why
  Stopped ///< the user's abort: the output is Input as it came
};

/// An outcome with its reason (empty when Done).
struct Verdict
{
  Outcome What = Outcome::Done;
  std::string Why;
  /// On several processes, once agreed (Parts::Agree): the process it came
  /// from. -1: not agreed yet, or one process.
  int Process = -1;

  static Verdict Fail(const std::string& why) { return { Outcome::Failed, why }; }
  static Verdict Stop() { return { Outcome::Stopped, "stopped" }; }
  bool Ok() const { return this->What == Outcome::Done; }
  /// What the user reads: the reason, and, once agreed on several
  /// processes, the process it came from (the same text on every process).
  std::string Message() const
  {
    return this->Process < 0 ? this->Why
                             : this->Why + " (on process " + std::to_string(this->Process) + ")";
  }
};

/**
 * Runs `step`, a step of this process alone (no collective inside: nothing
 * another process waits in), and returns its verdict; an exception it
 * throws becomes this process's failure, naming `what` and the exception,
 * instead of leaving the execution (and, on several processes, the others
 * waiting in the next collective). The caller then takes it to the next
 * agreement like any failure (Parts::Agree, LeafAgreement::Local).
 */
template <class Step>
Verdict Guarded(const std::string& what, const Step& step)
{
  try
  {
    return step();
  }
  catch (const std::exception& e)
  {
    return Verdict::Fail(what + " failed: " + e.what());
  }
  catch (...)
  {
    return Verdict::Fail(what + " failed: an exception of unknown type.");
  }
}

struct PointSharing;

/**
 * A dataset of Input as the processes share it (Parts::ShareTarget): the
 * dataset, and on several processes what the
 * processes learnt of its points (which this process shares with which
 * others, who owns each, their global ids; MPIParts reads it). The leaf's hooks and its halo
 * are made from this value (Parts::Hooks, Parts::Halo). Serial: the
 * dataset alone.
 */
struct SharedTarget
{
  vtkSmartPointer<vtkDataSet> Data;
  std::shared_ptr<const PointSharing> Points; ///< null on one process
};

class Parts
{
public:
  virtual ~Parts() = default;
  virtual int Rank() const = 0;
  virtual int Size() const = 0;
  /**
   * Whether this process sees the whole meshes (one process). Where it does
   * not, a part may be empty without anything being wrong, a Source cell's
   * covered measure is spread over processes, and a stop must wait for the
   * next agreement (all processes stop together).
   */
  bool Whole() const { return this->Size() == 1; }

  /**
   * The Source this process projects from. `error` comes in with this
   * process's failure so far (empty when none) and goes out with the first
   * process's failure, the same on every process (null is returned then).
   * Serial: `source` itself. On several processes: first every process
   * checks Source and Input's datasets (ids and offsets, as the wraps would:
   * a corrupt dataset is an error on every process, not a read out of its
   * arrays) and they agree; then it returns every non-ghost Source cell,
   * from any process, whose bounding box meets a box of this process's
   * Input cells grown by `reach` times the cell's size (surfaces meet within
   * a reach), merged by their points' global ids (the Source's GlobalIds, or
   * ids made from each process's numbering) into one grid whose points are
   * in the order of those ids, which it carries as GlobalIds. The fields
   * follow PieceArrays.h's rule over the processes with Source cells (one
   * missing on some processes is kept, NaN there; one that differs is
   * left out): `joined` says which, with the warnings (the same on every
   * process; serial: nothing).
   * With `neighborLayer`, also every cell that shares a point with such a
   * cell, and the cells around those (the neighbours a reconstruction of
   * cell data fits its gradients to: CellReconstruction.h).
   */
  virtual vtkSmartPointer<vtkDataSet> GatherSource(vtkDataSet* source, vtkDataObject* input,
    double reach, bool neighborLayer, std::string& error, JoinedFields& joined) = 0;

  /**
   * The verdict of the lowest process whose verdict is not Done, the same
   * on every process (its Process set to that process, unless it came
   * from an earlier agreement already), else Done. With `flag`: the flag
   * ANDed over the processes. The one place where a process's failure
   * reaches the others: every failure before a collective goes through it.
   */
  virtual Verdict Agree(const Verdict& mine, bool* flag = nullptr) = 0;
  /**
   * Ends the execution on every process after an exception in a step with
   * collectives inside (the other processes may be waiting in one, where no
   * agreement reaches them): says `why` on this process and aborts the run
   * (MPI_Abort). Serial: returns (the caller reports a failure).
   */
  virtual void Abandon(const std::string& why) = 0;
  /// Element-wise OR over the processes.
  virtual void Or(std::vector<char>& flags) = 0;
  /// Sums over the processes, in place.
  virtual void Sum(double* values, int count) = 0;
  /// Smallest values over the processes, in place.
  virtual void Minimum(double* values, int count) = 0;
  /// Largest values over the processes, in place (the smallest of the negatives).
  void Maximum(double* values, int count)
  {
    for (int i = 0; i < count; ++i)
    {
      values[i] = -values[i];
    }
    this->Minimum(values, count);
    for (int i = 0; i < count; ++i)
    {
      values[i] = -values[i];
    }
  }
  /// The union over the processes (sorted, without repeats).
  virtual std::vector<unsigned int> Union(const std::vector<unsigned int>& values) = 0;
  /// The union over the processes of values that are not NaN (sorted, without repeats): labels.
  virtual std::vector<double> UnionOfValues(const std::vector<double>& values) = 0;
  /**
   * Entry i of this process is keyed by keys[width * i ... width * i +
   * width - 1] with value values[i]; returns, per entry, the sum of the
   * values of all entries with that key on all processes (collective: every
   * process calls it, with the same width, entries or not).
   */
  virtual std::vector<double> SumByKey(
    const std::vector<long long>& keys, int width, const std::vector<double>& values) = 0;

  /**
   * Per dataset of Input: finds the points this process shares with others
   * (by the GlobalIds point array when every process has one, else by
   * their coordinates) and their global ids (its own, or made: each point
   * numbered by the lowest process that has it; SharedTarget::Points).
   * The dataset is `target` itself (cells other than simplices split by
   * its GlobalIds when it has them, else by its point ids, as in serial).
   * Serial: `target` itself.
   */
  virtual SharedTarget ShareTarget(vtkDataSet* target) = 0;
  /**
   * The solver's hooks for the shared dataset `shared`: for its points (P1;
   * row f of the system is point dataSetPoint(f)): shared rows summed over
   * the processes, each row counted by the lowest process that has it; for
   * its cells (P0): sums only. The hooks hold what they need (copies share
   * it). Serial: no hooks (the solver's own sums).
   */
  virtual mp::SolverHooks Hooks(const SharedTarget& shared, bool points, mp::Index rows,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) = 0;
  /**
   * The fringe's halo (MortarOperator::AggregateFringe) of the shared
   * dataset `shared`: `target` is its kernel mesh, its rows numbered as
   * for Hooks (row f is point dataSetPoint(f)). The cells of other
   * processes' parts within FringeSearchRings rings of this part's points, with their
   * points, and the hooks over the extended rows. Serial: no halo (no hooks).
   */
  virtual mp::FringeHalo Halo(const SharedTarget& shared, const mp::MeshView& target,
    const std::function<vtkIdType(mp::Index)>& dataSetPoint) = 0;
  /// Bytes this process sent (Source cells, shared rows) since it was made.
  virtual double SentBytes() const = 0;
};

/// `values` without NaN, sorted, without repeats (UnionOfValues' one process).
inline std::vector<double> SortedValues(std::vector<double> values)
{
  values.erase(
    std::remove_if(values.begin(), values.end(), [](double v) { return v != v; }), values.end());
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

/// One process: every collective is the identity.
class SerialParts final : public Parts
{
public:
  int Rank() const override { return 0; }
  int Size() const override { return 1; }
  vtkSmartPointer<vtkDataSet> GatherSource(
    vtkDataSet* source, vtkDataObject*, double, bool, std::string& error, JoinedFields&) override;
  Verdict Agree(const Verdict& mine, bool*) override { return mine; }
  void Abandon(const std::string&) override {}
  void Or(std::vector<char>&) override {}
  void Sum(double*, int) override {}
  void Minimum(double*, int) override {}
  std::vector<unsigned int> Union(const std::vector<unsigned int>& values) override
  {
    std::vector<unsigned int> all(values);
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  }
  std::vector<double> UnionOfValues(const std::vector<double>& values) override
  {
    return SortedValues(values);
  }
  std::vector<double> SumByKey(
    const std::vector<long long>& keys, int width, const std::vector<double>& values) override;
  SharedTarget ShareTarget(vtkDataSet* target) override;
  mp::SolverHooks Hooks(
    const SharedTarget&, bool, mp::Index, const std::function<vtkIdType(mp::Index)>&) override
  {
    return mp::SolverHooks();
  }
  mp::FringeHalo Halo(
    const SharedTarget&, const mp::MeshView&, const std::function<vtkIdType(mp::Index)>&) override
  {
    return mp::FringeHalo();
  }
  double SentBytes() const override { return 0; }
};
} // namespace mpvtk

#endif
