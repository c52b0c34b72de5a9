// One HTTP connection: reads requests (bodies up to a limit), checks the token, and answers from
// the REST API or the viewer's files, or hands the socket to a frame WebSocket.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <chrono>

#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>

#include "server/api_routes.hpp"
#include "server/connection_limits.hpp"
#include "server/frame_hub.hpp"
#include "server/request_log.hpp"

namespace dem::server {

// What every connection shares.
struct ServerState {
  JobManager& jobs;
  StudyManager& studies;
  FrameHub& frames;
  std::string openapi;
  std::filesystem::path web;
  std::filesystem::path cases;
  std::string token;
  std::size_t max_body;
  ConnectionLimits& connections;
  boost::asio::thread_pool& checks;                     // where submissions are checked (not the connections' threads)
  std::chrono::steady_clock::duration request_timeout;  // for a request's header; its body gets 60 s more
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  // `ticket`: the connection's place within the limits; null: answer 503 and close.
  HttpSession(boost::asio::ip::tcp::socket&& socket, ServerState& state, std::shared_ptr<void> ticket,
              std::string refused_why);
  void run();

 private:
  void read();
  void on_header(boost::beast::error_code ec, std::size_t bytes);
  void read_body();
  void on_read(boost::beast::error_code ec, std::size_t bytes);
  void on_read_error(boost::beast::error_code ec);
  void refuse(http::response<http::string_body> res);
  static bool local_request(const http::request_header<>& head);
  static bool same_origin_or_none(const http::request_header<>& head);
  void drain();
  void send(http::message_generator message);
  void on_write(bool keep_alive, boost::beast::error_code ec, std::size_t bytes);
  void upgrade(const Request& request, const Target& target);
  http::message_generator answer(const Request& req, const Target& target);  // the API's or the viewer's
  void close();
  void start_deadline(std::chrono::steady_clock::duration within);
  void on_deadline(boost::beast::error_code ec);
  bool timed_out(boost::beast::error_code ec);

  boost::beast::tcp_stream stream_;
  boost::asio::steady_timer deadline_;  // a request must come whole in time (slowloris)
  bool deadline_passed_ = false;
  std::shared_ptr<void> ticket_;
  std::string refused_why_;
  boost::beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::array<char, 4096> scratch_;
  ServerState& state_;
  std::string client_;            // the peer's address, for the request log
  RequestLine request_line_;      // of the request being answered
  unsigned answered_status_ = 0;  // of the answer being written (read from its bytes)
};

}  // namespace dem::server
