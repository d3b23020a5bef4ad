#include "hexdyn/sweep/scenario_process.hpp"

#include <malloc.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>

#include "hexdyn/core/bytes.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/interrupt.hpp"

namespace hexdyn {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kFrameHeader = 8 + 4 * 8 + 8;  // index, 4 timings, payload size

/// The scenario index that the test-only switch makes abort, if set.
std::optional<std::size_t> crash_switch() {
  const char* v = std::getenv("HEXDYN_TEST_CRASH_SCENARIO");
  if (v == nullptr || *v == '\0') return std::nullopt;
  char* end = nullptr;
  const unsigned long long k = std::strtoull(v, &end, 10);
  if (end == v || *end != '\0') return std::nullopt;
  return static_cast<std::size_t>(k);
}

/// Seconds the test-only switch HEXDYN_TEST_HOLD_SECONDS makes the process wait before each
/// scenario (0 when unset): a sweep that lasts on purpose, whatever the machine's speed, for
/// the tests that watch a sweep while it runs (tests/sweep/idle_ranks.sh).
double hold_switch() {
  const char* v = std::getenv("HEXDYN_TEST_HOLD_SECONDS");
  if (v == nullptr || *v == '\0') return 0.0;
  char* end = nullptr;
  const double s = std::strtod(v, &end);
  return end != v && *end == '\0' && s > 0.0 && s <= 3600.0 ? s : 0.0;
}

/// Sleeps `seconds`, resuming after a signal's interruption.
void hold(double seconds) {
  timespec left{static_cast<time_t>(seconds),
                static_cast<long>((seconds - std::floor(seconds)) * 1e9)};
  while (::nanosleep(&left, &left) != 0 && errno == EINTR) {
  }
}

/// Writes all bytes to a socket without SIGPIPE; false when the peer is gone.
bool send_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::send(fd, data, n, MSG_NOSIGNAL);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

bool read_exact(int fd, char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t r = ::read(fd, data, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    data += r;
    n -= static_cast<std::size_t>(r);
  }
  return true;
}

[[noreturn]] void child_main(const ScenarioFactory& factory, bool keep_runs,
                             const std::string& scratch, int in_fd, pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(0);
  // A crash kills the child as it would a plain process: no handler inherited from the
  // parent (MPI's backtrace printers, a test framework's, the SIGTERM and SIGINT handlers
  // of interrupt.hpp) runs in it.
  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);
  reset_interrupt_handlers_in_child();
  // No descriptor of the parent's stays open here: the checkpoint's lock (flock) is held
  // by its open file, so a child holding a copy would keep a killed sweep's lock until
  // the child died (docs/user/faults.md#orphans).
  if (in_fd > 3) ::close_range(3, static_cast<unsigned>(in_fd) - 1, 0);
  ::close_range(static_cast<unsigned>(in_fd) + 1, ~0u, 0);
  keep_freed_memory();
  const std::optional<std::size_t> crash_at = crash_switch();
  const double hold_s = hold_switch();
  std::vector<char> frame;
  for (;;) {
    std::uint64_t index = 0;
    if (!read_exact(in_fd, reinterpret_cast<char*>(&index), sizeof index)) ::_exit(0);
    if (crash_at && *crash_at == index) std::abort();  // test-only (HEXDYN_TEST_CRASH_SCENARIO)
    if (hold_s > 0.0) hold(hold_s);                    // test-only (HEXDYN_TEST_HOLD_SECONDS)
    const ScenarioEvent ev =
        compute_scenario(factory, static_cast<std::size_t>(index), keep_runs, scratch);
    frame.clear();
    put_pod(frame, index);
    for (double t : {ev.timing.config_s, ev.timing.physics_s, ev.timing.summary_s, ev.encode_s})
      put_pod(frame, t);
    put_pod(frame, static_cast<std::uint64_t>(ev.payload.size()));
    frame.insert(frame.end(), ev.payload.begin(), ev.payload.end());
    if (!send_all(in_fd, frame.data(), frame.size())) ::_exit(0);
  }
}

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::sigabbrev_np(sig);
    return "its process was killed by signal " + std::to_string(sig) +
           (name ? std::string(" (SIG") + name + ")" : std::string()) +
           (sig == SIGKILL ? ", as the out-of-memory killer does" : "");
  }
  if (WIFEXITED(status))
    return "its process exited with status " + std::to_string(WEXITSTATUS(status));
  return "its process ended";
}

}  // namespace

void keep_freed_memory() {
  ::mallopt(M_MMAP_THRESHOLD, 64 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

ScenarioEvent compute_scenario(const ScenarioFactory& factory, std::size_t index, bool keep_runs,
                               const std::string& scratch_dir) {
  ScenarioEvent ev;
  ev.index = index;
  ScenarioOutcome out = run_scenario(factory, index, keep_runs, &ev.timing);
  const auto t0 = Clock::now();
  ScenarioRecord record;
  try {
    if (out.run) record.run_image = encode_run_image(*out.run, scratch_dir);
    record.summary = std::move(out.summary);
  } catch (const std::exception& e) {
    record.summary = failed_summary(index, ScenarioStatus::kInternal,
                                    std::string("cannot keep its run: ") + e.what());
    record.run_image.clear();
  }
  ev.payload = encode_record(record);
  ev.encode_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return ev;
}

ScenarioProcess::ScenarioProcess(const ScenarioFactory& factory, bool keep_runs,
                                 std::string scratch_dir, bool isolate)
    : factory_(factory),
      keep_runs_(keep_runs),
      scratch_(std::move(scratch_dir)),
      isolate_(isolate) {}

ScenarioProcess::~ScenarioProcess() { stop_child(); }

void ScenarioProcess::start_child() {
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    throw Error(std::string("sweep: cannot create a socket pair for a scenario process: ") +
                std::strerror(errno));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(sv[0]);
    ::close(sv[1]);
    throw Error(std::string("sweep: cannot fork a scenario process: ") + std::strerror(err));
  }
  if (pid == 0) {
    ::close(sv[0]);
    child_main(factory_, keep_runs_, scratch_, sv[1], parent);
  }
  ::close(sv[1]);
  child_ = pid;
  to_child_ = from_child_ = sv[0];
  inbox_.clear();
  ++children_;
  std::vector<char> ids;
  for (std::size_t i : pending_) put_pod(ids, static_cast<std::uint64_t>(i));
  if (!ids.empty()) send_all(to_child_, ids.data(), ids.size());  // a dead child shows in wait()
}

void ScenarioProcess::stop_child() {
  if (child_ < 0) return;
  ::shutdown(to_child_, SHUT_RDWR);
  ::close(to_child_);
  to_child_ = from_child_ = -1;
  ::kill(child_, SIGKILL);  // it may be in the middle of a scenario nobody waits for
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = -1;
}

std::string ScenarioProcess::reap_child() {
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  ::close(to_child_);
  to_child_ = from_child_ = -1;
  child_ = -1;
  return describe_status(status);
}

void ScenarioProcess::submit(const std::vector<std::size_t>& indices) {
  if (indices.empty()) return;
  pending_.insert(pending_.end(), indices.begin(), indices.end());
  if (!isolate_) return;
  if (child_ < 0) {
    start_child();  // sends every pending index
    return;
  }
  std::vector<char> ids;
  for (std::size_t i : indices) put_pod(ids, static_cast<std::uint64_t>(i));
  send_all(to_child_, ids.data(), ids.size());
}

std::vector<ScenarioEvent> ScenarioProcess::read_frames() {
  std::vector<ScenarioEvent> events;
  std::size_t at = 0;
  while (inbox_.size() - at >= kFrameHeader) {
    const char* p = inbox_.data() + at;
    const auto size = get_pod<std::uint64_t>(p + 40);
    if (inbox_.size() - at - kFrameHeader < size) break;
    ScenarioEvent ev;
    ev.index = static_cast<std::size_t>(get_pod<std::uint64_t>(p));
    ev.timing = {get_pod<double>(p + 8), get_pod<double>(p + 16), get_pod<double>(p + 24)};
    ev.encode_s = get_pod<double>(p + 32);
    ev.payload.assign(p + kFrameHeader, p + kFrameHeader + size);
    at += kFrameHeader + static_cast<std::size_t>(size);
    if (pending_.empty() || pending_.front() != ev.index)
      throw Error("sweep: scenario process answered out of order");
    pending_.pop_front();
    events.push_back(std::move(ev));
  }
  inbox_.erase(inbox_.begin(), inbox_.begin() + static_cast<std::ptrdiff_t>(at));
  return events;
}

std::vector<ScenarioEvent> ScenarioProcess::wait(int timeout_ms) {
  std::vector<ScenarioEvent> events;
  if (pending_.empty()) return events;
  if (!isolate_) {
    const std::size_t i = pending_.front();
    pending_.pop_front();
    events.push_back(compute_scenario(factory_, i, keep_runs_, scratch_));
    return events;
  }
  if (child_ < 0) start_child();
  pollfd pfd{from_child_, POLLIN, 0};
  int rc = 0;
  do rc = ::poll(&pfd, 1, timeout_ms);
  while (rc < 0 && errno == EINTR);
  if (rc <= 0) return events;
  char buf[1 << 16];
  for (;;) {
    const ssize_t r = ::recv(from_child_, buf, sizeof buf, MSG_DONTWAIT);
    if (r > 0) {
      inbox_.insert(inbox_.end(), buf, buf + r);
      continue;
    }
    if (r < 0 && errno == EINTR) continue;
    if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    // End of file (or a reset): the child is gone. What it finished comes first.
    events = read_frames();
    ScenarioEvent crash;
    crash.crashed = true;
    crash.reason = reap_child();
    if (!pending_.empty()) {
      crash.index = pending_.front();
      pending_.pop_front();
      events.push_back(std::move(crash));
    }
    if (!pending_.empty()) start_child();
    return events;
  }
  return read_frames();
}

}  // namespace hexdyn
