#include "client/http_client.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

namespace dem::client {
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// How long the server may take to accept a connection, and to send the next bytes of a download
// (a whole answer: HttpClient::answer_timeout).
constexpr auto kConnectTimeout = std::chrono::seconds(30);
constexpr auto kDownloadIdleTimeout = std::chrono::milliseconds(60000);
// An API answer (JSON) larger than this is not the server's: a client that kept reading an endless
// body grew to 2 GB and died of bad_alloc (an independent tester's finding). Downloads go to disk.
constexpr std::uint64_t kLargestAnswer = 256ull << 20;

// Runs one asynchronous operation to its end. Beast's timeouts (expires_after) act only on
// asynchronous operations: a blocking read of a server that accepts and never answers, or trickles
// a byte a second, waited for ever.
template <class Start>
beast::error_code run_to_end(boost::asio::io_context& io, Start&& start) {
  beast::error_code result = boost::asio::error::would_block;
  start([&result](beast::error_code ec, auto&&...) { result = ec; });
  io.restart();
  io.run();
  return result;
}

// The error of a timed-out operation in words a user can act on.
std::string said(beast::error_code ec) {
  return ec == beast::error::timeout ? "the server did not answer in time" : ec.message();
}

// Connects a TCP stream to the server, or says why not.
void connect(beast::tcp_stream& stream, boost::asio::io_context& io, const HttpClient& client) {
  std::string host = client.host();  // "[::1]" names the address ::1
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  beast::error_code ec;
  tcp::resolver resolver(io);
  const tcp::resolver::results_type addresses = resolver.resolve(host, client.port(), ec);
  if (!ec) {
    stream.expires_after(kConnectTimeout);
    ec = run_to_end(io, [&](auto done) { stream.async_connect(addresses, done); });
  }
  if (ec) throw ClientError("cannot reach the server at " + client.url() + ": " + said(ec));
}

template <class Message>
void add_headers(Message& req, const HttpClient& client, const Headers& headers) {
  req.set(http::field::host, client.host() + ":" + client.port());
  req.set(http::field::user_agent, "dem-client");
  if (!client.token().empty()) req.set(http::field::authorization, "Bearer " + client.token());
  for (const auto& [name, value] : headers) req.set(name, value);
}

template <class Body>
Response to_response(http::response<Body>& res) {
  Response out;
  out.status = static_cast<int>(res.result_int());
  for (const auto& field : res) out.headers[lower(std::string(field.name_string()))] = std::string(field.value());
  return out;
}

}  // namespace

std::string Response::header(const std::string& name) const {
  const auto it = headers.find(name);
  return it == headers.end() ? "" : it->second;
}

HttpClient::HttpClient(const std::string& server, std::string token) : token_(std::move(token)) {
  std::string rest = server;
  if (rest.rfind("http://", 0) == 0)
    rest = rest.substr(7);
  else if (rest.find("://") != std::string::npos)
    throw ClientError("server " + server + ": only http:// is supported (put TLS in front with a proxy)");
  // a path (a server behind a proxy's prefix) or a user's password would be dropped without a word
  const std::size_t slash = rest.find('/');
  if (slash != std::string::npos && slash + 1 != rest.size())
    throw ClientError("server \"" + server + "\": a path after HOST:PORT is not supported (give http://HOST:PORT)");
  rest = rest.substr(0, slash);
  if (rest.find('@') != std::string::npos)
    throw ClientError("server: a user or password in the URL is not supported (give the token with --token)");
  const std::size_t colon = rest.rfind(':');
  host_ = colon == std::string::npos ? rest : rest.substr(0, colon);
  port_ = colon == std::string::npos ? "80" : rest.substr(colon + 1);
  if (host_.empty() || port_.empty())
    throw ClientError("server \"" + server + "\" is not of the form http://HOST:PORT");
}

Response HttpClient::request(const std::string& method, const std::string& target, const std::string& body,
                             const std::string& content_type, const Headers& headers) const {
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  connect(stream, io, *this);
  http::request<http::string_body> req{http::string_to_verb(method), target, 11};
  add_headers(req, *this, headers);
  if (!content_type.empty()) req.set(http::field::content_type, content_type);
  req.body() = body;
  req.prepare_payload();
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(kLargestAnswer);
  if (req.method() == http::verb::head) parser.skip(true);  // a HEAD answer has a length but no body
  stream.expires_after(answer_timeout_);
  beast::error_code ec = run_to_end(io, [&](auto done) { http::async_write(stream, req, done); });
  if (!ec) ec = run_to_end(io, [&](auto done) { http::async_read(stream, buffer, parser, done); });
  if (ec == http::error::body_limit)
    throw ClientError(method + " " + url() + target + ": the answer is over " + std::to_string(kLargestAnswer >> 20) +
                      " MB, more than any answer of dem-server");
  if (ec) throw ClientError(method + " " + url() + target + ": " + said(ec));
  http::response<http::string_body> res = parser.release();
  Response out = to_response(res);
  out.body = std::move(res.body());
  beast::error_code ignored;
  stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
  return out;
}

Response HttpClient::download(const std::string& target, const std::string& path) const {
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  connect(stream, io, *this);
  http::request<http::empty_body> req{http::verb::get, target, 11};
  add_headers(req, *this, {});
  const std::string partial = path + ".part";
  auto fail = [&](const std::string& why) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);  // no half file left behind
    throw ClientError("GET " + url() + target + ": " + why);
  };
  stream.expires_after(answer_timeout_);
  beast::error_code ec = run_to_end(io, [&](auto done) { http::async_write(stream, req, done); });
  if (ec) fail(said(ec));
  beast::flat_buffer buffer;
  http::response_parser<http::file_body> parser;
  parser.body_limit(boost::none);
  parser.get().body().open(partial.c_str(), beast::file_mode::write, ec);
  if (ec) throw ClientError("cannot write " + partial + ": " + ec.message());
  // a large file may take long: what is timed is the wait for its next bytes
  while (!parser.is_done()) {
    stream.expires_after(std::min(kDownloadIdleTimeout, answer_timeout_));
    ec = run_to_end(io, [&](auto done) { http::async_read_some(stream, buffer, parser, done); });
    if (ec) fail(said(ec));
  }
  http::response<http::file_body> res = parser.release();
  res.body().close();
  Response out = to_response(res);
  if (out.status == 200) {
    std::error_code renamed;
    std::filesystem::rename(partial, path, renamed);
    if (renamed) {  // the file there cannot be replaced (read-only, a folder): no .part left either
      std::error_code ignored;
      std::filesystem::remove(partial, ignored);
      throw ClientError("cannot write " + path + ": " + renamed.message());
    }
  } else {
    std::FILE* f = std::fopen(partial.c_str(), "rb");
    for (int c; f && (c = std::fgetc(f)) != EOF && out.body.size() < (1u << 20);)
      out.body.push_back(static_cast<char>(c));
    if (f) std::fclose(f);
    std::filesystem::remove(partial);
  }
  return out;
}

struct FrameStream::Impl {
  boost::asio::io_context io;
  websocket::stream<beast::tcp_stream> ws{io};
  beast::flat_buffer buffer;
};

FrameStream::FrameStream(const HttpClient& client, const std::string& target) : impl_(std::make_unique<Impl>()) {
  connect(beast::get_lowest_layer(impl_->ws), impl_->io, client);
  beast::get_lowest_layer(impl_->ws).expires_never();
  impl_->ws.set_option(websocket::stream_base::decorator([&client](websocket::request_type& req) {
    req.set(http::field::user_agent, "dem-client");
    if (!client.token().empty()) req.set(http::field::authorization, "Bearer " + client.token());
  }));
  impl_->ws.read_message_max(0);  // frames of large scenes are large
  try {
    impl_->ws.handshake(client.host() + ":" + client.port(), target);
  } catch (const boost::system::system_error& e) {
    throw ClientError("WebSocket " + client.url() + target + ": " + e.code().message());
  }
}

FrameStream::~FrameStream() {
  beast::error_code ignored;
  if (impl_->ws.is_open()) impl_->ws.close(websocket::close_code::normal, ignored);
}

std::optional<std::string> FrameStream::next() {
  for (;;) {
    impl_->buffer.clear();
    beast::error_code ec;
    impl_->ws.read(impl_->buffer, ec);
    if (ec == websocket::error::closed) {
      close_reason_ = std::string(impl_->ws.reason().reason.c_str());
      return std::nullopt;
    }
    if (ec) throw ClientError("reading frames: " + ec.message());
    if (impl_->ws.got_binary()) return beast::buffers_to_string(impl_->buffer.data());
  }
}

void FrameStream::send_text(const std::string& text) {
  impl_->ws.text(true);
  impl_->ws.write(boost::asio::buffer(text));
}

void FrameStream::close() {
  beast::error_code ignored;
  impl_->ws.close(websocket::close_code::normal, ignored);
}

}  // namespace dem::client
