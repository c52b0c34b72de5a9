#include "server/checkpoint.hpp"

#include <boost/crc.hpp>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "server/durable_file.hpp"
#include "server/own_files.hpp"
#include "sim/state_io.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

// 2: the list of output files is followed by its own checksum line (in 1 an edited length or name
// went unnoticed, and resuming cut a good file short)
constexpr const char* kMagic = "DEM-CHECKPOINT 2";
constexpr const char* kMagicWithoutHeaderSum = "DEM-CHECKPOINT 1";
constexpr const char* kHeaderSum = "header-crc32 ";

std::uint32_t crc32(std::string_view bytes) {
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

// An output file's name as listed: a plain name inside the outputs folder, nothing that leads out.
bool plain_file_name(const std::string& name) {
  return !name.empty() && name[0] != '.' && name.find('/') == std::string::npos &&
         name.find('\\') == std::string::npos && name.find('\0') == std::string::npos;
}

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
  const std::uint32_t header_sum = crc32(out.view());
  out << kHeaderSum << header_sum << '\n';
  StateIO::write(sim, out);
  const std::string bytes = std::move(out).str();

  write_file_durably(path, bytes);
}

void resume_from_checkpoint(Simulation& sim, const std::string& output_folder, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("no checkpoint at " + path);
  std::string header;  // every line before the header's checksum, as written
  std::string line;
  std::getline(in, line);
  const bool summed = line == kMagic;
  if (!summed && line != kMagicWithoutHeaderSum)
    throw std::runtime_error(path + " is not a checkpoint (first line \"" + line.substr(0, 80) + "\")");
  header += line + '\n';
  std::getline(in, line);
  header += line + '\n';
  std::size_t count = 0;
  try {
    count = std::stoul(line);
  } catch (const std::exception&) {
    throw std::runtime_error(path + ": the count of output files (\"" + line.substr(0, 80) + "\") is not a number");
  }
  std::map<std::string, std::uintmax_t> sizes;
  for (std::size_t k = 0; k < count; ++k) {
    if (!std::getline(in, line)) throw std::runtime_error(path + ": the list of output files ends early");
    header += line + '\n';
    // "NAME SIZE", the size in decimal digits only ("0x10" read as 0 once cut a file to nothing)
    const std::size_t space = line.rfind(' ');
    const std::string name = space == std::string::npos ? line : line.substr(0, space);
    const std::string digits = space == std::string::npos ? "" : line.substr(space + 1);
    std::uintmax_t size = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), size);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size())
      throw std::runtime_error(path + ": the line \"" + line.substr(0, 80) +
                               "\" of its list of output files is not "
                               "NAME SIZE");
    if (!plain_file_name(name))
      throw std::runtime_error(path + ": listed output \"" + name.substr(0, 80) + "\" is not a plain file name");
    if (!sizes.emplace(name, size).second)
      throw std::runtime_error(path + ": output \"" + name.substr(0, 80) + "\" is listed twice");
  }
  if (summed) {
    std::getline(in, line);
    const std::string expected = kHeaderSum + std::to_string(crc32(header));
    if (line != expected)
      throw std::runtime_error(path +
                               ": the checksum of its list of output files does not match the list: the file was "
                               "changed or damaged, and the job cannot be continued from it");
  }
  StateIO::read(sim, in);  // first: a state that does not fit leaves the files as they are
  StateIO::require_within_run(sim);
  // resuming cuts and appends to these files: a link planted among them would have it cut and
  // write a file anywhere
  if (!is_own_folder(output_folder) || !is_own_folder(fs::path(output_folder).parent_path()))
    throw std::runtime_error(output_folder +
                             " or its job folder is not a folder of the job's own (a link?): the job "
                             "cannot be continued");
  for (const fs::directory_entry& e : fs::directory_iterator(output_folder))
    if (!is_own_file(e.path()))
      throw std::runtime_error("output " + e.path().string() +
                               " is not a regular file of the job's own (a link, a folder, or a file with another "
                               "name elsewhere): the job cannot be continued");

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
