#include "hexdyn/core/progress.hpp"

#include <cmath>
#include <iomanip>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {
thread_local ProgressScope* current_scope = nullptr;
}  // namespace

ProgressScope::ProgressScope(std::ostream& os, std::string command, double interval_s,
                             std::string stage)
    : os_(os),
      command_(std::move(command)),
      stage_(std::move(stage)),
      interval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(interval_s))),
      start_(std::chrono::steady_clock::now()),
      next_(start_ + interval_),
      previous_(current_scope) {
  current_scope = this;
}

ProgressScope::~ProgressScope() { current_scope = previous_; }

void ProgressScope::report(const char* stage, double done, double total, const char* unit) {
  if (!stage_.empty() && stage_ != stage) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_) return;
  next_ = now + interval_;
  const double elapsed_s = std::chrono::duration<double>(now - start_).count();
  const double percent = total > 0.0 ? 100.0 * done / total : 0.0;
  os_ << "hexdyn: " << command_ << ": " << stage << " " << std::setprecision(4) << done << " of "
      << total << " " << unit << " (" << std::fixed << std::setprecision(0) << percent << " %), "
      << std::setprecision(1) << elapsed_s << " s elapsed" << std::defaultfloat
      << std::setprecision(6) << std::endl;
}

double parse_progress_interval(const std::string& text) {
  std::size_t used = 0;
  double v = -1.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(v >= 0.0 && v <= 86400.0))
    throw ConfigError("--progress: got " + text + ", expected seconds in [0, 86400]");
  return v;
}

void report_progress(const char* stage, double done, double total, const char* unit) {
  if (current_scope != nullptr) current_scope->report(stage, done, total, unit);
}

}  // namespace hexdyn
