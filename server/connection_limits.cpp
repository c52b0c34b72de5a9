#include "server/connection_limits.hpp"

namespace dem::server {

std::shared_ptr<void> ConnectionLimits::admit(const std::string& client, std::string& why) {
  std::lock_guard lock(mutex_);
  std::size_t& mine = per_client_[client];
  if (total_ >= max_total_) {
    why = "the server holds " + std::to_string(total_) + " connections, its limit (--max-connections)";
  } else if (mine >= max_per_client_) {
    why = "this client holds " + std::to_string(mine) +
          " connections, the limit for one address (--max-connections-per-client)";
  } else {
    ++total_;
    ++mine;
    return std::shared_ptr<void>(this, [this, client](void*) { release(client); });
  }
  if (mine == 0) per_client_.erase(client);
  return nullptr;
}

void ConnectionLimits::release(const std::string& client) {
  std::lock_guard lock(mutex_);
  --total_;
  const auto it = per_client_.find(client);
  if (it != per_client_.end() && --it->second == 0) per_client_.erase(it);
}

}  // namespace dem::server
