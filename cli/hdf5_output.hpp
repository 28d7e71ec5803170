// run.h5 beside a run's CSV files (outputs.hdf5: true): see hdf5_output.cpp for its layout.
#pragma once

#include <string>

#include "rigidity/units.hpp"

namespace rigidity::cli {

/// Writes `dir`/run.h5 from the CSV files and summary.json a run has written into `dir`, in the
/// scene's `units`; whole or not at all. \throws std::runtime_error (an HDF5 failure)
void write_hdf5(const std::string& dir, UnitSystem units);

}  // namespace rigidity::cli
