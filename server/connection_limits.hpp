// How many connections the server holds, in all and from each client address. A connection past
// either limit is answered 503 with Retry-After and closed: 20,000 connections from one client once
// used up the process's file descriptors.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace dem::server {

class ConnectionLimits {
 public:
  ConnectionLimits(std::size_t total, std::size_t per_client) : max_total_(total), max_per_client_(per_client) {}

  // A ticket held for the life of a connection from `client` (its address), or null with `why`
  // when a limit is reached. The limits object must outlive its tickets.
  std::shared_ptr<void> admit(const std::string& client, std::string& why);

 private:
  void release(const std::string& client);

  std::mutex mutex_;
  std::size_t max_total_, max_per_client_;
  std::size_t total_ = 0;
  std::map<std::string, std::size_t> per_client_;
};

}  // namespace dem::server
