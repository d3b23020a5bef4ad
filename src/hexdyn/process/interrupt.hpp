#pragma once
/// \file interrupt.hpp
/// SIGTERM and SIGINT (what Slurm sends at a time limit and on scancel, and Ctrl-C), and
/// every other signal whose default action ends the process and that is sent as a request
/// (SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGPIPE): every command ends cleanly on them,
/// with one line and exit status 128 + signal (docs/user/faults.md#signals).
///
/// Design, async-signal-safe throughout:
/// - a registry of the temporary files being written (publish_atomically registers
///   `.<name>.tmp.<pid>` before creating it and unregisters it after the rename or the
///   removal): fixed slots of fixed-size path buffers, published by a sig_atomic_t flag;
/// - the handler removes every registered temporary file (unlink(2)) and records the
///   signal in a sig_atomic_t;
/// - then either (`Mode::kExitInHandler`, for `run` and `envelope`, which keep nothing
///   between runs) it writes the command's preformatted line to stderr (write(2)) and
///   ends the process with _exit(128 + signal), or (`Mode::kPoll`, for a sweep's rank 0,
///   which must flush its checkpoint first) the program polls interrupted() between
///   scenarios and in the write path (check_interrupt()), flushes what it keeps, prints
///   its line and exits with 128 + signal.
/// A second signal while a kPoll program is stopping ends it at once (the registry is
/// already clean; the checkpoint journal is append-only and checksummed, so a cut record
/// is only recomputed on --resume).
#include <string>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

/// A handled signal arrived: thrown by check_interrupt(); exit status 128 + signal.
class Interrupted : public Error {
 public:
  explicit Interrupted(int signal);
  int exit_status() const override { return 128 + signal_; }
  int signal() const { return signal_; }

 private:
  int signal_;
};

enum class InterruptMode { kExitInHandler, kPoll };

/// `{signal}` in a handler's line: replaced by the signal's name ("SIGTERM", "SIGHUP", ...).
inline constexpr const char* kSignalPlaceholder = "{signal}";

/// Installs the handler of every handled signal (sigaction, SA_RESTART). `line` (up to 1000
/// bytes before and after kSignalPlaceholder; a newline added) is what kExitInHandler
/// writes before it exits. May be called again to change the line or the mode.
void install_interrupt_handlers(InterruptMode mode, const std::string& line);

/// Restores the default actions (a forked child that must die as a plain process).
void reset_interrupt_handlers_in_child();

/// The handled signal received, or 0.
int interrupted();

/// Throws Interrupted when a signal was received.
void check_interrupt();

/// "SIGTERM", "SIGINT", "SIGHUP", ... for the handled signals, else "signal N".
std::string signal_name(int signal);

/// While it lives, the handled signals other than SIGINT whose action is the default (not
/// ignored, not handled by the host program) remove the registered temporary files, write
/// `line` ({signal} replaced) and end the process with 128 + signal: what a library call
/// that publishes a file (Python's Result.write) promises in a host process whose signals
/// are otherwise its own. The dispositions are restored when it ends.
class FatalSignalScope {
 public:
  explicit FatalSignalScope(const std::string& line);
  ~FatalSignalScope();
  FatalSignalScope(const FatalSignalScope&) = delete;
  FatalSignalScope& operator=(const FatalSignalScope&) = delete;

 private:
  unsigned installed_ = 0;  ///< bit i: the i-th handled signal was installed here
};

/// Registers a temporary file that the handler removes; at most 16 at once, paths under
/// 4096 bytes (beyond that the path is not registered and only the ordinary cleanup
/// applies).
void register_temporary(const std::string& path);
/// Forgets a registered path (after it was renamed or removed).
void unregister_temporary(const std::string& path);

}  // namespace hexdyn
