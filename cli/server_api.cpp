#include "cli/server_api.hpp"

#include <cstdio>

#include "cli/terminal_text.hpp"

#include <boost/beast/http/status.hpp>

namespace dem::cli {

ApiError::ApiError(int status, const std::string& message, std::vector<std::string> problems)
    : std::runtime_error(message), status_(status), problems_(std::move(problems)) {}

std::string describe(const ApiError& e) {
  namespace http = boost::beast::http;
  const auto reason = http::obsolete_reason(http::int_to_status(static_cast<unsigned>(e.status())));
  std::string text = std::to_string(e.status());
  if (!reason.empty() && reason != "<unknown-status>") text += " " + std::string(reason);
  return text + ": " + e.what();
}

ApiError api_error(const client::Response& response) {
  const nlohmann::json body = nlohmann::json::parse(response.body, nullptr, false);
  std::string message;
  std::vector<std::string> problems;
  if (body.is_object() && body.contains("error") && body["error"].is_string()) {
    message = printable(body["error"].get<std::string>());
    if (body.contains("problems") && body["problems"].is_array())
      for (const auto& p : body["problems"])
        if (p.is_string()) problems.push_back(printable(p.get<std::string>()));
  } else {
    // not dem-server's error JSON (a proxy's page, say): its first line is the best clue
    message = printable(response.body.substr(0, response.body.find('\n')).substr(0, 200));
    if (message.empty()) message = "(no message)";
  }
  return ApiError(response.status, message, std::move(problems));
}

client::Response ServerApi::send(const std::string& method, const std::string& target, const std::string& body,
                                 const std::string& content_type, const client::Headers& headers) const {
  client::Response response = http_.request(method, target, body, content_type, headers);
  if (response.status < 200 || response.status >= 300) throw api_error(response);
  return response;
}

nlohmann::json ServerApi::call(const std::string& method, const std::string& target) const {
  return json_of(send(method, target), target);
}

nlohmann::json ServerApi::json_of(const client::Response& response, const std::string& target) const {
  nlohmann::json json = nlohmann::json::parse(response.body, nullptr, false);
  if (json.is_discarded()) throw client::ClientError(http_.url() + target + ": the answer is not JSON");
  return json;
}

std::string job_target(std::int64_t id) { return "/api/v1/jobs/" + std::to_string(id); }

void print_json_line(const nlohmann::json& value) {
  std::printf("%s\n", value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
}

}  // namespace dem::cli
