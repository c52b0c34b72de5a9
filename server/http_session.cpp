#include "server/http_session.hpp"

#include <chrono>

#include <boost/asio/dispatch.hpp>
#include <boost/beast/websocket.hpp>

#include "server/frame_session.hpp"
#include "server/static_files.hpp"

namespace dem::server {
namespace beast = boost::beast;
namespace websocket = beast::websocket;

HttpSession::HttpSession(boost::asio::ip::tcp::socket&& socket, ServerState& state)
    : stream_(std::move(socket)), state_(state) {}

void HttpSession::run() {
  boost::asio::dispatch(stream_.get_executor(), beast::bind_front_handler(&HttpSession::read, shared_from_this()));
}

void HttpSession::read() {
  parser_.emplace();
  parser_->body_limit(state_.max_body);
  stream_.expires_after(std::chrono::seconds(60));
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
}

void HttpSession::on_read(beast::error_code ec, std::size_t) {
  if (ec == http::error::end_of_stream) return close();
  if (ec == http::error::body_limit) {
    Request head;
    head.version(parser_->get().version());
    auto res = error_response(head, http::status::payload_too_large,
                              "the request body is over the limit of " + std::to_string(state_.max_body) + " bytes");
    res.keep_alive(false);  // the rest of the body is not read: the connection cannot go on
    return send(std::move(res));
  }
  if (ec) {
    if (ec != beast::error::timeout && ec != boost::asio::error::operation_aborted &&
        ec != boost::asio::error::connection_reset) {
      Request head;
      auto res = error_response(head, http::status::bad_request, "malformed HTTP request: " + ec.message());
      res.keep_alive(false);
      return send(std::move(res));
    }
    return close();
  }
  Request req = parser_->release();
  const std::optional<Target> target = parse_target(req.target());
  if (!target) return send(error_response(req, http::status::bad_request, "malformed path: " + std::string(req.target())));

  if (!state_.token.empty()) {
    const std::string given = request_token(req, *target);
    if (!tokens_equal(given, state_.token)) {
      auto res = error_response(req, http::status::unauthorized,
                                given.empty() ? "this server needs an access token: send \"Authorization: Bearer TOKEN\""
                                              : "the access token is wrong");
      res.set(http::field::www_authenticate, "Bearer");
      return send(std::move(res));
    }
  }
  const bool api = !target->segments.empty() && target->segments[0] == "api";
  if (api && websocket::is_upgrade(req)) return upgrade(std::move(req), *target);
  if (api) {
    ApiContext ctx{state_.jobs, state_.openapi, state_.cases};
    try {
      return send(handle_api(req, *target, ctx));
    } catch (const std::exception& e) {  // the store or the disk failed: say so, keep serving
      return send(error_response(req, http::status::internal_server_error, std::string("internal error: ") + e.what()));
    }
  }
  send(serve_static(req, *target, state_.web));
}

void HttpSession::upgrade(Request request, const Target& target) {
  const auto& s = target.segments;
  if (!(s.size() == 4 && s[1] == "jobs" && s[3] == "frames"))
    return send(error_response(request, http::status::not_found, "no WebSocket at " + std::string(request.target())));
  std::string why;
  std::shared_ptr<FrameChannel> channel;
  const std::optional<std::int64_t> id = parse_job_id(s[2]);
  const std::optional<JobRecord> job = id ? state_.jobs.get(*id) : std::nullopt;
  if (!job) return send(error_response(request, http::status::not_found, "no job " + s[2]));
  channel = state_.jobs.frames_of(job->id, why);
  const auto q = target.query.find("forceChains");
  const bool chains = q != target.query.end() && (q->second == "1" || q->second == "true");
  stream_.expires_never();  // the WebSocket keeps its own timeouts
  auto session = std::make_shared<FrameSession>(stream_.release_socket(), chains);
  session->start(std::move(request), std::move(channel), std::move(why));
}

void HttpSession::send(http::message_generator message) {
  const bool keep_alive = message.keep_alive();
  beast::async_write(stream_, std::move(message),
                     beast::bind_front_handler(&HttpSession::on_write, shared_from_this(), keep_alive));
}

void HttpSession::on_write(bool keep_alive, beast::error_code ec, std::size_t) {
  if (ec) return;
  if (!keep_alive) return close();
  read();
}

void HttpSession::close() {
  beast::error_code ignored;
  stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
}

}  // namespace dem::server
