// A TCP relay for tests: listens on a free loopback port, forwards every connection to a target
// port on loopback and keeps the last bytes that went through (both directions), so that a test
// can read what the wire carried. One thread per direction and connection: no relay deadlock.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace cosim::test {

// A loopback port nothing listens on right now (bound and released: a test picks its ports).
inline int freeLoopbackPort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    ::close(fd);
    throw std::runtime_error("no free loopback port");
  }
  ::close(fd);
  return ntohs(a.sin_port);
}

// A connection to 127.0.0.1:port, or -1.
inline int connectLoopback(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// True if the 8 bytes of `v` (as the wire packs a double) occur in `bytes`.
inline bool containsDouble(const std::string& bytes, double v) {
  char pattern[sizeof v];
  std::memcpy(pattern, &v, sizeof v);
  return bytes.find(std::string(pattern, sizeof v)) != std::string::npos;
}

class TcpRelay {
 public:
  // keep: how many of the most recent bytes are kept.
  explicit TcpRelay(int target_port, std::size_t keep = 16u << 20)
      : target_(target_port), keep_(keep) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::listen(listen_fd_, 16) != 0 ||
        ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
      throw std::runtime_error("relay: cannot listen on loopback");
    port_ = ntohs(a.sin_port);
    acceptor_ = std::thread([this] { acceptLoop(); });
  }
  ~TcpRelay() {
    stop_ = true;
    ::shutdown(listen_fd_, SHUT_RDWR);
    ::close(listen_fd_);
    if (acceptor_.joinable()) acceptor_.join();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (int fd : fds_) ::shutdown(fd, SHUT_RDWR);
    }
    for (auto& t : pumps_) t.join();
    for (int fd : fds_) ::close(fd);
  }
  TcpRelay(const TcpRelay&) = delete;
  TcpRelay& operator=(const TcpRelay&) = delete;

  int port() const { return port_; }
  std::string captured() {
    std::lock_guard<std::mutex> lock(mutex_);
    return bytes_;
  }
  std::size_t total() const { return total_; }
  int connections() const { return connections_; }

 private:
  void acceptLoop() {
    while (!stop_) {
      const int in = ::accept(listen_fd_, nullptr, nullptr);
      if (in < 0) return;
      const int out = connectLoopback(target_);
      if (out < 0) {
        ::close(in);
        continue;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      ++connections_;
      fds_.push_back(in);
      fds_.push_back(out);
      pumps_.emplace_back([this, in, out] { pump(in, out); });
      pumps_.emplace_back([this, in, out] { pump(out, in); });
    }
  }
  void pump(int from, int to) {
    std::vector<char> buf(1 << 16);
    for (;;) {
      const ssize_t n = ::read(from, buf.data(), buf.size());
      if (n <= 0) break;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        bytes_.append(buf.data(), static_cast<std::size_t>(n));
        if (bytes_.size() > 2 * keep_) bytes_.erase(0, bytes_.size() - keep_);
        total_ += static_cast<std::size_t>(n);
      }
      for (ssize_t done = 0; done < n;) {
        const ssize_t w = ::write(to, buf.data() + done, static_cast<std::size_t>(n - done));
        if (w <= 0) {
          ::shutdown(from, SHUT_RDWR);
          return;
        }
        done += w;
      }
    }
    ::shutdown(to, SHUT_WR);
  }

  int target_;
  std::size_t keep_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread acceptor_;
  std::mutex mutex_;
  std::vector<std::thread> pumps_;
  std::vector<int> fds_;
  std::string bytes_;
  std::atomic<std::size_t> total_{0};
  std::atomic<int> connections_{0};
};

}  // namespace cosim::test
