#include "results/results_json.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace dem::results {
namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json pieces_json(const MotionResults& m) {
  nlohmann::json quantiles = nlohmann::json::array();
  for (std::size_t k = 0; k < m.piece_travel.size(); ++k)
    quantiles.push_back({{"fraction", static_cast<double>(k) / static_cast<double>(m.piece_travel.size() - 1)},
                         {"travel", m.piece_travel[k]}});
  nlohmann::json j = {{"count", m.pieces}, {"travelMean", m.piece_travel_mean}, {"quantiles", quantiles}};
  if (m.piece_travel.size() == MotionResults::kPieceQuantiles) {  // 0, 0.05, ..., 1
    j["travelMedian"] = m.piece_travel[10];
    j["travelP90"] = m.piece_travel[18];
    j["travelMax"] = m.piece_travel[20];
  }
  return j;
}

nlohmann::json motion_json(const MotionResults& m) {
  return {
      {"reference", {{"step", m.reference_step}, {"time", m.reference_time}, {"stage", m.reference_stage}}},
      {"direction", vec(m.direction)},
      {"centreOfMass",
       {{"start", vec(m.com_start)},
        {"end", vec(m.com_end)},
        {"travel", m.com_travel},
        {"drop", m.com_drop},
        {"travelAngle", m.com_travel_angle}}},
      {"front", {{"start", m.front_start}, {"end", m.front_end}, {"advance", m.front_end - m.front_start}}},
      {"runout", {{"length", m.runout_length}, {"height", m.fall_height}, {"heightOverLength", m.h_over_l}}},
      {"deposit",
       {{"length", m.deposit_length}, {"width", m.deposit_width}, {"area", m.deposit_area}, {"cell", m.deposit_cell}}},
      {"pieces", pieces_json(m)},
  };
}

nlohmann::json source_json(const SourceResults& s) {
  nlohmann::json heights = nlohmann::json::array();
  for (std::size_t k = 0; k < s.heights.size(); ++k)
    heights.push_back(
        {{"fraction", static_cast<double>(k) / static_cast<double>(s.heights.size() - 1)}, {"height", s.heights[k]}});
  nlohmann::json j = {{"name", s.name},
                      {"inserted", s.inserted},
                      {"mass", s.mass},
                      {"crowdedBatches", s.crowded_batches},
                      {"heights", heights}};
  if (s.total_reached) j["totalReached"] = *s.total_reached;
  if (!s.heights.empty()) {
    j["heightMean"] = s.height_mean;
    j["heightMedian"] = s.heights[s.heights.size() / 2];
  }
  return j;
}

nlohmann::json fragments_json(const FragmentResults& f) {
  nlohmann::json sizes = nlohmann::json::array();
  for (const FragmentBin& b : f.sizes)
    sizes.push_back({{"minParticles", b.min_particles},
                     {"maxParticles", b.max_particles},
                     {"fragments", b.fragments},
                     {"mass", b.mass}});
  return {{"count", f.count},
          {"initialCount", f.initial_count},
          {"largestMassFraction", f.largest_mass_fraction},
          {"sizes", sizes},
          {"crushedMass", f.crushed_mass},
          {"crushedMassFraction", f.crushed_mass_fraction},
          {"bonds",
           {{"initial", f.bonds_initial},
            {"intact", f.bonds_intact},
            {"brokenTension", f.bonds_broken_tension},
            {"brokenShear", f.bonds_broken_shear}}}};
}

nlohmann::json loaded_wall_json(const LoadedWallResults& w) {
  nlohmann::json cycles = nlohmann::json::array();
  for (const LoadCycle& c : w.cycles)
    cycles.push_back({{"cycle", c.cycle},
                      {"endStep", c.end_step},
                      {"endTime", c.end_time},
                      {"settlement", c.displacement},
                      {"peak", c.peak_displacement},
                      {"resilient", c.resilient},
                      {"forceMin", c.force_min},
                      {"forceMax", c.force_max}});
  nlohmann::json j = {{"wall", w.wall},
                      {"index", w.index},
                      {"cyclic", w.cyclic},
                      {"startTime", w.start_time},
                      {"startDisplacement", w.start_displacement},
                      {"endSettlement", w.end_displacement},
                      {"forceMin", w.force_min},
                      {"forceMax", w.force_max},
                      {"cycles", cycles}};
  if (!w.cycles.empty()) {
    j["permanentSettlement"] = w.cycles.back().displacement;
    j["resilient"] = w.cycles.back().resilient;
  }
  return j;
}

// -0 is 0: a force that was never pushed (a stone's press before it touches) is written 0, not -0.0
void without_negative_zeros(nlohmann::json& j) {
  if (j.is_number_float() && j.get<double>() == 0.0) {
    j = 0.0;
  } else if (j.is_structured()) {
    for (nlohmann::json& child : j) without_negative_zeros(child);
  }
}

}  // namespace

nlohmann::json to_json(const RunResults& r) {
  nlohmann::json j = {
      {"status", r.ok ? "completed" : "stopped"},
      {"particles", r.particles},
      {"steps", r.steps},
      {"simulatedTime", r.simulated_time},
      {"timeStep", r.time_step},
      {"runSeconds", r.run_seconds},
      {"energy",
       {{"start", r.energy_start},
        {"end", r.energy_end},
        {"input", r.energy_input},
        {"dissipated", r.energy_dissipated},
        {"kineticEnd", r.kinetic_end}}},
  };
  if (!r.ok) j["error"] = r.error;
  if (!r.notes.empty()) j["notes"] = r.notes;
  if (r.motion) j["motion"] = motion_json(*r.motion);
  if (r.fragments) j["fragments"] = fragments_json(*r.fragments);
  if (!r.loaded_walls.empty()) {
    j["loadedWalls"] = nlohmann::json::array();
    for (const LoadedWallResults& w : r.loaded_walls) j["loadedWalls"].push_back(loaded_wall_json(w));
  }
  if (!r.sources.empty()) {
    j["sources"] = nlohmann::json::array();
    for (const SourceResults& s : r.sources) j["sources"].push_back(source_json(s));
  }
  without_negative_zeros(j);
  return j;
}

void write_results_file(const RunResults& r, const std::string& folder) {
  const std::filesystem::path path = std::filesystem::path(folder) / kResultsName;
  const std::filesystem::path temporary = std::filesystem::path(folder) / ".results.json.part";
  const std::string text = to_json(r).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  std::FILE* f = std::fopen(temporary.c_str(), "wb");
  bool ok = f != nullptr && std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (f != nullptr) ok = std::fclose(f) == 0 && ok;
  std::error_code error;
  if (ok) std::filesystem::rename(temporary, path, error);
  if (!ok || error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("cannot write " + path.string() + " (a full disk?)");
  }
}

}  // namespace dem::results
