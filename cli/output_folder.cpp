#include "cli/output_folder.hpp"

#include <stdexcept>
#include <system_error>

namespace dem::cli {

namespace fs = std::filesystem;

void make_output_folder(const fs::path& folder, const std::string& option) {
  const std::string named = option + " " + folder.string() + ": ";
  // the nearest of the path's folders that is there: a file there stops the path
  for (fs::path at = folder; !at.empty(); at = at.parent_path()) {
    std::error_code ec;
    const fs::file_status status = fs::status(at, ec);
    if (std::error_code link_ec; fs::is_symlink(fs::symlink_status(at, link_ec)) && !fs::exists(status))
      throw std::runtime_error(named + at.string() + " is a link to " + fs::read_symlink(at, link_ec).string() +
                               ", which is not there");
    if (ec || !fs::exists(status)) {
      if (at == at.parent_path()) break;
      continue;
    }
    if (!fs::is_directory(status)) throw std::runtime_error(named + at.string() + " is a file, not a folder");
    break;
  }
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw std::runtime_error(named + "cannot make the folder: " + ec.message());
}

}  // namespace dem::cli
