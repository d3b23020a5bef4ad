#include "hexdyn/mpi/worker.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/sweep/scenario_process.hpp"

namespace hexdyn {

bool isolation_from_environment() {
  const char* v = std::getenv("HEXDYN_SWEEP_ISOLATION");
  return v == nullptr || std::strcmp(v, "none") != 0;
}

void run_worker(const ScenarioFactory& factory, const WorkerOptions& options, WorkerLink& link) {
  using Clock = std::chrono::steady_clock;
  ScenarioProcess process(factory, options.keep_runs, options.scratch_dir, options.isolate);
  link.send_ready();
  std::vector<char> results;
  auto last_send = Clock::now();
  bool stopping = false;
  auto idle_sleep = std::chrono::microseconds(50);
  for (;;) {
    bool got_work = false;
    while (auto msg = link.poll_work()) {
      if (!*msg) {
        stopping = true;
        break;
      }
      process.submit(**msg);
      got_work = true;
    }
    if (process.outstanding() == 0) {
      if (!results.empty()) {
        link.send_results(std::move(results));
        results = {};
        last_send = Clock::now();
      }
      if (stopping) return;
      if (!got_work) {  // idle: back off up to 5 ms between looks
        std::this_thread::sleep_for(idle_sleep);
        idle_sleep = std::min(idle_sleep * 2, std::chrono::microseconds(5000));
      }
      continue;
    }
    idle_sleep = std::chrono::microseconds(50);
    // Down to the last scenario: look for new work often; otherwise wake for results.
    const int timeout_ms = process.outstanding() <= 1 ? 1 : 20;
    for (ScenarioEvent& ev : process.wait(timeout_ms)) {
      Finished f;
      f.index = ev.index;
      f.crashed = ev.crashed;
      f.reason = std::move(ev.reason);
      f.cost_s = ev.timing.config_s + ev.timing.physics_s;
      if (!ev.crashed)
        append_journal_record(f.payload, RecordKind::kRow, ev.index, options.identity,
                              ev.payload.data(), ev.payload.size());
      append_result(results, f);
    }
    const double since = std::chrono::duration<double>(Clock::now() - last_send).count();
    if (!results.empty() && (process.outstanding() <= 1 || since >= options.flush_interval_s)) {
      link.send_results(std::move(results));
      results = {};
      last_send = Clock::now();
    }
  }
}

}  // namespace hexdyn
