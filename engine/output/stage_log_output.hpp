// Stages.dat (project-defined, docs/formats.md): when each stage of a staged run began.
#pragma once

#include <string>

#include "output/legacy_output.hpp"
#include "sim/runner.hpp"

namespace dem {

class StageLogWriter final : public Observer {
 public:
  static bool wanted(const Simulation& sim) { return !sim.scene().stages.empty(); }
  StageLogWriter(const std::string& path, bool append = false);
  void frame(const Simulation&) override {}
  void stage_begun(const Simulation& sim) override;

 private:
  OutputFile file_;
};

}  // namespace dem
