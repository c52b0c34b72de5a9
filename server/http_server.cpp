#include "server/http_server.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>

#include <spdlog/spdlog.h>

#include "dem/version.hpp"
#include "server/http_session.hpp"
#include "server/openapi.hpp"
#include "server/server_log.hpp"

namespace dem::server {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace {

// The machine's memory, for the default limit of what one job may need.
double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 8e9;
}

// Accepts connections, each on a strand of its own.
class Listener : public std::enable_shared_from_this<Listener> {
 public:
  Listener(asio::io_context& io, const tcp::endpoint& endpoint, ServerState& state)
      : io_(io), acceptor_(asio::make_strand(io)), backoff_(acceptor_.get_executor()), state_(state) {
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(asio::socket_base::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(asio::socket_base::max_listen_connections);
  }
  unsigned short port() const { return acceptor_.local_endpoint().port(); }
  void accept() {
    acceptor_.async_accept(
        asio::make_strand(io_), [self = shared_from_this()](boost::system::error_code ec, tcp::socket s) {
          if (ec == asio::error::operation_aborted || !self->acceptor_.is_open()) return;  // stopped
          if (!ec) {
            boost::system::error_code no_peer;
            const std::string client = s.remote_endpoint(no_peer).address().to_string();
            std::string why;
            std::shared_ptr<void> ticket = self->state_.connections.admit(client, why);
            std::make_shared<HttpSession>(std::move(s), self->state_, std::move(ticket), std::move(why))->run();
            self->accept();
            return;
          }
          // out of file descriptors, say: try again in a moment rather than spin
          self->backoff_.expires_after(std::chrono::milliseconds(100));
          self->backoff_.async_wait([self](boost::system::error_code) { self->accept(); });
        });
  }
  void stop() {
    asio::post(acceptor_.get_executor(), [self = shared_from_this()] {
      boost::system::error_code ignored;
      self->acceptor_.close(ignored);
    });
  }

 private:
  asio::io_context& io_;
  tcp::acceptor acceptor_;  // on a strand: stop() closes it between accepts
  asio::steady_timer backoff_;
  ServerState& state_;
};

}  // namespace

// Holds an exclusive lock on DATA/server.lock for the life of the process (the kernel drops it
// when the process dies, kill -9 included): two servers on one job table would run jobs twice.
class DataLock {
 public:
  explicit DataLock(const std::filesystem::path& data) {
    std::filesystem::create_directories(data);
    const std::string path = (data / "server.lock").string();
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot open " + path);
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw std::runtime_error("another dem-server is using the data folder " + data.string());
  }
  ~DataLock() { ::close(fd_); }

 private:
  int fd_ = -1;
};

bool is_loopback(const std::string& address) {
  if (address == "localhost") return true;
  boost::system::error_code ec;
  const asio::ip::address a = asio::ip::make_address(address, ec);
  return !ec && a.is_loopback();
}

int run_server(const ServerOptions& options) {
  if (!is_loopback(options.address) && options.token.empty()) {
    std::fprintf(stderr,
                 "dem-server: listening on %s (not loopback) needs an access token: give --token TOKEN or set "
                 "DEM_SERVER_TOKEN; every request must then carry it\n",
                 options.address.c_str());
    return 2;
  }
  // a token that others on the network can guess by trying (no throttling slows them much: each
  // try is one cheap request) protects nothing; 16 characters of a random hex string is 64 bits
  constexpr std::size_t kShortestNetworkToken = 16;
  if (!is_loopback(options.address) && options.token.size() < kShortestNetworkToken) {
    std::fprintf(stderr,
                 "dem-server: listening on %s (not loopback) needs a token of at least %zu characters (got %zu); "
                 "make one with: openssl rand -hex 16\n",
                 options.address.c_str(), kShortestNetworkToken, options.token.size());
    return 2;
  }
  // The refusals above are the command's answer to its arguments (as main.cpp's are), printed
  // plainly; from here on the server logs, to stderr and DATA/server.log (one server a folder: the lock)
  const DataLock lock(options.data);
  const ServerLog server_log(options.data);
  FrameHub frames;
  ManagerOptions manager_options;
  manager_options.data = options.data;
  manager_options.concurrency = options.concurrency;
  manager_options.threads_per_job = options.threads_per_job;
  manager_options.checkpoint_seconds = options.checkpoint_seconds;
  manager_options.max_frame_rate = options.max_frame_rate;
  manager_options.max_output_bytes = options.max_output_bytes;
  manager_options.max_job_memory_bytes =
      options.max_job_memory_bytes > 0 ? options.max_job_memory_bytes : physical_memory_bytes() / 2;
  manager_options.retention.max_age_seconds = options.keep_finished_days * 86400;
  manager_options.retention.max_finished = options.keep_finished_jobs;
  JobManager jobs(manager_options, frames);
  ConnectionLimits connections(options.max_connections, options.max_connections_per_client);
  asio::thread_pool checks(2);  // submissions' checks; joined when the server returns
  StudyManager studies(options.data, jobs);
  ServerState state{jobs,
                    studies,
                    frames,
                    openapi_json(),
                    options.web,
                    options.cases,
                    options.token,
                    options.max_body,
                    connections,
                    checks,
                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                        std::chrono::duration<double>(options.request_timeout))};

  asio::io_context io(options.io_threads);
  boost::system::error_code ec;
  const asio::ip::address address =
      asio::ip::make_address(options.address == "localhost" ? "127.0.0.1" : options.address, ec);
  if (ec) {
    std::fprintf(stderr, "dem-server: --address %s is not an IP address\n", options.address.c_str());
    return 2;
  }
  std::shared_ptr<Listener> listener;
  try {
    listener = std::make_shared<Listener>(io, tcp::endpoint(address, options.port), state);
  } catch (const boost::system::system_error& e) {
    std::fprintf(stderr, "dem-server: cannot listen on %s port %u: %s\n", options.address.c_str(), options.port,
                 e.code().message().c_str());
    return 1;
  }
  listener->accept();
  jobs.start();
  const std::string host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
  // the first line on stdout, which scripts and the tests read for the port (spdlog's are on stderr)
  std::printf("dem-server listening on http://%s:%u/ (data: %s)\n", host.c_str(), listener->port(),
              options.data.c_str());
  std::fflush(stdout);
  spdlog::info("dem-server {} listening on http://{}:{}/ (data: {})", kVersion, host, listener->port(),
               options.data.string());

  asio::signal_set signals(io, SIGINT, SIGTERM);
  asio::steady_timer grace(io);
  signals.async_wait([&](boost::system::error_code, int signal) {
    std::printf("dem-server: signal %d: stopping (running jobs are checkpointed and stay queued)\n", signal);
    std::fflush(stdout);
    spdlog::info("signal {}: stopping (running jobs are checkpointed and stay queued)", signal);
    listener->stop();
    jobs.shutdown();
    frames.close_all("the server is shutting down");
    grace.expires_after(std::chrono::milliseconds(200));  // time for the close frames to go out
    grace.async_wait([&](boost::system::error_code) { io.stop(); });
    signals.async_wait([](boost::system::error_code, int) {  // asked twice: do not wait any longer
      spdlog::warn("second signal: exiting now (running jobs resume from their last checkpoints)");
      std::_Exit(1);
    });
  });

  std::vector<std::thread> threads;
  for (int k = 1; k < options.io_threads; ++k) threads.emplace_back([&] { io.run(); });
  io.run();
  for (std::thread& t : threads) t.join();
  jobs.shutdown();
  spdlog::info("stopped");
  std::printf("dem-server: stopped\n");
  return 0;
}

}  // namespace dem::server
