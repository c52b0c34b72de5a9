#include "server/checkpoint.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "server/durable_file.hpp"
#include "sim/state_io.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

constexpr const char* kMagic = "DEM-CHECKPOINT 1";

// The length of every output file, each synced first: the checkpoint never counts bytes a machine
// crash could take back.
std::map<std::string, std::uintmax_t> output_sizes(const std::string& folder) {
  std::map<std::string, std::uintmax_t> sizes;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    if (!e.is_regular_file()) continue;
    sync_path(e.path());
    sizes[e.path().filename().string()] = e.file_size();
  }
  return sizes;
}

}  // namespace

void write_checkpoint(const Simulation& sim, const std::string& output_folder, const std::string& path) {
  std::ostringstream out;
  const std::map<std::string, std::uintmax_t> sizes = output_sizes(output_folder);
  out << kMagic << '\n' << sizes.size() << '\n';
  for (const auto& [name, size] : sizes) out << name << ' ' << size << '\n';
  StateIO::write(sim, out);
  const std::string bytes = std::move(out).str();

  write_file_durably(path, bytes);
}

void resume_from_checkpoint(Simulation& sim, const std::string& output_folder, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("no checkpoint at " + path);
  std::string magic;
  std::getline(in, magic);
  if (magic != kMagic) throw std::runtime_error(path + " is not a checkpoint (first line \"" + magic + "\")");
  std::size_t count = 0;
  in >> count;
  std::map<std::string, std::uintmax_t> sizes;
  for (std::size_t k = 0; k < count; ++k) {
    std::string name;
    std::uintmax_t size = 0;
    if (!(in >> name >> size)) throw std::runtime_error(path + ": the list of output files ends early");
    sizes[name] = size;
  }
  in.get();                // the newline before the state
  StateIO::read(sim, in);  // first: a state that does not fit leaves the files as they are
  StateIO::require_within_run(sim);

  for (const fs::directory_entry& e : fs::directory_iterator(output_folder)) {
    if (!e.is_regular_file()) continue;
    const auto found = sizes.find(e.path().filename().string());
    if (found != sizes.end() && e.file_size() < found->second)  // lost (a machine crash): never pad
      throw std::runtime_error("output file " + found->first + " is shorter than at the checkpoint " + path +
                               ": the job cannot be continued from it");
  }
  for (const auto& [name, size] : sizes)
    if (!fs::exists(fs::path(output_folder) / name))
      throw std::runtime_error("output file " + name + " of the checkpoint " + path + " is missing");
  for (const fs::directory_entry& e : fs::directory_iterator(output_folder)) {
    if (!e.is_regular_file()) continue;
    const auto found = sizes.find(e.path().filename().string());
    if (found == sizes.end())
      fs::remove(e.path());  // created after the checkpoint
    else if (e.file_size() != found->second)
      fs::resize_file(e.path(), found->second);  // cut back
  }
}

}  // namespace dem::server
