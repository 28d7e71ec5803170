// Loading librigidity_mpi.so for `rigidity sweep` under mpirun (cli/mpi_sweep.hpp).
#include "mpi_sweep.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"

namespace rigidity::cli {

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

std::unique_ptr<MpiSweep> open_mpi_sweep() {
  // The module is installed beside librigidity_sweep, which holds sweep_case_dir (the build
  // tree puts them together too).
  Dl_info library{};
  const auto* anchor = reinterpret_cast<const void*>(&sweep_case_dir);
  std::filesystem::path module(kMpiSweepModule);
  if (::dladdr(anchor, &library) != 0 && library.dli_fname != nullptr)
    module = std::filesystem::path(library.dli_fname).parent_path() / kMpiSweepModule;
  // Never closed: MPI_Finalize runs from the session's destructor, and Open MPI's libraries
  // stay loaded to the end of the process.
  void* handle = ::dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* reason = ::dlerror();
    throw CommandError(kExitInternal, "started by mpirun, but the MPI sweep module cannot be loaded (" +
                                          std::string(reason ? reason : module.string()) +
                                          "); build rigidity with MPI (RIGIDITY_MPI=ON), or run the sweep "
                                          "without mpirun (-j N threads)");
  }
  const auto factory = reinterpret_cast<MpiSweepFactory>(::dlsym(handle, kMpiSweepFactory));
  if (factory == nullptr)
    throw CommandError(kExitInternal,
                       module.string() + " has no " + kMpiSweepFactory + "; it is not rigidity's MPI module");
  return std::unique_ptr<MpiSweep>(factory());
}

}  // namespace rigidity::cli
