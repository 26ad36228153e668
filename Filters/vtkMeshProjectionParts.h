// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMeshProjectionParts.h
 * @brief What a distributed run of vtkMeshProjectionFilter asks of the
 *        processes (not public, not wrapped).
 *
 * vtkPMeshProjectionFilter gives the serial filter one of these while it
 * runs on several processes; the serial filter calls it at fixed points of
 * every execution, so that the local machinery (search, pieces, local
 * blocks) runs unchanged on each process's part of Input and the Source
 * cells that part needs, and the solve is one global system. Every method
 * is collective: all processes call it, in the same order.
 */
#ifndef vtkMeshProjectionParts_h
#define vtkMeshProjectionParts_h

#include "Transfer/BlockCG.h" // SolverHooks

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <functional>
#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
class Parts
{
public:
  virtual ~Parts() = default;
  virtual int Rank() const = 0;
  virtual int Size() const = 0;

  /**
   * The Source cells this process needs: every non-ghost Source cell, from
   * any process, whose bounding box meets a box of this process's Input
   * cells grown by `reach` times the cell's size (surfaces meet within a
   * reach), merged by their points' global ids (the Source's GlobalIds, or
   * ids made from each process's numbering) into one grid whose points are
   * in the order of those ids, which it carries as GlobalIds. Only the
   * arrays every process's Source has are kept.
   */
  virtual vtkSmartPointer<vtkDataSet> GatherSource(
    vtkDataSet* source, vtkDataObject* input, double reach, std::string& error) = 0;

  /**
   * Empty when no process failed, else the reason of the first process that
   * did (its own words on that process, "... on process k" elsewhere).
   * With `flag`: the flag ANDed over the processes.
   */
  virtual std::string Agree(const std::string& why, bool* flag = nullptr) = 0;
  /// Element-wise OR over the processes.
  virtual void Or(std::vector<char>& flags) = 0;
  /// Sums over the processes, in place.
  virtual void Sum(double* values, int count) = 0;
  /// The union over the processes (sorted).
  virtual std::vector<unsigned int> Union(const std::vector<unsigned int>& values) = 0;
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
   * their coordinates) and returns the dataset with global point ids (its
   * own, or made: each point numbered by the lowest process that has it).
   */
  virtual vtkSmartPointer<vtkDataSet> ShareTarget(vtkDataSet* target) = 0;
  /**
   * The solver's hooks for the last shared dataset: for its points (P1; row
   * f of the system is point dataSetPoint(f)): shared rows summed over the
   * processes, each row counted by the lowest process that has it; for its
   * cells (P0): sums only. They stay valid until the next ShareTarget.
   */
  virtual mp::SolverHooks Hooks(
    bool points, mp::Index rows, const std::function<vtkIdType(mp::Index)>& dataSetPoint) = 0;
  /// Bytes this process sent (Source cells, shared rows) since it was made.
  virtual double SentBytes() const = 0;
};
} // namespace mpvtk

#endif
