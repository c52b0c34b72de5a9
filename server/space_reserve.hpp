// A little disk space held back in the data folder for the job table: when the disk fills, the
// file is given up so that the table can still record how jobs ended (a job that failed on a full
// disk came back "interrupted", its reason lost, when the server restarted on the still-full disk),
// and taken again once there is room.
#pragma once

#include <cstdint>
#include <filesystem>

namespace dem::server {

class SpaceReserve {
 public:
  SpaceReserve(std::filesystem::path path, std::uint64_t bytes);
  // Frees the space (deletes the file); false when there was none held.
  bool release();
  // Takes the space again when the file system has it to spare (well over the reserve); true when held.
  bool restore();
  bool held() const { return held_; }

 private:
  std::filesystem::path path_;
  std::uint64_t bytes_;
  bool held_ = false;
};

}  // namespace dem::server
