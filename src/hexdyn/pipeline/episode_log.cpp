// The log of relaxed and failed samples (pipeline/episode_log.hpp).
#include "hexdyn/pipeline/episode_log.hpp"

#include <algorithm>

#include "hexdyn/core/common.hpp"

namespace hexdyn {
namespace {

/// What a relaxed sample is, said once per run before its first relaxed line.
constexpr const char* kRelaxedNote =
    "hexdyn: relaxed samples: the allocation met the named constraints only with penalised "
    "slack (/solver/status 1); in a touchdown transient (marked impact) this is by design, the "
    "prescribed impact forces leave the trunk equations unsatisfiable "
    "(docs/theory/allocation.md#relaxed-samples)";

constexpr const char* kFrictionNote = "required friction: ";

const char* status_word(SolverStatus s) {
  return s == SolverStatus::kRelaxed ? "relaxed" : "failed";
}

/// The message without its leading status word ("relaxed: ", "failed: ").
std::string without_status_word(const std::string& message, SolverStatus s) {
  const std::string word = std::string(status_word(s)) + ": ";
  return message.compare(0, word.size(), word) == 0 ? message.substr(word.size()) : message;
}

/// "t = [1.7, 1.70047] s: 56 sample(s) relaxed: <message>", one episode.
void write_one(std::ostream& os, const EpisodeLog::Episode& e) {
  os << "hexdyn: t = [" << e.start_s << ", " << e.end_s << "] s: " << e.count << " sample(s) "
     << status_word(e.status) << ": " << brief_message(without_status_word(e.message, e.status))
     << "\n";
}

/// The summary of the episodes of one kind (more than one).
void write_summary(std::ostream& os, const std::vector<const EpisodeLog::Episode*>& kind) {
  int samples = 0, no_friction = 0;
  const EpisodeLog::Episode* worst = kind.front();
  for (const EpisodeLog::Episode* e : kind) {
    samples += e->count;
    no_friction += e->no_friction;
    if (e->worst > worst->worst) worst = e;
  }
  const EpisodeLog::Episode& first = *kind.front();
  os << "hexdyn: " << kind.size() << " episodes of " << status_word(first.status) << " samples "
     << (first.touchdown ? "in touchdown transients" : "outside touchdowns") << ", " << samples
     << " samples from t = " << first.start_s << " to " << kind.back()->end_s
     << " s; worst at t = " << worst->worst_s << " s: " << worst_row(worst->message);
  if (no_friction > 0) {
    const std::string& m = worst->message;
    const auto at = m.find(kFrictionNote);
    const std::string phrase = at == std::string::npos ? "" : brief_message(m.substr(at));
    os << "; at " << no_friction << " samples, " << phrase;
  }
  os << " (each sample's message in /solver/messages)\n";
}

}  // namespace

void EpisodeLog::add(double t_s, SolverStatus status, bool touchdown, double max_violation,
                     const std::string& message) {
  if (!log_) return;  // nothing is written: a sweep's run keeps no episodes
  if (open_ && episodes_.back().touchdown != touchdown) close();
  if (!open_) {
    Episode e;
    e.start_s = e.end_s = e.worst_s = t_s;
    e.touchdown = touchdown;
    episodes_.push_back(e);
    open_ = true;
  }
  Episode& e = episodes_.back();
  e.end_s = t_s;
  ++e.count;
  e.status = std::max(e.status, status);
  if (message.find(kFrictionNote) != std::string::npos) ++e.no_friction;
  if (max_violation > e.worst) {
    e.worst = max_violation;
    e.worst_s = t_s;
    e.message = message;
  }
}

void EpisodeLog::close() { open_ = false; }

void EpisodeLog::flush() {
  close();
  if (!log_) return;
  bool noted = false;
  std::vector<bool> written(episodes_.size(), false);
  for (std::size_t i = 0; i < episodes_.size(); ++i) {
    if (written[i]) continue;
    std::vector<const Episode*> kind;
    for (std::size_t j = i; j < episodes_.size(); ++j)
      if (episodes_[j].status == episodes_[i].status &&
          episodes_[j].touchdown == episodes_[i].touchdown) {
        kind.push_back(&episodes_[j]);
        written[j] = true;
      }
    if (episodes_[i].status == SolverStatus::kRelaxed && !noted) *log_ << kRelaxedNote << "\n";
    noted = noted || episodes_[i].status == SolverStatus::kRelaxed;
    if (kind.size() == 1)
      write_one(*log_, *kind.front());
    else
      write_summary(*log_, kind);
  }
  episodes_.clear();
}

std::string worst_row(const std::string& message) {
  std::string m = message;
  const auto colon = m.find(": ");
  if (colon != std::string::npos && colon < m.find(" by ")) m = m.substr(colon + 2);
  const auto end = m.find_first_of(",;(");
  std::string row = m.substr(0, end);
  while (!row.empty() && row.back() == ' ') row.pop_back();
  const auto impact = message.find("(impact ");
  if (impact != std::string::npos)
    row += " " + message.substr(impact, message.find(')', impact) - impact + 1);
  return row;
}

std::string brief_message(const std::string& message) {
  const auto at = message.find(kFrictionNote);
  if (at == std::string::npos) return message;
  const auto open = message.find(" (", at);
  return open == std::string::npos ? message : message.substr(0, open);
}

}  // namespace hexdyn
