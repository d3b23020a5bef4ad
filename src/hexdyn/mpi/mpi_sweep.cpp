#include "hexdyn/mpi/mpi_sweep.hpp"

#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

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
#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/sweep/sweep.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Message tags. A worker sends kReady once, then one kResult per scenario (which also
/// asks for the next one); rank 0 answers each with kWork (an index, or −1 to stop).
enum Tag : int { kTagReady = 1, kTagResult = 2, kTagWork = 3 };

/// MPI_Init_thread / MPI_Finalize for the lifetime of the sweep.
///
/// The sequential MUMPS that Ipopt links exports dummy MPI_Init, MPI_Comm_rank,
/// MPI_Finalize and MPI_Wtime (rank 0 of 1, no-op finalise), and it comes before
/// libmpi in the executable's symbol lookup order. This file therefore calls the
/// profiling entry points PMPI_Comm_rank and PMPI_Finalize, which only the MPI library
/// defines, and never MPI_Init or MPI_Wtime; the constructor checks that the ranks it
/// sees are 0..size−1 once each.
class MpiSession {
 public:
  MpiSession() {
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &thread_level_);
    PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    long long mine = rank_, sum = 0;
    MPI_Allreduce(&mine, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (sum != static_cast<long long>(size_) * (size_ - 1) / 2) {
      std::cerr << "hexdyn: internal error: MPI ranks are not distinct (MPI symbols shadowed "
                   "by another library?)\n";
      MPI_Abort(MPI_COMM_WORLD, 4);
    }
  }
  ~MpiSession() { PMPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// True if threads other than the main one may exist (they never call MPI).
  bool threads_allowed() const { return thread_level_ >= MPI_THREAD_FUNNELED; }

 private:
  int thread_level_ = MPI_THREAD_SINGLE, rank_ = 0, size_ = 1;
};

void send(const std::vector<char>& bytes, int dest, int tag) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("sweep: message of " + std::to_string(bytes.size()) + " bytes exceeds MPI's limit");
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

/// Receives the message announced by `st` (from MPI_Probe / MPI_Iprobe).
std::vector<char> receive(const MPI_Status& st) {
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  std::vector<char> bytes(static_cast<std::size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return bytes;
}

/// Computes one scenario and encodes its checkpoint (any rank, any thread; no MPI).
Finished compute(const ScenarioInput& in, bool keep_runs, int rank, const std::string& scratch) {
  const ScenarioOutcome out = run_scenario(in, keep_runs);
  Finished f;
  f.index = in.index;
  f.status = out.summary.status;
  f.message = out.summary.message;
  f.wall_time_s = out.summary.wall_time_s;
  f.rank = rank;
  f.checkpoint = encode_checkpoint(out, scratch);
  return f;
}

std::string scratch_directory() { return fs::temp_directory_path().string(); }

// ---- worker ranks

int worker_loop(int rank) {
  const std::string scratch = scratch_directory();
  send({}, 0, kTagReady);
  for (;;) {
    MPI_Status st;
    MPI_Probe(0, kTagWork, MPI_COMM_WORLD, &st);
    const std::optional<Work> work = unpack_work(receive(st));
    if (!work) break;
    send(pack_result(compute(work->input, work->keep_runs, rank, scratch)), 0, kTagResult);
  }
  return 0;
}

/// Waits for every rank without spinning: workers poll a non-blocking barrier with
/// short sleeps, so they leave their cores to rank 0 while it writes the sweep file.
void quiet_barrier() {
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  int done = 0;
  for (;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// ---- rank 0

/// The queue of scenarios shared by rank 0's coordinator and its compute thread.
struct WorkQueue {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::size_t> pending;
  std::vector<Finished> finished;  ///< computed by the local thread, not yet stored
  bool local_running = false;
  bool stop = false;
  std::exception_ptr local_error;

  std::optional<std::size_t> take() {
    std::lock_guard<std::mutex> lock(mutex);
    if (stop || pending.empty()) return std::nullopt;
    const std::size_t i = pending.front();
    pending.pop_front();
    return i;
  }
};

class Coordinator {
 public:
  Coordinator(const SweepOptions& opt, const MpiSession& mpi) : opt_(opt), mpi_(mpi) {}

  /// Reads and validates everything; throws hexdyn::Error before any work.
  void prepare() {
    spec_ = load_sweep(opt_.sweep_path);
    check_output_path_writable(opt_.output_path);
    checkpoint_ =
        std::make_unique<Checkpoint>(opt_.output_path, spec_, opt_.keep_runs, opt_.resume);
    const std::size_t n = spec_.scenario_count();
    state_.assign(n, State::kPending);
    invalid_.resize(n);
    for (std::size_t i : checkpoint_->finished()) {
      state_[i] = State::kDone;
      ++resumed_;
      if (read_checkpoint_summary(checkpoint_->scenario_path(i)).status != ScenarioStatus::kOk)
        ++failed_;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (state_[i] == State::kDone) continue;
      if (auto bad = check_scenario(scenario_input(spec_, i))) {
        invalid_[i] = std::move(*bad);
        state_[i] = State::kDone;
        ++failed_;
        ++invalid_count_;
      } else {
        queue_.pending.push_back(i);
      }
    }
  }

  /// Distributes the pending scenarios and writes the sweep file. Returns 0.
  int run() {
    const auto start = Clock::now();
    const std::size_t n = spec_.scenario_count();
    done_ = n - queue_.pending.size();
    announce();
    ProgressMeter meter(n, done_, opt_.progress_interval_s, start);

    const bool local_compute = mpi_.size() == 1 || mpi_.threads_allowed();
    std::thread local;
    if (local_compute && !queue_.pending.empty()) {
      queue_.local_running = true;
      local = std::thread([this] { local_loop(); });
    }
    try {
      int remote_active = mpi_.size() - 1;
      for (;;) {
        bool progressed = store_local();
        if (mpi_.size() > 1) progressed = serve_remote(remote_active) || progressed;
        if (auto line = meter.update(done_, failed_, Clock::now())) std::cerr << *line << "\n";
        bool local_running = false;
        {
          std::unique_lock<std::mutex> lock(queue_.mutex);
          if (queue_.local_error) std::rethrow_exception(queue_.local_error);
          local_running = queue_.local_running || !queue_.finished.empty();
          if (!local_running && remote_active == 0) break;
          if (!progressed) {
            // Wake at once for a local result; poll remote ranks every millisecond.
            const auto wait =
                mpi_.size() > 1 ? std::chrono::milliseconds(1) : std::chrono::milliseconds(200);
            queue_.changed.wait_for(lock, wait, [this] { return !queue_.finished.empty(); });
          }
        }
      }
    } catch (...) {
      {
        std::lock_guard<std::mutex> lock(queue_.mutex);
        queue_.stop = true;
      }
      if (local.joinable()) local.join();
      throw;
    }
    if (local.joinable()) local.join();
    if (queue_.local_error) std::rethrow_exception(queue_.local_error);

    std::vector<ScenarioSummary> rows(n);
    for (std::size_t i = 0; i < n; ++i)
      rows[i] = invalid_[i] ? *invalid_[i] : read_checkpoint_summary(checkpoint_->scenario_path(i));
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    write_sweep_file(opt_.output_path, spec_, rows, opt_.keep_runs ? checkpoint_.get() : nullptr,
                     {mpi_.size(), wall, resumed_});
    try {
      checkpoint_->remove();
    } catch (const Error& e) {
      std::cerr << "hexdyn: warning: " << e.what() << "\n";
    }
    std::size_t ok = 0;
    for (const auto& r : rows) ok += r.status == ScenarioStatus::kOk ? 1 : 0;
    std::cerr << "hexdyn: sweep: wrote " << opt_.output_path << ": " << n << " scenarios, " << ok
              << " ok, " << n - ok << " failed; " << computed_ << " computed by this run, "
              << resumed_ << " taken from the checkpoint; " << mpi_.size() << " rank"
              << (mpi_.size() > 1 ? "s" : "") << ", " << format_duration(wall) << "\n";
    return 0;
  }

 private:
  enum class State { kPending, kDone };

  void announce() const {
    const std::size_t n = spec_.scenario_count();
    std::ostringstream s;
    s << "hexdyn: sweep '" << spec_.name << "': " << n << " scenario" << (n == 1 ? "" : "s")
      << " over " << spec_.axes.size() << " ax" << (spec_.axes.size() == 1 ? "is" : "es") << " on "
      << mpi_.size() << " rank" << (mpi_.size() > 1 ? "s" : "") << "; " << queue_.pending.size()
      << " to compute";
    if (resumed_ > 0) s << ", " << resumed_ << " from the checkpoint";
    if (invalid_count_ > 0) {
      s << ", " << invalid_count_ << " with values out of range (recorded as failed";
      for (const auto& r : invalid_)
        if (r) {
          s << "; first: " << r->message;
          break;
        }
      s << ")";
    }
    std::cerr << s.str() << "\n";
  }

  void local_loop() {
    try {
      const std::string scratch = scratch_directory();
      while (const auto i = queue_.take()) {
        Finished f = compute(scenario_input(spec_, *i), opt_.keep_runs, 0, scratch);
        {
          std::lock_guard<std::mutex> lock(queue_.mutex);
          queue_.finished.push_back(std::move(f));
        }
        queue_.changed.notify_one();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(queue_.mutex);
      queue_.local_error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(queue_.mutex);
      queue_.local_running = false;
    }
    queue_.changed.notify_one();
  }

  /// Stores what the local thread finished; true if there was anything.
  bool store_local() {
    std::vector<Finished> got;
    {
      std::lock_guard<std::mutex> lock(queue_.mutex);
      got.swap(queue_.finished);
    }
    for (const Finished& f : got) store(f);
    return !got.empty();
  }

  /// Answers every waiting message of the worker ranks; true if there was any.
  bool serve_remote(int& remote_active) {
    bool any = false;
    for (;;) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (!flag) return any;
      any = true;
      const std::vector<char> msg = receive(st);
      if (st.MPI_TAG == kTagResult) store(unpack_result(msg, st.MPI_SOURCE));
      if (const auto i = queue_.take()) {
        send(pack_work(scenario_input(spec_, *i), opt_.keep_runs), st.MPI_SOURCE, kTagWork);
      } else {
        send(pack_stop(), st.MPI_SOURCE, kTagWork);
        --remote_active;
      }
    }
  }

  void store(const Finished& f) {
    checkpoint_->store(f.index, f.checkpoint);
    state_[f.index] = State::kDone;
    ++done_;
    ++computed_;
    if (f.status != ScenarioStatus::kOk) ++failed_;
    if (opt_.verbose) {
      std::cerr << "hexdyn: sweep: scenario " << scenario_id(spec_, f.index) << " "
                << status_name(f.status) << " (rank " << f.rank << ", " << std::fixed
                << std::setprecision(2) << f.wall_time_s << std::defaultfloat << " s)";
      if (!f.message.empty()) std::cerr << ": " << f.message;
      std::cerr << "\n";
    }
  }

  const SweepOptions& opt_;
  const MpiSession& mpi_;
  SweepSpec spec_;
  std::unique_ptr<Checkpoint> checkpoint_;
  std::vector<State> state_;
  std::vector<std::optional<ScenarioSummary>> invalid_;
  WorkQueue queue_;
  std::size_t done_ = 0, failed_ = 0, computed_ = 0, resumed_ = 0, invalid_count_ = 0;
};

}  // namespace

int run_sweep(const SweepOptions& options) {
  MpiSession mpi;
  if (mpi.rank() != 0) {
    int status = 0;
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (status != 0) return status;
    try {
      worker_loop(mpi.rank());
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
    std::cerr << "hexdyn: error: " << e.what() << "\n";
    status = e.exit_status();
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << e.what() << "\n";
    status = 4;
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (status != 0) return status;

  try {
    status = coordinator.run();
  } catch (const std::exception& e) {
    const bool input = dynamic_cast<const Error*>(&e) != nullptr;
    std::cerr << "hexdyn: " << (input ? "error: " : "internal error: ") << e.what()
              << " (finished scenarios are kept; continue with --resume)\n";
    status = input ? dynamic_cast<const Error&>(e).exit_status() : 4;
    if (mpi.size() > 1) MPI_Abort(MPI_COMM_WORLD, status);
    return status;
  }
  quiet_barrier();
  return status;
}

bool launched_as_secondary_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && *value != '\0') return std::strcmp(value, "0") != 0;
  }
  return false;
}

}  // namespace hexdyn
