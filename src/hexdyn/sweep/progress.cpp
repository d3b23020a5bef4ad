#include "hexdyn/sweep/progress.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace hexdyn {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "unknown";
  const long long s = std::llround(seconds);
  char buf[64];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%lld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%lld min %02lld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  return buf;
}

ProgressMeter::ProgressMeter(std::size_t total, std::size_t already_done, double interval_s,
                             Clock::time_point start)
    : total_(total),
      already_done_(already_done),
      done_(already_done),
      interval_s_(interval_s),
      start_(start),
      last_line_(start),
      done_at_last_line_(already_done) {}

std::optional<std::string> ProgressMeter::update(std::size_t done, std::size_t failed,
                                                 Clock::time_point now) {
  done_ = done;
  failed_ = failed;
  if (done_ == done_at_last_line_) return std::nullopt;
  if (std::chrono::duration<double>(now - last_line_).count() < interval_s_) return std::nullopt;
  last_line_ = now;
  done_at_last_line_ = done_;
  return line(now);
}

std::string ProgressMeter::line(Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::size_t computed = done_ - already_done_;
  std::ostringstream s;
  s << "hexdyn: sweep: " << done_ << "/" << total_ << " done";
  if (failed_ > 0) s << ", " << failed_ << " failed";
  if (computed > 0 && elapsed > 0.0) {
    const double rate = static_cast<double>(computed) / elapsed;
    char r[32];
    std::snprintf(r, sizeof r, "%.3g", rate);
    s << ", " << r << " scenarios/s";
    if (done_ < total_)
      s << ", " << format_duration(static_cast<double>(total_ - done_) / rate) << " left";
  }
  s << ", " << format_duration(elapsed) << " elapsed";
  return s.str();
}

}  // namespace hexdyn
