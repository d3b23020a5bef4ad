#pragma once
/// \file cancel.hpp
/// Stopping a computation early from another thread (docs/user/faults.md#signals): Python's
/// hexdyn.run computes in a thread of its own and, on Ctrl-C, sets a flag that the stages
/// poll between samples (check_cancelled), so the run ends within one sample's work.
///
/// The flag is the computing thread's (thread_local), set by a CancelScope for the length
/// of the computation; a thread without one is never cancelled, and the poll costs one
/// thread-local read.
#include <atomic>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

/// Thrown by check_cancelled when the computation was asked to stop (exit status 130, as
/// SIGINT's).
class Cancelled : public Error {
 public:
  Cancelled() : Error("computation cancelled") {}
  int exit_status() const override { return 130; }
};

/// While it lives, check_cancelled() on this thread throws Cancelled once `*flag` is true.
/// Scopes nest (the inner one's flag counts until it ends).
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>* flag);
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

/// Throws Cancelled when this thread's CancelScope flag is set. Called by the stages between
/// samples: kinematics, dynamics, the refinement passes, the touchdowns and the posture search.
void check_cancelled();

}  // namespace hexdyn
