#include "hexdyn/sweep/coordinator.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

SweepCoordinator::SweepCoordinator(std::size_t count, std::vector<std::size_t> axis_sizes,
                                   int workers, CoordinatorOptions options)
    : count_(count),
      axis_sizes_(std::move(axis_sizes)),
      options_(options),
      workers_(static_cast<std::size_t>(std::max(workers, 1))),
      state_(count, kPending),
      crashed_once_(count, 0),
      undispatched_(count) {
  const std::size_t product =
      std::accumulate(axis_sizes_.begin(), axis_sizes_.end(), std::size_t{1}, std::multiplies<>());
  if (axis_sizes_.empty() || product != count)
    throw Error("sweep coordinator: the axis sizes do not multiply to the scenario count");
  for (std::size_t s : axis_sizes_) {
    log_sum_.emplace_back(s, 0.0);
    log_n_.emplace_back(s, 0u);
  }
}

void SweepCoordinator::mark_finished(std::size_t index) {
  if (index >= count_ || state_[index] == kDone) return;
  state_[index] = kDone;
  --undispatched_;
  ++finished_count_;
}

void SweepCoordinator::mark_crashed_once(std::size_t index) {
  if (index < count_) crashed_once_[index] = 1;
}

std::size_t SweepCoordinator::batch_size() const {
  const std::size_t workers = workers_.size();
  std::size_t b = 2;  // before any cost is known: one to compute, one in hand
  if (ema_cost_ > 0.0)
    b = static_cast<std::size_t>(std::clamp(options_.target_batch_s / ema_cost_, 1.0,
                                            static_cast<double>(options_.max_batch)));
  // Guided: never more than a share of what is left, so the ends of the workers meet.
  const std::size_t share = std::max<std::size_t>(1, undispatched_ / (2 * workers));
  return std::max<std::size_t>(1, std::min(b, share));
}

double SweepCoordinator::predicted_log_cost(std::size_t index,
                                            const std::vector<double>& axis_mean) const {
  double sum = 0.0;
  for (std::size_t a = axis_sizes_.size(); a-- > 0;) {
    const std::size_t v = index % axis_sizes_[a];
    index /= axis_sizes_[a];
    // A value not seen yet: the axis's mean.
    sum += log_n_[a][v] > 0 ? log_sum_[a][v] / log_n_[a][v] : axis_mean[a];
  }
  return sum;
}

void SweepCoordinator::sort_tail() {
  tail_sorted_ = true;
  tail_.clear();
  for (; cursor_ < count_; ++cursor_)
    if (state_[cursor_] == kPending) tail_.push_back(cursor_);
  std::vector<std::pair<double, std::size_t>> keyed;
  keyed.reserve(tail_.size());
  // Each axis's mean log cost over the values seen, once (the fallback of unseen values).
  std::vector<double> axis_mean(axis_sizes_.size(), 0.0);
  for (std::size_t a = 0; a < axis_sizes_.size(); ++a) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < log_n_[a].size(); ++k) {
      sum += log_sum_[a][k];
      n += log_n_[a][k];
    }
    axis_mean[a] = n > 0 ? sum / static_cast<double>(n) : 0.0;
  }
  for (std::size_t i : tail_) keyed.emplace_back(predicted_log_cost(i, axis_mean), i);
  // Costliest last (taken from the back); ties in index order.
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) {
    return x.first < y.first || (x.first == y.first && x.second > y.second);
  });
  for (std::size_t k = 0; k < keyed.size(); ++k) tail_[k] = keyed[k].second;
}

bool SweepCoordinator::take(std::size_t& index) {
  while (!retry_.empty()) {
    index = retry_.front();
    retry_.pop_front();
    if (state_[index] == kPending) return true;
  }
  if (!tail_sorted_) {
    const std::size_t tail_size = std::max(count_ / 4, 8 * workers_.size());
    if (undispatched_ <= tail_size && costs_seen_ > 0) sort_tail();
  }
  if (tail_sorted_) {
    while (!tail_.empty()) {
      index = tail_.back();
      tail_.pop_back();
      if (state_[index] == kPending) return true;
    }
    return false;
  }
  for (; cursor_ < count_; ++cursor_)
    if (state_[cursor_] == kPending) {
      index = cursor_++;
      return true;
    }
  return false;
}

void SweepCoordinator::refill(int w, std::vector<Assignment>& out, std::size_t at_least) {
  Worker& wk = workers_[static_cast<std::size_t>(w)];
  if (wk.stopped || wk.outstanding > 1) return;
  const std::size_t b = std::max(batch_size(), at_least);
  Assignment a;
  a.worker = w;
  std::size_t index = 0;
  while (a.indices.size() < b && take(index)) {
    state_[index] = kOut;
    --undispatched_;
    a.indices.push_back(index);
  }
  if (a.indices.empty()) return;
  wk.outstanding += a.indices.size();
  out.push_back(std::move(a));
}

void SweepCoordinator::stop_idle(std::vector<Assignment>& out) {
  if (!finished()) return;
  for (std::size_t w = 0; w < workers_.size(); ++w) {
    Worker& wk = workers_[w];
    if (wk.ready && !wk.stopped && wk.outstanding == 0) {
      wk.stopped = true;
      Assignment a;
      a.worker = static_cast<int>(w);
      a.stop = true;
      out.push_back(std::move(a));
    }
  }
}

void SweepCoordinator::on_ready(int w, std::vector<Assignment>& out) {
  workers_[static_cast<std::size_t>(w)].ready = true;
  refill(w, out);
  stop_idle(out);
}

void SweepCoordinator::finish(std::size_t index) {
  if (state_[index] == kDone) return;
  state_[index] = kDone;
  ++finished_count_;
}

void SweepCoordinator::on_result(int w, std::size_t index, double cost_s,
                                 std::vector<Assignment>& out) {
  if (index >= count_) throw Error("sweep coordinator: result for an unknown scenario");
  Worker& wk = workers_[static_cast<std::size_t>(w)];
  if (wk.outstanding > 0) --wk.outstanding;
  finish(index);
  if (cost_s > 0.0 && std::isfinite(cost_s)) {
    ++costs_seen_;
    ema_cost_ = costs_seen_ == 1 ? cost_s : 0.9 * ema_cost_ + 0.1 * cost_s;
    const double lc = std::log(cost_s);
    std::size_t rest = index;
    for (std::size_t a = axis_sizes_.size(); a-- > 0;) {
      const std::size_t v = rest % axis_sizes_[a];
      rest /= axis_sizes_[a];
      log_sum_[a][v] += lc;
      ++log_n_[a][v];
    }
  }
  refill(w, out);
  stop_idle(out);
}

bool SweepCoordinator::on_crash(int w, std::size_t index, std::vector<Assignment>& out) {
  if (index >= count_) throw Error("sweep coordinator: crash of an unknown scenario");
  Worker& wk = workers_[static_cast<std::size_t>(w)];
  if (wk.outstanding > 0) --wk.outstanding;
  bool final_crash = false;
  if (crashed_once_[index]) {
    finish(index);
    final_crash = true;
  } else {
    crashed_once_[index] = 1;
    state_[index] = kPending;
    ++undispatched_;
    retry_.push_back(index);
  }
  refill(w, out);
  // Workers left idle while the retry was out: give it to one of them.
  for (std::size_t v = 0; v < workers_.size() && !retry_.empty(); ++v)
    if (workers_[v].ready && !workers_[v].stopped && workers_[v].outstanding == 0)
      refill(static_cast<int>(v), out);
  stop_idle(out);
  return final_crash;
}

}  // namespace hexdyn
