// The REST API of dem-server as the client verbs use it: a 2xx answer becomes its JSON, any other
// answer an ApiError carrying what the server said, so every verb reports failures the same way.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/http_client.hpp"

namespace dem::cli {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message, std::vector<std::string> problems);
  int status() const { return status_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  int status_;
  std::vector<std::string> problems_;
};

// "404 Not Found: no job 7" (the status, its reason and the server's message).
std::string describe(const ApiError& e);

// "/api/v1/jobs/ID": a job's address, under which its actions, log and artifacts are.
std::string job_target(std::int64_t id);

// Prints one JSON document on one line of standard output (--json is JSON Lines: --wait --json
// prints two), the server's text's invalid UTF-8 replaced, not thrown on.
void print_json_line(const nlohmann::json& value);

// Turns a non-2xx response into an ApiError (the server's {"error", "problems"} when it sent them).
ApiError api_error(const client::Response& response);

class ServerApi {
 public:
  explicit ServerApi(client::HttpClient http) : http_(std::move(http)) {}

  // The answer when it is a 2xx; throws ApiError otherwise, client::ClientError when unreachable.
  client::Response send(const std::string& method, const std::string& target, const std::string& body = "",
                        const std::string& content_type = "", const client::Headers& headers = {}) const;
  // The JSON of a 2xx answer to a request without a body.
  nlohmann::json call(const std::string& method, const std::string& target) const;
  // The JSON of an answer from send() (throws client::ClientError when it is not JSON).
  nlohmann::json json_of(const client::Response& response, const std::string& target) const;

  const client::HttpClient& http() const { return http_; }

 private:
  client::HttpClient http_;
};

}  // namespace dem::cli
