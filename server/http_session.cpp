#include "server/http_session.hpp"

#include <chrono>

#include <boost/asio/dispatch.hpp>
#include <boost/beast/websocket.hpp>

#include "server/frame_session.hpp"
#include "server/request_policy.hpp"
#include "server/static_files.hpp"

namespace dem::server {
namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace {

// The methods a resource of this server may answer (the rest get a 405 listing what it allows);
// any other method is implemented nowhere here: 501.
bool routed_method(http::verb m) {
  using v = http::verb;
  return m == v::get || m == v::head || m == v::post || m == v::put || m == v::delete_ || m == v::options ||
         m == v::patch;
}

}  // namespace

HttpSession::HttpSession(boost::asio::ip::tcp::socket&& socket, ServerState& state, std::shared_ptr<void> ticket,
                         std::string refused_why)
    : stream_(std::move(socket)),
      deadline_(stream_.get_executor()),
      ticket_(std::move(ticket)),
      refused_why_(std::move(refused_why)),
      state_(state) {
  boost::system::error_code no_peer;
  const auto peer = stream_.socket().remote_endpoint(no_peer);
  client_ = no_peer ? "-" : peer.address().to_string();
  request_line_.client = client_;
  request_line_.secret = state_.token;
}

void HttpSession::run() {
  if (ticket_) {
    boost::asio::dispatch(stream_.get_executor(), beast::bind_front_handler(&HttpSession::read, shared_from_this()));
    return;
  }
  // past a connection limit: answered at once, whatever the client sends
  boost::asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    Request head;
    auto res = error_response(head, http::status::service_unavailable,
                              "too many connections: " + self->refused_why_ + "; try again in a moment");
    res.set(http::field::retry_after, "1");
    self->refuse(std::move(res));
  });
}

void HttpSession::read() {
  request_line_ = RequestLine{};  // nothing read yet
  request_line_.client = client_;
  request_line_.secret = state_.token;
  parser_.emplace();
  // no limit while the header is read: a declared length past it is answered after the token's
  // check (on_header), which then sets the limit for the body
  parser_->body_limit(boost::none);
  stream_.expires_never();  // the request's own deadline, below
  start_deadline(state_.request_timeout);
  // the header first: the token and the body's size are checked before any body is read
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::on_header, shared_from_this()));
}

// A request must arrive whole in time: one that stalls half sent (slowloris) is answered 408 and
// its connection closed; an idle kept-alive connection is closed without a word.
void HttpSession::start_deadline(std::chrono::steady_clock::duration within) {
  deadline_passed_ = false;
  deadline_.expires_after(within);
  deadline_.async_wait(beast::bind_front_handler(&HttpSession::on_deadline, shared_from_this()));
}

void HttpSession::on_deadline(beast::error_code ec) {
  if (ec) return;  // met, or moved on
  deadline_passed_ = true;
  beast::error_code ignored;
  stream_.socket().cancel(ignored);  // the pending read ends with operation_aborted: timed_out() answers
}

bool HttpSession::timed_out(beast::error_code ec) {
  if (!deadline_passed_ || ec != boost::asio::error::operation_aborted) return false;
  if (parser_->got_some() || buffer_.size() > 0) {
    Request head;
    refuse(error_response(
        head, http::status::request_timeout,
        "the request did not arrive whole within " +
            std::to_string(std::chrono::duration_cast<std::chrono::seconds>(state_.request_timeout).count()) +
            " s (--request-timeout; a body gets 60 s more)"));
  } else {
    close();
  }
  return true;
}

// An early answer (before or instead of the body): the connection closes after it.
void HttpSession::refuse(http::response<http::string_body> res) {
  res.keep_alive(false);
  send(std::move(res));
}

void HttpSession::on_header(beast::error_code ec, std::size_t) {
  if (timed_out(ec)) return;
  if (ec == http::error::end_of_stream) return close();
  if (ec) return on_read_error(ec);
  auto& head = parser_->get();
  request_line_.method = std::string(head.method_string());
  request_line_.target = std::string(head.target());  // as sent (before an absolute form is read)
  request_line_.version = head.version();
  request_line_.start = std::chrono::steady_clock::now();
  // an answer before the body: the request's version, and HEAD kept (a method Beast does not know
  // must not be copied: setting it throws, which once took the whole server down)
  Request head_only;
  head_only.version(head.version());
  head_only.target(head.target());  // the problem's instance
  if (head.method() == http::verb::head) head_only.method(http::verb::head);
  if (head.version() >= 11 && head.find(http::field::host) == head.end())
    return refuse(error_response(head_only, http::status::bad_request, "an HTTP/1.1 request needs a Host header"));
  // a header that names one thing, given twice: which one counts would depend on the reader
  for (const char* name : {"Host", "Origin", "Authorization", "Idempotency-Key", "Transfer-Encoding"})
    if (head.count(name) > 1)
      return refuse(error_response(head_only, http::status::bad_request,
                                   std::string("the request has more than one ") + name + " header (RFC 9110 5.3)"));
  // RFC 9112 6.1: a body is framed by chunked, last; anything else cannot be read safely (400 here),
  // and a coding before chunked is one this server does not decode (501, after the token's check)
  const auto coding_field = head.find(http::field::transfer_encoding);
  const beast::string_view coding = coding_field == head.end() ? beast::string_view{} : coding_field->value();
  const TransferCoding coding_kind =
      coding_field == head.end() ? TransferCoding::Chunked : classify_transfer_coding(coding);
  if (coding_kind == TransferCoding::NotChunkedLast)
    return refuse(error_response(head_only, http::status::bad_request,
                                 "Transfer-Encoding \"" + printable(coding) +
                                     "\" does not end in chunked: the body's length cannot be known (RFC 9112 6.1)"));
  if (is_absolute_form(head.target())) {
    const std::optional<AbsoluteTarget> absolute = split_absolute_form(head.target());
    if (!absolute)
      return refuse(error_response(
          head_only, http::status::bad_request,
          "malformed absolute target (an http or https URI with a host is expected): " + printable(head.target())));
    // RFC 9112 3.2.2: the target's authority names the server, and every check below reads the Host
    head.target(absolute->origin_form);
    head.set(http::field::host, absolute->authority);
  }
  // RFC 9110 9.3.7: OPTIONS * asks about the server itself (answered after the token's check)
  const bool server_options = head.target() == "*" && head.method() == http::verb::options;
  if (!server_options && (head.target().empty() || head.target()[0] != '/'))
    return refuse(
        error_response(head_only, http::status::bad_request,
                       "malformed path (a path from the root, /..., is expected): " + printable(head.target())));
  const std::optional<Target> target = server_options ? std::optional<Target>(Target{}) : parse_target(head.target());
  if (!target)
    return refuse(error_response(head_only, http::status::bad_request, "malformed path: " + printable(head.target())));
  if (!state_.token.empty()) {
    Request for_token;
    for_token.base() = head;
    const std::string given = request_token(for_token, *target);
    if (!tokens_equal(given, state_.token)) {
      auto res =
          error_response(head_only, http::status::unauthorized,
                         given.empty() ? "this server needs an access token: send \"Authorization: Bearer TOKEN\""
                                       : "the access token is wrong");
      res.set(http::field::www_authenticate, "Bearer");
      return refuse(std::move(res));
    }
    // a page of another site (or of another port of this host, which SameSite does not tell apart)
    // must not use the cookie this server gave its own pages
    if (!same_origin_or_none(head))
      return refuse(
          error_response(head_only, http::status::forbidden,
                         "requests from pages of another origin are refused (the Origin is not this server)"));
  } else if (!local_request(head)) {
    // without a token only this machine's pages may talk to the server: a foreign Host is DNS
    // rebinding, a foreign Origin another site's page driving the browser
    return refuse(
        error_response(head_only, http::status::forbidden,
                       "this server has no access token, so it answers only requests to 127.0.0.1 or localhost "
                       "from pages of its own; give it --token to serve others"));
  }
  // after the token's check: a stranger learns nothing of what the server implements
  if (head.method() == http::verb::unknown)
    return refuse(error_response(head_only, http::status::not_implemented,
                                 printable(head.method_string()) +
                                     " is not a method this server knows (methods are "
                                     "case-sensitive: GET, HEAD, POST, DELETE, OPTIONS)"));
  if (!routed_method(head.method()))  // TRACE, CONNECT, WebDAV's: implemented on no resource
    return refuse(error_response(head_only, http::status::not_implemented,
                                 std::string(head.method_string()) +
                                     " is implemented on no resource of this server (GET, HEAD, POST, DELETE, "
                                     "OPTIONS are)"));
  if (coding_kind == TransferCoding::UnknownBeforeChunked)
    return refuse(error_response(head_only, http::status::not_implemented,
                                 "Transfer-Encoding \"" + printable(coding) + "\": this server decodes chunked only"));
  if (server_options) {
    http::response<http::string_body> res{http::status::no_content, head.version()};
    res.set(http::field::allow, "GET, HEAD, POST, DELETE, OPTIONS");
    res.set(http::field::date, http_date_now());
    return refuse(std::move(res));
  }
  // checked here, after the token: a stranger learns nothing of the limit
  if (parser_->content_length() && *parser_->content_length() > state_.max_body)
    return refuse(
        error_response(head_only, http::status::payload_too_large,
                       "the request body is over the limit of " + std::to_string(state_.max_body) + " bytes"));
  parser_->body_limit(state_.max_body);  // a chunked body is cut off as it passes the limit
  const auto expect = head.find(http::field::expect);
  // RFC 9110 10.1.1: an HTTP/1.0 request's 100-continue is ignored (and 15.2: no 1xx to a 1.0 client)
  if (expect != head.end() && head.version() >= 11) {
    if (!beast::iequals(expect->value(), "100-continue"))
      return refuse(error_response(head_only, http::status::expectation_failed,
                                   "the only expectation this server meets is 100-continue"));
    // the client waits for this before it sends the body (curl does past 1 KB)
    auto go_on = std::make_shared<http::response<http::empty_body>>(http::status::continue_, head.version());
    return http::async_write(stream_, *go_on,
                             [self = shared_from_this(), go_on](beast::error_code write_ec, std::size_t) {
                               if (write_ec) return self->close();
                               self->read_body();
                             });
  }
  read_body();
}

void HttpSession::read_body() {
  start_deadline(state_.request_timeout + std::chrono::seconds(60));
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
}

void HttpSession::on_read_error(beast::error_code ec) {
  if (ec == http::error::header_limit) {  // RFC 6585 5 (a request line past the limit counts here too)
    Request head;
    return refuse(error_response(head, http::status::request_header_fields_too_large,
                                 "the request's header (its line and fields) is over the limit of 8 KB"));
  }
  if (ec == http::error::body_limit) {  // a chunked body that grew past the limit
    Request head;
    return refuse(
        error_response(head, http::status::payload_too_large,
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
  if (timed_out(ec)) return;
  if (ec) return on_read_error(ec);
  deadline_.cancel();
  Request req = parser_->release();
  Target target = *parse_target(req.target());  // checked with the header
  drop_api_version(target);
  const bool api = !target.segments.empty() && target.segments[0] == "api";
  if (api && websocket::is_upgrade(req)) return upgrade(req, target);
  // Checking a submission builds its simulation (dem validate's checks), which for a large scene
  // takes a while: off the connections' threads, which must go on answering (two large
  // submissions once held /api/health for 2.6 s).
  if (api && req.method() == http::verb::post && target.segments.size() == 2 &&
      (target.segments[1] == "jobs" || target.segments[1] == "studies")) {
    return boost::asio::post(
        state_.checks, [self = shared_from_this(), req = std::move(req), target = std::move(target)] {
          boost::asio::post(self->stream_.get_executor(),
                            [self, answer = self->answer(req, target)]() mutable { self->send(std::move(answer)); });
        });
  }
  send(answer(req, target));
}

http::message_generator HttpSession::answer(const Request& req, const Target& target) {
  try {
    if (!target.segments.empty() && target.segments[0] == "api") {
      ApiContext ctx{state_.jobs, state_.studies, state_.openapi, state_.cases};
      return handle_api(req, target, ctx);
    }
    // a page opened with ?access_token= keeps the token in a cookie for its scripts and styles: the
    // server's own token (checked cookie-safe at start), never the value of the request
    std::string cookie;
    if (!state_.token.empty() && target.query.count("access_token") &&
        tokens_equal(target.query.at("access_token"), state_.token))
      cookie = "dem_token=" + state_.token + "; Path=/; HttpOnly; SameSite=Strict";
    return serve_static(req, target, state_.web, cookie);
  } catch (const std::exception& e) {  // the store or the disk failed: say so, keep serving
    // a full data folder is for the operator to mend (delete jobs: that still works), not a fault
    const JobManager::StoreHealth store = state_.jobs.store_health();
    if (store.low_on_space)
      return error_response(req, http::status::insufficient_storage,
                            std::string("the data folder is full: ") + e.what());
    return error_response(req, http::status::internal_server_error, std::string("internal error: ") + e.what());
  }
}

bool HttpSession::local_request(const http::request_header<>& head) {
  auto local = [](std::string_view authority) {
    const std::optional<std::string> host = host_of_authority(authority);
    return host && is_loopback_host(*host);
  };
  const auto host = head.find(http::field::host);
  if (host != head.end() && !local(std::string_view(host->value().data(), host->value().size()))) return false;
  const auto origin = head.find(http::field::origin);
  if (origin != head.end()) {
    const std::optional<std::string> authority =
        authority_of_origin(std::string_view(origin->value().data(), origin->value().size()));
    if (!authority || !local(*authority)) return false;
  }
  return true;
}

bool HttpSession::same_origin_or_none(const http::request_header<>& head) {
  const auto origin = head.find(http::field::origin);
  if (origin == head.end()) return true;  // not sent by a page
  const auto host = head.find(http::field::host);
  const std::optional<std::string> authority =
      authority_of_origin(std::string_view(origin->value().data(), origin->value().size()));
  return authority && host != head.end() &&
         same_authority(*authority, std::string_view(host->value().data(), host->value().size()));
}

void HttpSession::upgrade(const Request& request, const Target& target) {
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
  deadline_.cancel();
  auto session = std::make_shared<FrameSession>(stream_.release_socket(), chains);
  session->hold(ticket_);  // the connection stays counted while it streams
  // Beast answers the handshake: 101, or 400 to one it refuses (nothing when the client left)
  session->on_handshake([line = request_line_](beast::error_code handshake) {
    const unsigned status = !handshake ? 101 : handshake == websocket::condition::handshake_failed ? 400 : 0;
    log_request(line, status, std::nullopt);
  });
  session->start(request, std::move(channel), std::move(why));
}

void HttpSession::send(http::message_generator message) {
  const bool keep_alive = message.keep_alive();
  deadline_.cancel();
  stream_.expires_never();  // a large artifact may take long to send; the next read sets a deadline again
  answered_status_ = 0;
  beast::async_write(stream_, StatusReadingAnswer(std::move(message), answered_status_),
                     beast::bind_front_handler(&HttpSession::on_write, shared_from_this(), keep_alive));
}

void HttpSession::on_write(bool keep_alive, beast::error_code ec, std::size_t bytes) {
  log_request(request_line_, answered_status_, bytes);  // a write cut short too: what was sent
  if (ec) return;
  if (!keep_alive) return close();
  read();
}

void HttpSession::close() {
  deadline_.cancel();  // its wait holds the session (and its place within the limits)
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
