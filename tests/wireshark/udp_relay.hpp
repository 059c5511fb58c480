// A recording UDP relay between an OCU and a node: the OCU talks to `front`,
// the relay talks to the node from `back`, and every datagram it passes on is
// kept (with the OCU's and the node's real endpoints) for a capture file. It
// replaces a live capture, which needs privileges CI may not have.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "pcap_writer.hpp"

namespace jaus::test {

struct RecordedDatagram {
  UdpEndpoint from;
  UdpEndpoint to;
  std::vector<std::uint8_t> bytes;
};

class UdpRelay {
 public:
  UdpRelay(const UdpEndpoint& front, const UdpEndpoint& back, const UdpEndpoint& node)
      : front_(open_bound(front)), back_(open_bound(back)), node_(node) {
    if (front_ >= 0 && back_ >= 0) thread_ = std::thread([this] { run(); });
  }
  ~UdpRelay() {
    stop();
    if (front_ >= 0) ::close(front_);
    if (back_ >= 0) ::close(back_);
  }
  UdpRelay(const UdpRelay&) = delete;
  UdpRelay& operator=(const UdpRelay&) = delete;

  bool ok() const { return front_ >= 0 && back_ >= 0; }
  void stop() {
    stopping_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::vector<RecordedDatagram> recorded() const {
    std::lock_guard lock(mutex_);
    return recorded_;
  }

 private:
  static sockaddr_in to_sockaddr(const UdpEndpoint& e) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(e.port);
    std::uint32_t ip = 0;
    for (const auto octet : e.ip) ip = (ip << 8) | octet;
    a.sin_addr.s_addr = htonl(ip);
    return a;
  }
  static UdpEndpoint from_sockaddr(const sockaddr_in& a) {
    const std::uint32_t ip = ntohl(a.sin_addr.s_addr);
    return {{static_cast<std::uint8_t>(ip >> 24), static_cast<std::uint8_t>(ip >> 16),
             static_cast<std::uint8_t>(ip >> 8), static_cast<std::uint8_t>(ip)},
            ntohs(a.sin_port)};
  }
  static int open_bound(const UdpEndpoint& e) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    const auto a = to_sockaddr(e);
    if (fd >= 0 && ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
      ::close(fd);
      return -1;
    }
    return fd;
  }

  void run() {
    std::vector<std::uint8_t> buffer(65536);
    while (!stopping_) {
      pollfd fds[2] = {{front_, POLLIN, 0}, {back_, POLLIN, 0}};
      if (::poll(fds, 2, 50) <= 0) continue;  // the timeout only lets stop() be seen
      for (int i = 0; i < 2; ++i) {
        if (!(fds[i].revents & POLLIN)) continue;
        sockaddr_in sender{};
        socklen_t length = sizeof sender;
        const auto n =
            ::recvfrom(fds[i].fd, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&sender), &length);
        if (n < 0) continue;
        std::vector<std::uint8_t> bytes(buffer.begin(), buffer.begin() + n);
        if (i == 0) {
          // OCU -> node: recorded as sent from the OCU to the node.
          ocu_ = from_sockaddr(sender);
          const auto to = to_sockaddr(node_);
          ::sendto(back_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
          record(*ocu_, node_, std::move(bytes));
        } else if (ocu_ && from_sockaddr(sender).port == node_.port) {
          const auto to = to_sockaddr(*ocu_);
          ::sendto(front_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
          record(node_, *ocu_, std::move(bytes));
        }
      }
    }
  }
  void record(const UdpEndpoint& from, const UdpEndpoint& to, std::vector<std::uint8_t> bytes) {
    std::lock_guard lock(mutex_);
    recorded_.push_back({from, to, std::move(bytes)});
  }

  int front_;
  int back_;
  UdpEndpoint node_;
  std::optional<UdpEndpoint> ocu_;
  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  std::vector<RecordedDatagram> recorded_;
  std::thread thread_;
};

}  // namespace jaus::test
