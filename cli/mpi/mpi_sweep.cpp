// librigidity_mpi.so: the MPI side of `rigidity sweep` (cli/mpi_sweep.hpp). Rank 0's main
// thread makes every MPI call (MPI_THREAD_FUNNELED); a second thread of rank 0 runs cases.
#include "mpi_sweep.hpp"

#include <mpi.h>

#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rigidity/run_recorder.hpp"

namespace rigidity::cli {
namespace {

constexpr int kTagRow = 1;   // rank r -> rank 0: a finished row ("EXIT_CODE ROW"), or "" for a case cut short
constexpr int kTagCase = 2;  // rank 0 -> rank r: a case index to run
constexpr int kTagStop = 3;  // rank 0 -> rank r: no more cases

/// How long rank 0's MPI thread waits between looks for a row while none has come.
constexpr auto kPollInterval = std::chrono::microseconds(200);
/// Cases sent ahead to each other rank: it starts the next while rank 0 takes its row.
constexpr std::size_t kInFlight = 2;

/// The message of a row: "EXIT_CODE ROW", or empty for a case cut short by Ctrl-C (it runs
/// again next time).
std::string row_message(const Sweep& sweep, const SweepRow& row) {
  return row.status == "interrupted" ? std::string() : std::to_string(row.exit_code) + " " + sweep_csv_row(sweep, row);
}

class Session final : public MpiSweep {
 public:
  Session() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    by_rank_.assign(static_cast<std::size_t>(size_), 0);
  }
  ~Session() override {
    // Rank 0 leaving before it dispatched (the sweep file did not load, the table was refused)
    // releases the ranks waiting for their first case.
    if (rank_ == 0 && !dispatched_)
      for (int r = 1; r < size_; ++r) MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG, r, kTagStop, MPI_COMM_WORLD);
    MPI_Finalize();
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  [[nodiscard]] int rank() const override { return rank_; }
  [[nodiscard]] int size() const override { return size_; }
  [[nodiscard]] std::vector<std::size_t> cases_by_rank() const override { return by_rank_; }

  [[nodiscard]] SweepExecutor dispatcher(const Sweep& sweep, const std::string& out_dir) override {
    return [this, &sweep, out_dir](const std::vector<std::size_t>& pending, const SweepRowSink& done) {
      dispatched_ = true;
      std::mutex lock;  // guards next, done and by_rank_
      std::size_t next = 0;
      const auto take = [&]() -> std::optional<std::size_t> {
        if (next >= pending.size() || interrupt_requested()) return std::nullopt;
        return pending[next++];
      };
      const auto finish = [&](int rank, std::size_t index, int exit_code, const std::string& line) {
        done(index, exit_code, line);
        ++by_rank_[static_cast<std::size_t>(rank)];
      };

      // Every other rank has kInFlight cases sent ahead, before rank 0 takes any: every rank
      // computes when there are enough cases, and a rank finds its next case waiting when it
      // sends a row back.
      const auto ranks = static_cast<std::size_t>(size_);
      std::vector<std::deque<std::size_t>> assigned(ranks);
      std::vector<bool> stopped(ranks, false);
      std::size_t outstanding = 0;
      const auto refill = [&](int r) {
        const auto k = static_cast<std::size_t>(r);
        if (stopped[k]) return;
        if (const std::optional<std::size_t> index = take()) {
          assigned[k].push_back(*index);
          ++outstanding;
          const unsigned long value = *index;
          MPI_Send(&value, 1, MPI_UNSIGNED_LONG, r, kTagCase, MPI_COMM_WORLD);
        } else {
          MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG, r, kTagStop, MPI_COMM_WORLD);
          stopped[k] = true;
        }
      };
      for (std::size_t k = 0; k < kInFlight; ++k)
        for (int r = 1; r < size_; ++r) refill(r);
      // Rank 0's own first case is taken now, before any row comes back: however slowly its
      // thread starts, the other ranks' refills cannot take every case before it has one.
      std::optional<std::size_t> first = take();

      std::thread local([&]() {
        for (std::optional<std::size_t> index = first; index;) {
          const SweepRow row = run_sweep_case(sweep, *index, sweep_case_dir(sweep, out_dir, *index));
          if (row.status == "interrupted") return;  // cut short: run again next time
          const std::string line = sweep_csv_row(sweep, row);
          const std::lock_guard<std::mutex> guard(lock);
          finish(0, *index, row.exit_code, line);
          index = take();
        }
      });

      while (outstanding > 0) {
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kTagRow, MPI_COMM_WORLD, &arrived, &status);
        if (arrived == 0) {
          std::this_thread::sleep_for(kPollInterval);
          continue;
        }
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string message(static_cast<std::size_t>(length), '\0');
        MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagRow, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::deque<std::size_t>& queue = assigned[static_cast<std::size_t>(status.MPI_SOURCE)];
        const std::size_t index = queue.front();  // a rank runs its cases in the order sent
        queue.pop_front();
        --outstanding;
        const std::lock_guard<std::mutex> guard(lock);
        if (!message.empty()) {
          const std::size_t space = message.find(' ');
          finish(status.MPI_SOURCE, index, std::stoi(message.substr(0, space)), message.substr(space + 1));
        }
        refill(status.MPI_SOURCE);
      }
      for (int r = 1; r < size_; ++r)
        if (!stopped[static_cast<std::size_t>(r)]) MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG, r, kTagStop, MPI_COMM_WORLD);
      local.join();
    };
  }

  std::size_t work(const Sweep& sweep, const std::string& out_dir) override {
    std::size_t run = 0;
    for (;;) {
      MPI_Status status;
      unsigned long index = 0;
      MPI_Recv(&index, 1, MPI_UNSIGNED_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
      if (status.MPI_TAG == kTagStop) return run;
      const SweepRow row = run_sweep_case(sweep, index, sweep_case_dir(sweep, out_dir, index));
      ++run;
      const std::string message = row_message(sweep, row);
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagRow, MPI_COMM_WORLD);
    }
  }

 private:
  int rank_ = 0, size_ = 1;
  std::vector<std::size_t> by_rank_;
  bool dispatched_ = false;
};

}  // namespace
}  // namespace rigidity::cli

extern "C" __attribute__((visibility("default"))) rigidity::cli::MpiSweep* rigidity_mpi_sweep_open() {
  return new rigidity::cli::Session();
}
