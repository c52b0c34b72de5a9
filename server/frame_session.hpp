// A viewer's WebSocket on /api/jobs/{id}/frames: binary messages, each one Frame (proto/dem.proto).
// It holds at most the frame being written and the latest one offered: a slow viewer skips frames
// and never makes the server queue them. The viewer may send the text {"forceChains": true|false}.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <string>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include "server/frame_hub.hpp"
#include "server/http_util.hpp"

namespace dem::server {

class FrameSession final : public FrameViewer, public std::enable_shared_from_this<FrameSession> {
 public:
  FrameSession(boost::asio::ip::tcp::socket&& socket, bool force_chains);
  // Accepts the upgrade, then joins `channel`; with no channel, closes at once saying `why`.
  void start(const Request& request, std::shared_ptr<FrameChannel> channel, std::string why);
  // Keeps the connection's place within the server's limits (ConnectionLimits) while it lives.
  void hold(std::shared_ptr<void> ticket) { ticket_ = std::move(ticket); }
  // Called once the handshake is answered (or failed), before any frame: the request log's line.
  void on_handshake(std::function<void(boost::beast::error_code)> done) { handshake_done_ = std::move(done); }

  void offer(std::shared_ptr<const EncodedFrame> frame) override;
  void end(const std::string& reason) override;
  bool wants_force_chains() const override { return force_chains_.load(); }

 private:
  void on_accept(boost::beast::error_code ec);
  void read();
  void on_read(boost::beast::error_code ec, std::size_t bytes);
  void write_next();
  void on_write(boost::beast::error_code ec, std::size_t bytes);
  void close();
  void leave();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  boost::beast::flat_buffer incoming_;
  std::shared_ptr<FrameChannel> channel_;
  std::string refuse_reason_;
  std::atomic<bool> force_chains_;
  // on the session's strand only:
  static constexpr std::size_t kWaitingFrames = 3;
  std::shared_ptr<const EncodedFrame> writing_;
  std::deque<std::shared_ptr<const EncodedFrame>> pending_;  // at most kWaitingFrames, oldest first
  std::uint64_t radii_sent_ = 0;                             // the version of the radii this viewer has
  bool ending_ = false;
  bool joined_ = false;    // to its job's channel, before the handshake
  bool accepted_ = false;  // the handshake is done: frames may be written
  bool closed_ = false;
  std::string end_reason_;
  std::shared_ptr<void> ticket_;
  std::function<void(boost::beast::error_code)> handshake_done_;
};

}  // namespace dem::server
