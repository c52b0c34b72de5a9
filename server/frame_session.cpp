#include "server/frame_session.hpp"

#include <utility>
#include <vector>

#include <boost/asio/post.hpp>

namespace dem::server {
namespace beast = boost::beast;
namespace websocket = beast::websocket;

FrameSession::FrameSession(boost::asio::ip::tcp::socket&& socket, bool force_chains)
    : ws_(std::move(socket)), force_chains_(force_chains) {
  // A small kernel buffer: a viewer that reads slowly is then sent the newest frame, not one that
  // waited behind megabytes of older ones.
  boost::system::error_code ignored;
  beast::get_lowest_layer(ws_).socket().set_option(boost::asio::socket_base::send_buffer_size(256 * 1024), ignored);
}

void FrameSession::start(const Request& request, std::shared_ptr<FrameChannel> channel, std::string why) {
  channel_ = std::move(channel);
  refuse_reason_ = std::move(why);
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(http::field::server, "dem-server"); }));
  // Joined before the handshake is answered: a job that starts as the viewer's client sees the
  // answer publishes its first frame to this viewer too (it went to nobody, and the viewer missed
  // step 0). Frames offered before the handshake is done wait for it (write_next).
  joined_ = channel_ && channel_->join(shared_from_this());
  ws_.async_accept(request, beast::bind_front_handler(&FrameSession::on_accept, shared_from_this()));
}

void FrameSession::on_accept(beast::error_code ec) {
  if (handshake_done_) std::exchange(handshake_done_, nullptr)(ec);
  if (ec) {
    leave();
    return;
  }
  accepted_ = true;
  if (!joined_) {
    end_reason_ = channel_ ? channel_->end_reason() : refuse_reason_;
    if (end_reason_.empty()) end_reason_ = "the job is over";
    ending_ = true;
    close();
    return;
  }
  read();
  write_next();  // what came while the handshake was answered
}

void FrameSession::read() {
  ws_.async_read(incoming_, beast::bind_front_handler(&FrameSession::on_read, shared_from_this()));
}

void FrameSession::on_read(beast::error_code ec, std::size_t) {
  if (ec) {  // the viewer left (or the socket failed)
    leave();
    return;
  }
  if (ws_.got_text()) {
    const std::string text = beast::buffers_to_string(incoming_.data());
    const nlohmann::json message = nlohmann::json::parse(text, nullptr, false);
    if (message.is_object() && message.contains("forceChains") && message["forceChains"].is_boolean())
      force_chains_ = message["forceChains"].get<bool>();
  }
  incoming_.consume(incoming_.size());
  read();
}

void FrameSession::offer(std::shared_ptr<const EncodedFrame> frame) {
  boost::asio::post(ws_.get_executor(), [self = shared_from_this(), frame = std::move(frame)]() mutable {
    // A few frames wait while one is written, so that a viewer that keeps up is not made to skip by
    // a moment's delay (a fast test viewer on a busy machine missed one in ten runs); past them the
    // oldest waiting is dropped: a slow viewer skips frames and its memory stays bounded.
    self->pending_.push_back(std::move(frame));
    if (self->pending_.size() > kWaitingFrames) self->pending_.pop_front();
    if (!self->writing_) self->write_next();
  });
}

void FrameSession::end(const std::string& reason) {
  boost::asio::post(ws_.get_executor(), [self = shared_from_this(), reason] {
    self->ending_ = true;
    self->end_reason_ = reason;
    if (!self->writing_) self->write_next();  // the last frame first, then the close
  });
}

void FrameSession::write_next() {
  if (closed_ || !accepted_) return;
  if (pending_.empty()) {
    if (ending_) close();
    return;
  }
  writing_ = std::move(pending_.front());
  pending_.pop_front();
  std::vector<boost::asio::const_buffer> parts{boost::asio::buffer(*writing_->base)};
  if (radii_sent_ != writing_->radii_version) parts.push_back(boost::asio::buffer(*writing_->radii));
  radii_sent_ = writing_->radii_version;
  if (force_chains_ && writing_->force_chains) parts.push_back(boost::asio::buffer(*writing_->force_chains));
  ws_.binary(true);
  ws_.async_write(parts, beast::bind_front_handler(&FrameSession::on_write, shared_from_this()));
}

void FrameSession::on_write(beast::error_code ec, std::size_t) {
  writing_.reset();
  if (ec) {
    leave();
    return;
  }
  write_next();
}

void FrameSession::close() {
  if (closed_) return;
  closed_ = true;
  std::string reason = end_reason_.substr(0, 120);  // a close frame's reason is at most 123 bytes
  ws_.async_close(websocket::close_reason(websocket::close_code::normal, reason),
                  [self = shared_from_this()](beast::error_code) { self->leave(); });
}

void FrameSession::leave() {
  if (channel_) channel_->leave(this);
}

}  // namespace dem::server
