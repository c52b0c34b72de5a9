#include "server/frame_hub.hpp"

#include <algorithm>

namespace dem::server {

bool FrameChannel::wants_force_chains() const {
  std::lock_guard lock(mutex_);
  for (const auto& w : viewers_)
    if (auto v = w.lock(); v && v->wants_force_chains()) return true;
  return false;
}

void FrameChannel::publish(const std::shared_ptr<const EncodedFrame>& frame) {
  std::vector<std::shared_ptr<FrameViewer>> targets;
  {
    std::lock_guard lock(mutex_);
    latest_ = frame;
    for (const auto& w : viewers_)
      if (auto v = w.lock()) targets.push_back(std::move(v));
  }
  for (const auto& v : targets) v->offer(frame);  // outside the lock: offer posts to the viewer's strand
}

bool FrameChannel::join(const std::shared_ptr<FrameViewer>& viewer) {
  std::shared_ptr<const EncodedFrame> latest;
  {
    std::lock_guard lock(mutex_);
    if (ended_) return false;
    viewers_.erase(std::remove_if(viewers_.begin(), viewers_.end(), [](const auto& w) { return w.expired(); }),
                   viewers_.end());
    viewers_.push_back(viewer);
    viewers_count_.store(static_cast<int>(viewers_.size()));
    latest = latest_;
  }
  if (latest) viewer->offer(latest);
  return true;
}

void FrameChannel::leave(const FrameViewer* viewer) {
  std::lock_guard lock(mutex_);
  viewers_.erase(std::remove_if(viewers_.begin(), viewers_.end(),
                                [&](const auto& w) {
                                  const auto v = w.lock();
                                  return !v || v.get() == viewer;
                                }),
                 viewers_.end());
  viewers_count_.store(static_cast<int>(viewers_.size()));
  if (viewers_.empty()) latest_.reset();  // frames are not made while nobody watches: it would grow old
}

void FrameChannel::end(const std::string& reason) {
  std::vector<std::shared_ptr<FrameViewer>> targets;
  {
    std::lock_guard lock(mutex_);
    if (ended_) return;
    ended_ = true;
    end_reason_ = reason;
    for (const auto& w : viewers_)
      if (auto v = w.lock()) targets.push_back(std::move(v));
    viewers_.clear();
    viewers_count_.store(0);
  }
  for (const auto& v : targets) v->end(reason);
}

std::string FrameChannel::end_reason() const {
  std::lock_guard lock(mutex_);
  return end_reason_;
}

std::shared_ptr<FrameChannel> FrameHub::open(std::int64_t job) {
  std::lock_guard lock(mutex_);
  std::shared_ptr<FrameChannel>& channel = channels_[job];
  if (!channel) channel = std::make_shared<FrameChannel>();
  return channel;
}

std::shared_ptr<FrameChannel> FrameHub::find(std::int64_t job) const {
  std::lock_guard lock(mutex_);
  const auto it = channels_.find(job);
  return it == channels_.end() ? nullptr : it->second;
}

void FrameHub::close(std::int64_t job, const std::string& reason) {
  std::shared_ptr<FrameChannel> channel;
  {
    std::lock_guard lock(mutex_);
    const auto it = channels_.find(job);
    if (it == channels_.end()) return;
    channel = it->second;
    channels_.erase(it);
  }
  channel->end(reason);
}

void FrameHub::close_all(const std::string& reason) {
  std::map<std::int64_t, std::shared_ptr<FrameChannel>> all;
  {
    std::lock_guard lock(mutex_);
    all.swap(channels_);
  }
  for (auto& [job, channel] : all) channel->end(reason);
}

}  // namespace dem::server
