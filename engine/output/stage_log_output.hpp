// Stages.dat (project-defined, docs/formats.md): when each stage of a staged run began, written at
// the stage's first frame (every stage ends with one). A continued run reads the last stage the
// file lists and goes on from there: no line twice, none left out, wherever the state was saved.
#pragma once

#include <string>

#include "output/legacy_output.hpp"
#include "sim/runner.hpp"

namespace dem {

class StageLogWriter final : public Observer {
 public:
  static bool wanted(const Simulation& sim) { return !sim.scene().stages.empty(); }
  explicit StageLogWriter(const std::string& path, bool append = false);
  void frame(const Simulation& sim) override;

 private:
  int logged_ = -1;  // the last stage written (0-based)
  OutputFile file_;
};

}  // namespace dem
