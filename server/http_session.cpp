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
  // the header first: the token and the body's size are checked before any body is read
  http::async_read_header(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_header, shared_from_this()));
}

// An early answer (before or instead of the body): the connection closes after it.
void HttpSession::refuse(http::response<http::string_body> res) {
  res.keep_alive(false);
  send(std::move(res));
}

void HttpSession::on_header(beast::error_code ec, std::size_t) {
  if (ec == http::error::end_of_stream) return close();
  if (ec) return on_read_error(ec);
  const auto& head = parser_->get();
  Request head_only;
  head_only.version(head.version());
  head_only.method(head.method());
  const std::optional<Target> target = parse_target(head.target());
  if (!target) return refuse(error_response(head_only, http::status::bad_request, "malformed path: " + std::string(head.target())));
  if (!state_.token.empty()) {
    Request for_token;
    for_token.base() = head;
    const std::string given = request_token(for_token, *target);
    if (!tokens_equal(given, state_.token)) {
      auto res = error_response(head_only, http::status::unauthorized,
                                given.empty() ? "this server needs an access token: send \"Authorization: Bearer TOKEN\""
                                              : "the access token is wrong");
      res.set(http::field::www_authenticate, "Bearer");
      return refuse(std::move(res));
    }
  } else if (!local_request(head)) {
    // without a token only this machine's pages may talk to the server: a foreign Host is DNS
    // rebinding, a foreign Origin another site's page driving the browser
    return refuse(error_response(head_only, http::status::forbidden,
                                 "this server has no access token, so it answers only requests to 127.0.0.1 or localhost "
                                 "from pages of its own; give it --token to serve others"));
  }
  if (parser_->content_length() && *parser_->content_length() > state_.max_body)
    return refuse(error_response(head_only, http::status::payload_too_large,
                                 "the request body is over the limit of " + std::to_string(state_.max_body) + " bytes"));
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
}

void HttpSession::on_read_error(beast::error_code ec) {
  if (ec == http::error::body_limit) {  // a chunked body that grew past the limit
    Request head;
    return refuse(error_response(head, http::status::payload_too_large,
                                 "the request body is over the limit of " + std::to_string(state_.max_body) + " bytes"));
  }
  if (ec != beast::error::timeout && ec != boost::asio::error::operation_aborted &&
      ec != boost::asio::error::connection_reset && ec != http::error::end_of_stream) {
    Request head;
    return refuse(error_response(head, http::status::bad_request, "malformed HTTP request: " + ec.message()));
  }
  close();
}

void HttpSession::on_read(beast::error_code ec, std::size_t) {
  if (ec) return on_read_error(ec);
  Request req = parser_->release();
  const Target target = *parse_target(req.target());  // checked with the header
  try {
    const bool api = !target.segments.empty() && target.segments[0] == "api";
    if (api && websocket::is_upgrade(req)) return upgrade(std::move(req), target);
    if (api) {
      ApiContext ctx{state_.jobs, state_.openapi, state_.cases};
      return send(handle_api(req, target, ctx));
    }
    // a page opened with ?access_token= keeps the token in a cookie for its scripts and styles
    std::string cookie;
    if (!state_.token.empty() && target.query.count("access_token"))
      cookie = "dem_token=" + target.query.at("access_token") + "; Path=/; HttpOnly; SameSite=Strict";
    send(serve_static(req, target, state_.web, cookie));
  } catch (const std::exception& e) {  // the store or the disk failed: say so, keep serving
    send(error_response(req, http::status::internal_server_error, std::string("internal error: ") + e.what()));
  }
}

bool HttpSession::local_request(const http::request_header<>& head) {
  auto host_of = [](std::string_view authority) {  // "127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "[::1]"
    if (!authority.empty() && authority[0] == '[') return std::string(authority.substr(0, authority.find(']') + 1));
    return std::string(authority.substr(0, authority.find(':')));
  };
  auto local = [](const std::string& host) {
    return host == "127.0.0.1" || host == "localhost" || host == "[::1]" || host.rfind("127.", 0) == 0;
  };
  const auto host = head.find(http::field::host);
  if (host != head.end() && !local(host_of(std::string_view(host->value().data(), host->value().size())))) return false;
  const auto origin = head.find(http::field::origin);
  if (origin != head.end()) {
    std::string_view o(origin->value().data(), origin->value().size());
    const std::size_t scheme = o.find("://");
    if (scheme == std::string_view::npos || !local(host_of(o.substr(scheme + 3)))) return false;
  }
  return true;
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
  stream_.expires_never();  // a large artifact may take long to send; the next read sets a deadline again
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
  drain();
}

// Reads and drops what the client still sends (the body of a refused request) until it closes, for
// at most 5 s: closing with unread data would reset the connection and lose the answer sent.
void HttpSession::drain() {
  stream_.expires_after(std::chrono::seconds(5));
  stream_.async_read_some(boost::asio::buffer(scratch_),
                          [self = shared_from_this()](beast::error_code ec, std::size_t) {
                            if (!ec) self->drain();
                          });
}

}  // namespace dem::server
