// Who watches which job. The engine publishes each frame to its job's channel; every viewer keeps
// only the latest frame it has not sent yet, so a slow viewer skips frames instead of queueing them.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "server/frame_encoder.hpp"

namespace dem::server {

// A viewer of one job (a WebSocket session). Calls come from the engine's thread.
class FrameViewer {
 public:
  virtual ~FrameViewer() = default;
  virtual void offer(std::shared_ptr<const EncodedFrame> frame) = 0;  // replaces any frame not yet sent
  virtual void end(const std::string& reason) = 0;                    // the job is over (or the server stops)
  virtual bool wants_force_chains() const = 0;
};

class FrameChannel {
 public:
  bool has_viewers() const { return viewers_count_.load(std::memory_order_relaxed) > 0; }
  bool wants_force_chains() const;
  void publish(const std::shared_ptr<const EncodedFrame>& frame);
  // Joins a viewer; it is offered the latest frame at once (if others watch; else it waits for the
  // next). False when the channel has ended.
  bool join(const std::shared_ptr<FrameViewer>& viewer);
  void leave(const FrameViewer* viewer);
  void end(const std::string& reason);
  std::string end_reason() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::weak_ptr<FrameViewer>> viewers_;
  std::atomic<int> viewers_count_{0};
  std::shared_ptr<const EncodedFrame> latest_;
  bool ended_ = false;
  std::string end_reason_;
};

class FrameHub {
 public:
  // The job's channel, made when first asked for (by a viewer of a queued job, or the job starting).
  std::shared_ptr<FrameChannel> open(std::int64_t job);
  std::shared_ptr<FrameChannel> find(std::int64_t job) const;
  void close(std::int64_t job, const std::string& reason);  // when it stops
  void close_all(const std::string& reason);

 private:
  mutable std::mutex mutex_;
  std::map<std::int64_t, std::shared_ptr<FrameChannel>> channels_;
};

}  // namespace dem::server
