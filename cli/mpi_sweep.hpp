#pragma once
/// `rigidity sweep` under mpirun. The MPI side lives in a module of its own,
/// librigidity_mpi.so (cli/mpi/mpi_sweep.cpp), loaded only when the command runs under mpirun
/// or srun: the `rigidity` executable links no MPI library.
///
/// Every rank computes cases. Rank 0 writes the table: it gives each other rank a first case,
/// then hands out the next case to whichever rank sends back a row, while a thread of its own
/// runs cases from the same queue.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "rigidity/sweep.hpp"

namespace rigidity::cli {

/// MPI for the life of the object (MPI_Init_thread in the module's factory, MPI_Finalize in
/// the destructor).
class MpiSweep {
 public:
  virtual ~MpiSweep() = default;
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  /// Rank 0: the executor that spreads the pending cases over every rank, rank 0 included.
  [[nodiscard]] virtual SweepExecutor dispatcher(const Sweep& sweep, const std::string& out_dir) = 0;
  /// Ranks 1..N-1: run the cases rank 0 hands out until it says stop; returns the number run.
  virtual std::size_t work(const Sweep& sweep, const std::string& out_dir) = 0;
  /// Rank 0, after the dispatcher has run: the cases each rank computed, by rank.
  [[nodiscard]] virtual std::vector<std::size_t> cases_by_rank() const = 0;
};

/// The module's factory, exported as kMpiSweepFactory.
using MpiSweepFactory = MpiSweep* (*)();
inline constexpr const char* kMpiSweepFactory = "rigidity_mpi_sweep_open";
/// The module's file name, looked for in the directory of librigidity_sweep (beside librigidity).
inline constexpr const char* kMpiSweepModule = "librigidity_mpi.so";

/// Started by mpirun or srun (which set these), not by hand.
[[nodiscard]] bool launched_by_mpi();

/// Loads the module and starts MPI. \throws CommandError naming the module when it cannot be loaded
[[nodiscard]] std::unique_ptr<MpiSweep> open_mpi_sweep();

}  // namespace rigidity::cli
