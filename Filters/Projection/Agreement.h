// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Agreement.h
 * @brief The rounds in which the processes agree while projecting one leaf,
 *        by name.
 *
 * On several processes every process takes part in each round, in order:
 * Shape (whether the leaf is a surface: any process's parts out of one
 * plane), Build (whether every process can reuse its kept operators),
 * Solve (whether every process built its operators and
 * their target mass) and Solved (whether
 * every process's solves and extrapolation went through, before the
 * outputs' sums: a solve's sums are collective, so a failed solve fails
 * alike everywhere, and this round makes that an agreement with the same
 * reason on every process rather than a coincidence). A process that fails
 * or stops before a round still takes part in the rounds left, with its
 * verdict, and then acts on what the first of them agreed: the same on
 * every process (a stop here and a failure on a lower process in the same
 * round is that failure everywhere, and the other way round a stop), so
 * that all go on or end alike. The steps between rounds that involve this
 * process alone run through Local, which turns their exceptions into
 * failures agreed in the next round. On one process every round is the
 * identity.
 */
#ifndef MeshProjection_Projection_Agreement_h
#define MeshProjection_Projection_Agreement_h

#include "Parallel/Parts.h"

namespace mpvtk
{
class LeafAgreement
{
public:
  enum Round
  {
    Shape = 0,
    Build = 1,
    Solve = 2,
    Solved = 3,
    Rounds = 4
  };

  explicit LeafAgreement(Parts& parts)
    : P(parts)
  {}

  /// Round `round` (the next one): this process goes on; `flag` is ANDed over the processes.
  Verdict At(Round round, bool* flag = nullptr)
  {
    this->Next = static_cast<int>(round) + 1;
    return this->P.Agree(Verdict(), flag);
  }

  /**
   * This process ends the leaf with `mine`: takes part in the rounds left
   * with it and returns what the first of them agreed (`mine` when none is
   * left, or when `agreed` says `mine` came out of a round already).
   */
  Verdict End(const Verdict& mine, bool agreed = false)
  {
    Verdict outcome = mine;
    for (; this->Next < Rounds; ++this->Next)
    {
      const Verdict first = this->P.Agree(mine);
      if (!agreed)
      {
        outcome = first.Ok() ? mine : first;
        agreed = true;
      }
    }
    return outcome;
  }

  /**
   * A step of this process alone before the next round (no collective
   * inside but the rounds it takes part in), run Guarded: a failure or a
   * stop it returns, or an exception it throws, ends the leaf here (End:
   * the rounds left, whose first gives every process the same verdict).
   * A step that ended the leaf itself keeps that verdict.
   */
  template <class Step>
  Verdict Local(const std::string& what, const Step& step)
  {
    const Verdict mine = Guarded(what, step);
    return mine.Ok() ? mine : this->End(mine);
  }

private:
  Parts& P;
  int Next = 0;
};
} // namespace mpvtk

#endif
