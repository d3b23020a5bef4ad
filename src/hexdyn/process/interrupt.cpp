#include "hexdyn/process/interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <string>

namespace hexdyn {
namespace {

constexpr int kSlots = 16;
constexpr std::size_t kPathMax = 4096;
constexpr std::size_t kLineMax = 1024;

struct Slot {
  std::atomic<int> used{0};
  char path[kPathMax] = {0};
};
Slot g_slots[kSlots];

volatile sig_atomic_t g_signal = 0;
std::atomic<int> g_exit_in_handler{0};
char g_line[kLineMax] = {0};  ///< text before the signal's name
std::atomic<std::size_t> g_line_size{0};
char g_tail[kLineMax] = {0};  ///< text after it, newline included
std::atomic<std::size_t> g_tail_size{0};

void write_text(const char* text, std::size_t n) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(STDERR_FILENO, text + done, n - done);
    if (w <= 0) return;
    done += static_cast<std::size_t>(w);
  }
}

static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

/// The signals handled: every one whose default action ends the process and that a user, a
/// batch system or a closed pipe sends (SIGKILL and SIGSTOP cannot be caught; SIGSEGV and
/// its kind are faults of the program, not requests).
constexpr int kHandled[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2, SIGALRM, SIGPIPE};

/// The name of a handled signal (a static string: safe in the handler), or nullptr.
const char* name_of(int sig) {
  switch (sig) {
    case SIGHUP:
      return "SIGHUP";
    case SIGINT:
      return "SIGINT";
    case SIGQUIT:
      return "SIGQUIT";
    case SIGTERM:
      return "SIGTERM";
    case SIGUSR1:
      return "SIGUSR1";
    case SIGUSR2:
      return "SIGUSR2";
    case SIGALRM:
      return "SIGALRM";
    case SIGPIPE:
      return "SIGPIPE";
    default:
      return nullptr;
  }
}

void remove_registered() {
  for (Slot& s : g_slots)
    if (s.used.load(std::memory_order_acquire) == 1) ::unlink(s.path);
}

void on_signal(int sig) {
  const int saved = errno;
  const bool second = g_signal != 0;
  if (!second) g_signal = sig;
  remove_registered();
  if (g_exit_in_handler.load() != 0 || second) {
    if (!second) {
      write_text(g_line, g_line_size.load());
      const char* name = name_of(sig) ? name_of(sig) : "a signal";
      write_text(name, std::strlen(name));
      write_text(g_tail, g_tail_size.load());
    }
    ::_exit(128 + sig);
  }
  errno = saved;
}

}  // namespace

Interrupted::Interrupted(int sig) : Error("interrupted by " + signal_name(sig)), signal_(sig) {}

std::string signal_name(int sig) {
  if (const char* name = name_of(sig)) return name;
  return "signal " + std::to_string(sig);
}

namespace {

void set_line(InterruptMode mode, const std::string& line) {
  // The line is replaced while no handler uses it: size 0 first, then the bytes.
  g_line_size.store(0);
  g_tail_size.store(0);
  const std::size_t at = line.find(kSignalPlaceholder);
  const std::string head = line.substr(0, std::min(at, kLineMax - 1));
  const std::string tail =
      at == std::string::npos
          ? std::string("\n")
          : line.substr(at + std::strlen(kSignalPlaceholder), kLineMax - 2) + "\n";
  std::memcpy(g_line, head.data(), head.size());
  std::memcpy(g_tail, tail.data(), tail.size());
  g_line_size.store(head.size());
  g_tail_size.store(at == std::string::npos ? 0 : tail.size());
  g_exit_in_handler.store(mode == InterruptMode::kExitInHandler ? 1 : 0);
}

struct sigaction handler_action() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : kHandled) sigaddset(&sa.sa_mask, sig);  // one handler at a time
  sa.sa_flags = SA_RESTART;  // the program polls; interrupted system calls go on
  return sa;
}

}  // namespace

void install_interrupt_handlers(InterruptMode mode, const std::string& line) {
  set_line(mode, line);
  const struct sigaction sa = handler_action();
  for (int sig : kHandled) ::sigaction(sig, &sa, nullptr);
}

void reset_interrupt_handlers_in_child() {
  for (int sig : kHandled) ::signal(sig, SIG_DFL);
}

FatalSignalScope::FatalSignalScope(const std::string& line) {
  set_line(InterruptMode::kExitInHandler, line);
  const struct sigaction sa = handler_action();
  for (std::size_t i = 0; i < std::size(kHandled); ++i) {
    const int sig = kHandled[i];
    if (sig == SIGINT) continue;  // the host's (Python's KeyboardInterrupt)
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL ||
        (old.sa_flags & SA_SIGINFO) != 0)
      continue;
    if (::sigaction(sig, &sa, nullptr) == 0) installed_ |= 1u << i;
  }
}

FatalSignalScope::~FatalSignalScope() {
  for (std::size_t i = 0; i < std::size(kHandled); ++i)
    if (installed_ & (1u << i)) ::signal(kHandled[i], SIG_DFL);
}

int interrupted() { return g_signal; }

void check_interrupt() {
  if (const int sig = g_signal) throw Interrupted(sig);
}

void register_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return;
  for (Slot& s : g_slots) {
    if (s.used.load(std::memory_order_acquire) != 0) continue;
    std::memcpy(s.path, path.c_str(), path.size() + 1);
    s.used.store(1, std::memory_order_release);
    return;
  }
}

void unregister_temporary(const std::string& path) {
  for (Slot& s : g_slots)
    if (s.used.load(std::memory_order_acquire) == 1 && path == s.path) {
      s.used.store(0, std::memory_order_release);
      return;
    }
}

}  // namespace hexdyn
