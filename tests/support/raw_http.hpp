// Raw bytes to the server over a loopback socket, for requests no well-behaved client would send
// (unknown methods, missing headers, half-sent requests): the answer as text, whatever it is.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <string>

namespace dem::test {

// An open connection to 127.0.0.1:port.
class RawConnection {
 public:
  explicit RawConnection(unsigned short port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      if (fd_ >= 0) ::close(fd_);
      fd_ = -1;
    }
  }
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return fd_ >= 0; }

  bool send(const std::string& bytes) {
    std::size_t sent = 0;
    while (fd_ >= 0 && sent < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return false;
      sent += static_cast<std::size_t>(n);
    }
    return fd_ >= 0;
  }

  // What one read brings within `seconds` (empty: closed, or nothing came).
  std::string receive_some(double seconds) {
    pollfd p{fd_, POLLIN, 0};
    if (fd_ < 0 || ::poll(&p, 1, static_cast<int>(seconds * 1000)) <= 0) return "";
    char buf[65536];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  }

  // What arrives until the server closes the connection, or until `seconds` pass without it closing
  // (then with `timed_out` set), or, with `until` given, until the text read contains it.
  std::string receive(double seconds, bool* timed_out = nullptr, const std::string& until = "") {
    std::string out;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    if (timed_out) *timed_out = false;
    while (fd_ >= 0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) {
        if (timed_out) *timed_out = true;
        break;
      }
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
      char buf[65536];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;  // closed (or reset)
      out.append(buf, static_cast<std::size_t>(n));
      if (!until.empty() && out.find(until) != std::string::npos) break;
    }
    return out;
  }

 private:
  int fd_ = -1;
};

// One exchange on a new connection: `request` sent whole, the answer read until its headers and
// Content-Length bytes of body are in, the server closes the connection, or `seconds` pass.
inline std::string raw_exchange(unsigned short port, const std::string& request, double seconds = 5) {
  RawConnection c(port);
  if (!c.connected()) throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port));
  c.send(request);
  std::string answer = c.receive(seconds, nullptr, "\r\n\r\n");
  const std::size_t head_end = answer.find("\r\n\r\n");
  if (head_end == std::string::npos) return answer;
  std::size_t length = 0;
  for (const char* name : {"\r\nContent-Length: ", "\r\ncontent-length: "}) {
    const std::size_t at = answer.find(name);
    if (at != std::string::npos && at < head_end) length = std::stoul(answer.substr(at + std::string(name).size()));
  }
  while (answer.size() < head_end + 4 + length) {
    const std::string more = c.receive_some(seconds);
    if (more.empty()) break;
    answer += more;
  }
  return answer;
}

// The status code of the first response in `answer` ("HTTP/1.1 400 Bad Request" -> 400), 0 if none.
inline int status_of(const std::string& answer) {
  if (answer.rfind("HTTP/1.", 0) != 0 || answer.size() < 12) return 0;
  return std::stoi(answer.substr(9, 3));
}

}  // namespace dem::test
