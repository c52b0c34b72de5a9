// What the server's integration tests share: a temporary data folder, a running dem-server, job
// specs of a chosen size and length, and waiting for a job to reach a state.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "client/http_client.hpp"
#include "support/server_process.hpp"

namespace dem::test {

namespace fs = std::filesystem;

// Spheres on a hexagonal lattice poured into a box (the demo case, smaller): `radius` sets how many
// (0.012 m: 486), `steps` how long, a frame every `every` steps.
inline std::string pouring_spec(double radius, long steps, long every, bool force_chains = false) {
  std::ostringstream s;
  s << R"({
  "name": "pouring test",
  "materials": [{"name": "granite", "density": 2650, "youngsModulus": 5e7, "poissonRatio": 0.25},
                {"name": "steel", "rigid": true}],
  "interactions": [{"a": "granite", "b": "granite", "restitution": 0.5, "friction": 0.5, "rollingFriction": 0.05},
                   {"a": "granite", "b": "steel", "restitution": 0.5, "friction": 0.4, "rollingFriction": 0.05}],
  "contact": {"normal": "HERTZ", "rolling": "EPSD"},
  "lattices": [{"kind": "HEX", "min": {"x": -0.1, "y": -0.1, "z": 0.05}, "max": {"x": 0.1, "y": 0.1, "z": 0.35},
                "radius": )"
    << radius << R"(, "spacing": 1.3, "material": "granite", "velocity": {"x": 0.3}}],
  "walls": [
    {"name": "floor", "material": "steel", "plate": {"c1": {"x": -0.15, "y": -0.15}, "c2": {"x": 0.15, "y": -0.15}, "c3": {"x": 0.15, "y": 0.15}, "c4": {"x": -0.15, "y": 0.15}}},
    {"name": "left", "material": "steel", "plane": {"point": {"x": -0.15}, "normal": {"x": 1}}},
    {"name": "right", "material": "steel", "plane": {"point": {"x": 0.15}, "normal": {"x": -1}}},
    {"name": "front", "material": "steel", "plane": {"point": {"y": -0.15}, "normal": {"y": 1}}},
    {"name": "back", "material": "steel", "plane": {"point": {"y": 0.15}, "normal": {"y": -1}}}],
  "gravity": {"z": -9.81},
  "numerics": {"threads": 1},
  "time": {"steps": )"
    << steps << R"(},
  "outputs": {"everySteps": )"
    << every << R"(, "forceChains": )" << (force_chains ? "true" : "false") << R"(}
})";
  return s.str();
}

// `text` with its first `from` replaced by `to` (a test fails if there is none).
inline std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "\"" << from << "\" is not in the text";
    return text;
  }
  return text.substr(0, at) + to + text.substr(at + from.size());
}

inline std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A fresh folder under the system's temporary folder, removed at the end.
class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("dem_server_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    server_.reset();
    fs::remove_all(dir_);
  }

  void start_server(const std::vector<std::string>& extra = {}) {
    server_ = std::make_unique<ServerProcess>(dir_ / "data", extra);
    client_ = std::make_unique<client::HttpClient>(server_->url());
  }

  nlohmann::json submit_json(const std::string& spec, const client::Headers& headers = {}) {
    const client::Response r = client_->request("POST", "/api/jobs", spec, "application/json", headers);
    EXPECT_TRUE(r.status == 201 || r.status == 200) << r.status << " " << r.body;
    return nlohmann::json::parse(r.body);
  }

  nlohmann::json job(long id) { return nlohmann::json::parse(client_->get("/api/jobs/" + std::to_string(id)).body); }

  // Polls until the job is in one of `states` (comma-separated), at most `seconds`.
  nlohmann::json wait_for(long id, const std::string& states, double seconds = 120) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    nlohmann::json j;
    while (std::chrono::steady_clock::now() < end) {
      j = job(id);
      const std::string state = j.value("state", std::string());
      for (std::size_t at = 0; at <= states.size();) {  // the comma-separated names
        std::size_t end = states.find(',', at);
        if (end == std::string::npos) end = states.size();
        if (states.compare(at, end - at, state) == 0) return j;
        at = end + 1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ADD_FAILURE() << "job " << id << " did not reach " << states << " in " << seconds << " s: " << j.dump();
    return j;
  }

  // Runs `dem run` on `spec` into DIR/name and returns the folder.
  fs::path dem_run(const std::string& spec, const std::string& name) {
    const fs::path spec_file = dir_ / (name + ".json"), out = dir_ / name;
    write_text(spec_file, spec);
    const std::string command = std::string(DEM_BINARY_DIR) + "/dem run '" + spec_file.string() + "' --out '" +
                                out.string() + "' --quiet > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return out;
  }

  fs::path dir_;
  std::unique_ptr<ServerProcess> server_;
  std::unique_ptr<client::HttpClient> client_;
};

}  // namespace dem::test
