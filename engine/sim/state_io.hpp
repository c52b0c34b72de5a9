// Saving and restoring a running simulation (the manuals' restart option): every piece of state a
// step reads, so that a run continued from a saved state is the uninterrupted run, bit for bit.
// The file is binary, for the same build of the engine and the same job spec (checked: counts of
// particles, walls, bonds and the step size must match).
#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "sim/simulation.hpp"

namespace dem {

class StateIO {
 public:
  static void write(const Simulation& sim, std::ostream& out);
  // Throws std::runtime_error naming what does not match or where the data ends.
  // A state is checked against its checksum (the last four bytes, CRC-32) and against the job (its
  // counts, indices and sizes) before anything in it is followed; after a failed read `sim` holds
  // part of the state and must be thrown away.
  static void read(Simulation& sim, std::istream& in);
  // Throws std::runtime_error when the state read is past the end of the run the spec asks for
  // (continuing it would write nothing and call that a finished run).
  static void require_within_run(const Simulation& sim);

  // To a file, atomically (written beside it, then renamed over it): a crash never leaves half a
  // state where the last whole one was.
  static void write_file(const Simulation& sim, const std::string& path);
  static void read_file(Simulation& sim, const std::string& path);
};

}  // namespace dem
