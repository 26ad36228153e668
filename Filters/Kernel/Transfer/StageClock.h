// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file StageClock.h
 * @brief The clock of MortarOperator's timings (OperatorTimings): wall-clock
 *        seconds since a stage began.
 *
 * One helper for the files the operator's stages live in (MortarOperator.cxx,
 * MortarBuild.cxx, MortarSession.h, MortarApply.cxx), so that they all time
 * their stages the same way: std::chrono::steady_clock, which never goes
 * back when the system's clock is set.
 */
#ifndef MeshProjection_Kernel_StageClock_h
#define MeshProjection_Kernel_StageClock_h

#include <chrono>

namespace mp
{
/// Wall-clock seconds from `since` to now (steady_clock).
inline double SecondsSince(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}
} // namespace mp

#endif
