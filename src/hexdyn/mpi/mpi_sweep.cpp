#include "hexdyn/mpi/mpi_sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/mpi/comm_detail.hpp"
#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/mpi/worker.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/launch.hpp"
#include "hexdyn/sweep/coordinator.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/sweep.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace mpi_detail;

/// Message tags. A worker sends kReady once, then kResult messages (finished scenarios,
/// several at a time), and kInterrupted (the signal's number) if it was signalled; rank 0
/// sends kWork (a batch of indices, or the stop).
enum Tag : int { kTagReady = 1, kTagResult = 2, kTagWork = 3, kTagInterrupted = 4 };

/// Longest time a signalled worker waits for rank 0 to end the job before it ends itself.
constexpr auto kWorkerGrace = std::chrono::seconds(10);

std::string scratch_directory() { return fs::temp_directory_path().string(); }

// ---- worker ranks

/// SIGTERM, SIGINT (mpirun and Slurm send them to every rank): a worker stops only
/// between messages, after a result it was sending has arrived, so that rank 0 never
/// loses a worker in the middle of a transfer inside MPI. It then stops its scenario
/// process, tells rank 0, and waits for rank 0 to end the job: mpirun kills every rank
/// left as soon as one rank exits, so a worker that left first would cut rank 0 off before
/// it flushed its checkpoint and said what it kept. A signal to a worker alone thereby
/// stops the sweep the same way (docs/user/faults.md#signals).
void worker_rank(const ScenarioFactory& factory, const SweepIdentity& identity) {
  WorkerOptions wo;
  wo.keep_runs = identity.keep_runs;
  wo.identity = identity;
  wo.isolate = isolation_from_environment();
  wo.scratch_dir = scratch_directory();
  WorkerLink link;
  link.send_ready = [] { send({}, 0, kTagReady); };
  link.send_results = [](std::vector<char>&& msg) {
    send(msg, 0, kTagResult);
    check_interrupt();
  };
  link.poll_work = []() -> std::optional<std::optional<std::vector<std::size_t>>> {
    check_interrupt();
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(0, kTagWork, MPI_COMM_WORLD, &flag, &st);
    if (!flag) return std::nullopt;
    return unpack_work(receive(st));
  };
  try {
    run_worker(factory, wo, link);
  } catch (const Interrupted& e) {  // the scenario process is stopped (~ScenarioProcess)
    send(pack_interrupted(e.signal()), 0, kTagInterrupted);
    const auto until = Clock::now() + kWorkerGrace;
    while (Clock::now() < until) {
      int flag = 0;  // drives MPI's progress, so that the notice leaves over any transport
      MPI_Iprobe(0, kTagWork, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::_exit(e.exit_status());
  }
}

// ---- rank 0

/// The messages between rank 0's coordinator (main thread) and its compute thread.
struct LocalLink {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::optional<std::vector<std::size_t>>> work;  ///< nothing = stop
  std::deque<std::vector<char>> results;
  bool ready = false, running = false;
  std::exception_ptr error;
};

class Coordinator {
 public:
  Coordinator(const SweepOptions& opt, const MpiSession& mpi) : opt_(opt), mpi_(mpi) {}

  /// Reads and validates everything; throws hexdyn::Error before any work.
  void prepare() {
    start_ = Clock::now();
    spec_ = load_sweep(opt_.sweep_path);
    check_output_target(opt_.output_path, spec_.inputs);
    checkpoint_ =
        std::make_unique<Checkpoint>(opt_.output_path, spec_, opt_.keep_runs, opt_.resume);
    factory_ = std::make_unique<ScenarioFactory>(spec_);
    robot_ = sweep_robot_shape(*factory_);  // one robot shape per sweep, else a ConfigError
  }

  const SweepSpec& spec() const { return spec_; }
  const SweepIdentity& identity() const { return checkpoint_->identity(); }
  const ScenarioFactory& factory() const { return *factory_; }

  /// Distributes the scenarios and writes the sweep file. Returns 0.
  int run() {
    const std::size_t n = spec_.scenario_count();
    resume_from_checkpoint(n);
    announce();
    ProgressMeter meter(n, resumed_, opt_.progress_interval_s, start_);
    std::cerr << meter.line(Clock::now()) << "\n";

    const bool local_compute = mpi_.size() == 1 || mpi_.threads_allowed();
    std::thread local;
    if (local_compute && !coord_->finished()) {
      local_.running = true;
      local = std::thread([this] { local_loop(); });
    }
    try {
      coordinate(meter);
    } catch (const Interrupted& e) {
      stop_now(e);
    } catch (const CheckpointLost& e) {
      stop_now(e);
    } catch (...) {
      stop_local(local);
      try {
        checkpoint_->flush(true);
      } catch (...) {
      }
      throw;
    }
    stop_local(local);
    if (local_.error) std::rethrow_exception(local_.error);
    if (!coord_->finished()) throw Error("sweep: workers stopped before every scenario finished");
    workers_done_ = true;
    try {
      checkpoint_->flush(true);
      return finish();
    } catch (const Interrupted& e) {
      stop_now(e);
    } catch (const CheckpointLost& e) {
      stop_now(e);
    }
  }

  /// Every worker rank was told to stop (a failure after this point needs no MPI_Abort).
  bool workers_done() const { return workers_done_; }

 private:
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  /// The scheduler of the n scenarios, with what the checkpoint holds marked: its finished
  /// rows (failed ones counted) and the scenarios whose process crashed once; its warnings
  /// printed.
  void resume_from_checkpoint(std::size_t n) {
    std::vector<std::size_t> sizes;
    for (const auto& a : spec_.axes) sizes.push_back(a.size());
    coord_ = std::make_unique<SweepCoordinator>(n, sizes, mpi_.size());
    for (const ScenarioSummary& r : checkpoint_->finished()) {
      coord_->mark_finished(r.index);
      if (r.status != ScenarioStatus::kOk) ++failed_;
    }
    for (std::size_t i : checkpoint_->crash_attempts()) coord_->mark_crashed_once(i);
    resumed_ = checkpoint_->finished().size();
    for (const std::string& w : checkpoint_->warnings())
      std::cerr << "hexdyn: warning: " << w << "\n";
  }

  /// Serves rank 0's compute thread and the worker ranks, hands out work, flushes the
  /// checkpoint (past 1 MiB buffered or 0.5 s, synced to disk every 5 s) and prints
  /// progress through meter, until no result is pending and no one computes. Throws
  /// Interrupted on a signal (between results) and the compute thread's error.
  void coordinate(ProgressMeter& meter) {
    std::vector<Assignment> out;
    auto last_flush = Clock::now(), last_sync = Clock::now();
    // Between looks at the worker ranks when nothing happened: from 0.1 ms, doubling to
    // 4 ms (Open MPI has no blocking receive that sleeps); rank 0's own compute thread
    // wakes the coordinator at once through the condition variable.
    auto idle_wait = std::chrono::microseconds(100);
    remote_active_ = mpi_.size() - 1;
    for (;;) {
      bool progressed = serve_local(out);
      if (mpi_.size() > 1) progressed = serve_remote(out) || progressed;
      dispatch(out);
      const auto now = Clock::now();
      if (checkpoint_->buffered() > (1u << 20) || seconds(now - last_flush) > 0.5) {
        const bool sync = seconds(now - last_sync) > 5.0;
        checkpoint_->flush(sync);
        last_flush = now;
        if (sync) last_sync = now;
      }
      if (auto line = meter.update(done_ + resumed_, failed_, now)) std::cerr << *line << "\n";
      check_interrupt();  // SIGTERM, SIGINT: between results (interrupt.hpp)
      std::unique_lock<std::mutex> lock(local_.mutex);
      if (local_.error) std::rethrow_exception(local_.error);
      if (!local_.running && local_.results.empty() && remote_active_ == 0) break;
      if (progressed) {
        idle_wait = std::chrono::microseconds(100);
      } else {
        const auto wait = mpi_.size() > 1 ? idle_wait : std::chrono::microseconds(200000);
        idle_wait = std::min(idle_wait * 2, std::chrono::microseconds(4000));
        local_.changed.wait_for(lock, wait, [this] {
          return !local_.results.empty() || (local_.ready && !local_ready_seen_) || !local_.running;
        });
      }
    }
  }

  /// Ends the process at once after a signal (checkpoint flushed) or a lost checkpoint
  /// (nothing written): one line, then _exit, without waiting for a scenario in progress
  /// (its child dies with this process, PR_SET_PDEATHSIG); under mpirun the job ends
  /// with this rank. The journal is written (into the page cache, which outlives this
  /// process) and the line printed before the journal is synced to disk: mpirun sends
  /// SIGKILL 1 s after its SIGTERM (Open MPI's odls_base_sigkill_timeout), and a sync on
  /// a busy disk can take longer. docs/user/faults.md#signals
  [[noreturn]] void stop_now(const Error& e) {
    std::string kept;
    const bool signalled = dynamic_cast<const Interrupted*>(&e) != nullptr;
    if (signalled) {
      try {
        checkpoint_->flush(false);
        const std::size_t n = checkpoint_->finished().size() + done_;
        kept = ": " + std::to_string(n) + " finished scenario" + (n == 1 ? "" : "s") +
               " kept in the checkpoint " + checkpoint_->directory() +
               ", no temporary file left; continue with: hexdyn sweep " + opt_.sweep_path + " -o " +
               opt_.output_path + (opt_.keep_runs ? " --keep-runs" : "") + " --resume";
      } catch (const Error& f) {
        kept = ": the checkpoint could not be flushed: " + std::string(f.what());
      }
      std::cerr << "hexdyn: sweep " << e.what() << kept << "\n";
    } else {
      std::cerr << "hexdyn: error: " << one_line(e.what()) << "\n";
    }
    std::cerr.flush();
    if (signalled) {
      try {
        checkpoint_->flush(true);
      } catch (const Error& f) {
        std::cerr << "hexdyn: sweep: the checkpoint could not be synced to disk: "
                  << one_line(f.what()) << "\n";
      }
    }
    ::_exit(e.exit_status());
  }

  void announce() const {
    const std::size_t n = spec_.scenario_count();
    std::ostringstream s;
    s << "hexdyn: sweep '" << spec_.name << "': " << n << " scenario" << (n == 1 ? "" : "s")
      << " over " << spec_.axes.size() << " ax" << (spec_.axes.size() == 1 ? "is" : "es") << " on "
      << mpi_.size() << " rank" << (mpi_.size() > 1 ? "s" : "") << "; " << n - resumed_
      << " to compute";
    if (resumed_ > 0) s << ", " << resumed_ << " from the checkpoint";
    // Scenarios holding a value that is not valid on its own (checked once per value).
    std::size_t valid = 1;
    std::string first;
    for (const SweepAxis& a : spec_.axes) {
      std::size_t ok = 0;
      for (const std::string& e : a.errors) {
        if (e.empty())
          ++ok;
        else if (first.empty())
          first = e;
      }
      valid *= ok;
    }
    if (valid < n)
      s << ", " << n - valid << " with values out of range (recorded as failed; first: " << first
        << ")";
    s << "; checkpoint " << checkpoint_->directory();
    std::cerr << s.str() << "\n";
  }

  void local_loop() {
    try {
      WorkerOptions wo;
      wo.keep_runs = opt_.keep_runs;
      wo.identity = checkpoint_->identity();
      wo.isolate = isolation_from_environment();
      wo.scratch_dir = scratch_directory();
      WorkerLink link;
      link.send_ready = [this] {
        {
          std::lock_guard<std::mutex> lock(local_.mutex);
          local_.ready = true;
        }
        local_.changed.notify_one();
      };
      link.send_results = [this](std::vector<char>&& msg) {
        {
          std::lock_guard<std::mutex> lock(local_.mutex);
          local_.results.push_back(std::move(msg));
        }
        local_.changed.notify_one();
      };
      link.poll_work = [this]() -> std::optional<std::optional<std::vector<std::size_t>>> {
        std::lock_guard<std::mutex> lock(local_.mutex);
        if (local_.work.empty()) return std::nullopt;
        std::optional<std::optional<std::vector<std::size_t>>> w(std::in_place);
        w->swap(local_.work.front());
        local_.work.pop_front();
        return w;
      };
      run_worker(*factory_, wo, link);
    } catch (...) {
      std::lock_guard<std::mutex> lock(local_.mutex);
      local_.error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(local_.mutex);
      local_.running = false;
    }
    local_.changed.notify_one();
  }

  void stop_local(std::thread& local) {
    {
      std::lock_guard<std::mutex> lock(local_.mutex);
      local_.work.push_back(std::nullopt);
    }
    if (local.joinable()) local.join();
  }

  /// Handles what rank 0's compute thread sent; true if anything.
  bool serve_local(std::vector<Assignment>& out) {
    std::deque<std::vector<char>> got;
    bool ready = false;
    {
      std::lock_guard<std::mutex> lock(local_.mutex);
      got.swap(local_.results);
      ready = local_.ready && !local_ready_seen_;
      if (ready) local_ready_seen_ = true;
    }
    if (ready) coord_->on_ready(0, out);
    for (const auto& msg : got) take_results(0, msg, out);
    return ready || !got.empty();
  }

  /// Answers every waiting message of the worker ranks; true if there was any.
  bool serve_remote(std::vector<Assignment>& out) {
    bool any = false;
    for (;;) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (!flag) return any;
      any = true;
      const std::vector<char> msg = receive(st);
      if (st.MPI_TAG == kTagReady) {
        coord_->on_ready(st.MPI_SOURCE, out);
      } else if (st.MPI_TAG == kTagInterrupted) {  // a worker was signalled (worker_rank)
        throw Interrupted(unpack_interrupted(msg));
      } else {
        take_results(st.MPI_SOURCE, msg, out);
      }
      dispatch(out);
    }
  }

  void dispatch(std::vector<Assignment>& out) {
    for (Assignment& a : out) {
      if (a.worker == 0) {
        {
          std::lock_guard<std::mutex> lock(local_.mutex);
          if (a.stop)
            local_.work.push_back(std::nullopt);
          else
            local_.work.push_back(std::move(a.indices));
        }
        continue;
      }
      if (a.stop) --remote_active_;
      send(a.stop ? pack_stop() : pack_work(a.indices), a.worker, kTagWork);
    }
    out.clear();
  }

  void take_results(int worker, const std::vector<char>& msg, std::vector<Assignment>& out) {
    for (Finished& f : unpack_results(msg)) {
      if (f.crashed) {
        if (!coord_->on_crash(worker, f.index, out)) {
          checkpoint_->append_crash(f.index, f.reason);
          std::cerr << "hexdyn: warning: scenario " << scenario_id(spec_, f.index) << ": "
                    << f.reason << " (rank " << worker << "); it is computed once more\n";
          continue;
        }
        ScenarioRecord r;
        r.summary = failed_summary(f.index, ScenarioStatus::kCrashed,
                                   scenario_source_name(scenario_id(spec_, f.index)) +
                                       ": crashed twice, not retried: " + f.reason);
        const std::vector<char> payload = encode_record(r);
        checkpoint_->append_row(f.index, payload.data(), payload.size());
        count(worker, f, r.summary);
        continue;
      }
      // The worker built the journal record (checksum included): it is appended as it is.
      const BuiltRecord b =
          checkpoint_->append_row_record(f.index, f.payload.data(), f.payload.size());
      ScenarioRecord r = decode_record(b.payload, b.size, false);
      if (r.summary.index != f.index) throw Error("sweep: a result names the wrong scenario");
      check_row_joints(r.summary, robot_.joints(), scenario_id(spec_, f.index), worker);
      coord_->on_result(worker, f.index, f.cost_s, out);
      count(worker, f, r.summary);
    }
  }

  void count(int worker, const Finished& f, ScenarioSummary& row) {
    ++done_;
    if (row.status != ScenarioStatus::kOk) ++failed_;
    if (opt_.verbose) {
      std::cerr << "hexdyn: sweep: scenario " << scenario_id(spec_, f.index) << " "
                << status_name(row.status) << " (rank " << worker << ", " << std::fixed
                << std::setprecision(2) << row.wall_time_s << std::defaultfloat << " s)";
      if (!row.message.empty()) std::cerr << ": " << row.message;
      std::cerr << "\n";
    }
    rows_.push_back(std::move(row));
  }

  int finish() {
    const std::size_t n = spec_.scenario_count();
    std::vector<ScenarioSummary> rows(n);
    std::vector<char> have(n, 0);
    for (const std::vector<ScenarioSummary>* list :
         std::initializer_list<const std::vector<ScenarioSummary>*>{&checkpoint_->finished(),
                                                                    &rows_})
      for (const ScenarioSummary& r : *list)
        if (!have[r.index]) {
          have[r.index] = 1;
          rows[r.index] = r;
        }
    for (std::size_t i = 0; i < n; ++i)
      if (!have[i]) throw Error("sweep: scenario " + scenario_id(spec_, i) + " has no result");
    const double wall = seconds(Clock::now() - start_);
    checkpoint_->verify();  // a lost checkpoint stops the sweep before it writes (CheckpointLost)
    write_sweep_file(opt_.output_path, spec_, rows, robot_,
                     opt_.keep_runs ? checkpoint_.get() : nullptr, {mpi_.size(), wall, resumed_});
    const std::size_t journals = checkpoint_->journal_count();
    try {
      checkpoint_->remove();
    } catch (const CheckpointLost&) {
      std::cerr << "hexdyn: warning: the checkpoint " << checkpoint_->directory()
                << " was removed or replaced after " << opt_.output_path
                << " was complete; the output is whole, that checkpoint left untouched\n";
    } catch (const Error& e) {
      std::cerr << "hexdyn: warning: " << e.what() << "\n";
    }
    std::size_t ok = 0, crashed = 0;
    for (const auto& r : rows) {
      ok += r.status == ScenarioStatus::kOk ? 1 : 0;
      crashed += r.status == ScenarioStatus::kCrashed ? 1 : 0;
    }
    std::cerr << "hexdyn: sweep: wrote " << opt_.output_path << ": " << n << " scenarios, " << ok
              << " ok, " << n - ok << " failed";
    if (crashed > 0) std::cerr << " (" << crashed << " crashed)";
    std::cerr << "; " << done_ << " computed by this run, " << resumed_
              << " taken from the checkpoint (" << journals << " journal"
              << (journals == 1 ? "" : "s") << "); " << mpi_.size() << " rank"
              << (mpi_.size() > 1 ? "s" : "") << ", " << format_duration(wall) << "\n";
    return 0;
  }

  const SweepOptions& opt_;
  const MpiSession& mpi_;
  Clock::time_point start_;
  SweepSpec spec_;
  std::unique_ptr<Checkpoint> checkpoint_;
  std::unique_ptr<ScenarioFactory> factory_;
  RobotShape robot_;  ///< the scenarios' robot shape (sweep_robot_shape)
  std::unique_ptr<SweepCoordinator> coord_;
  LocalLink local_;
  bool local_ready_seen_ = false;
  int remote_active_ = 0;  ///< worker ranks not yet told to stop
  bool workers_done_ = false;
  std::vector<ScenarioSummary> rows_;  ///< computed by this run, in arrival order
  std::size_t done_ = 0, failed_ = 0, resumed_ = 0;
};

}  // namespace

int run_sweep(const SweepOptions& options) {
  die_with_launcher();
  MpiSession mpi;
  // Rank 0 flushes the checkpoint and says what it kept; a worker notes the signal, tells
  // rank 0 between messages and waits for it to end the job (worker_rank).
  install_interrupt_handlers(InterruptMode::kPoll, "hexdyn: sweep interrupted");
  if (mpi.rank() != 0) {
    int status = 0;
    broadcast_status(status);
    if (status != 0) return status;
    try {
      std::vector<char> bytes;
      broadcast_bytes(bytes);
      SweepIdentity identity;
      const SweepSpec spec = unpack_spec(bytes, identity);
      // Rank 0's bytes of every input: all ranks compute with the same files, those of
      // /meta input_sha256 (config/inputs.hpp).
      for (const InputFile& f : spec.inputs) keep_input(f);
      const ScenarioFactory factory(spec);
      worker_rank(factory, identity);
    } catch (const std::exception& e) {
      std::cerr << "hexdyn: error: rank " << mpi.rank() << ": " << e.what() << "\n";
      MPI_Abort(MPI_COMM_WORLD, 4);
    }
    quiet_barrier();
    return 0;
  }

  Coordinator coordinator(options, mpi);
  int status = 0;
  try {
    coordinator.prepare();
  } catch (const Error& e) {
    std::cerr << "hexdyn: error: " << one_line(e.what()) << "\n";
    status = e.exit_status();
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << one_line(e.what()) << "\n";
    status = 4;
  }
  broadcast_status(status);
  if (status != 0) return status;

  try {
    if (mpi.size() > 1) {
      std::vector<char> bytes = pack_spec(coordinator.spec(), coordinator.identity());
      broadcast_bytes(bytes);
    }
    status = coordinator.run();
  } catch (const std::exception& e) {
    const bool input = dynamic_cast<const Error*>(&e) != nullptr;
    std::cerr << "hexdyn: " << (input ? "error: " : "internal error: ") << one_line(e.what())
              << " (finished scenarios are kept; continue with --resume)\n";
    status = input ? dynamic_cast<const Error&>(e).exit_status() : 4;
    // After every worker rank was told to stop (the final write: a full disk), they wait
    // at the barrier: meet them there instead of aborting the job.
    if (!coordinator.workers_done()) {
      if (mpi.size() > 1) MPI_Abort(MPI_COMM_WORLD, status);
      return status;
    }
  }
  quiet_barrier();
  // A signal that came after the sweep file was complete: it is kept, nothing to resume.
  if (const int sig = interrupted()) {
    if (status == 0)
      std::cerr << "hexdyn: sweep: " << signal_name(sig) << " arrived after " << options.output_path
                << " was complete; nothing to resume\n";
    return 128 + sig;
  }
  return status;
}

}  // namespace hexdyn
