// A user-space UDP relay that delays, reorders and drops datagrams (issue
// 32): this machine's kernel has no netem. It runs on a thread of the test
// process inside a lab namespace, listens on `listen` there, forwards every
// datagram from the OCU to a fixed vehicle endpoint from a socket of its own,
// and every datagram from the vehicle back to the OCU endpoint it last heard
// from. Each datagram waits base + uniform(0, jitter) before it goes on (so a
// jitter larger than the spacing of two datagrams reorders them) unless it
// is dropped, with probability drop_probability.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <future>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "in_namespace.hpp"
#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::test::network {

struct DelayLineOptions {
  std::string name_space;  // the lab namespace the relay's sockets live in
  sockaddr_in listen{};    // where the OCU sends
  sockaddr_in vehicle{};   // where the relay forwards the OCU's datagrams
  std::chrono::milliseconds base{40};
  std::chrono::milliseconds jitter{80};
  double drop_probability = 0.0;
  std::uint32_t seed = 32;
  // Called on the relay's thread with each datagram as it goes on to the
  // vehicle (a test's look at what arrived in which order); may be empty.
  std::function<void(std::span<const std::uint8_t>)> on_delivery_to_vehicle;
};

inline sockaddr_in ipv4_endpoint(const char* address, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  ::inet_pton(AF_INET, address, &a.sin_addr);
  return a;
}

class DelayLine {
 public:
  struct Counters {
    std::uint64_t received = 0;   // both ways
    std::uint64_t forwarded = 0;
    std::uint64_t dropped = 0;
    std::uint64_t reordered = 0;  // delivered after a datagram of the same direction received later
  };

  static jaus::Expected<std::unique_ptr<DelayLine>> start(DelayLineOptions options) {
    std::unique_ptr<DelayLine> line(new DelayLine(std::move(options)));
    std::promise<jaus::Expected<void>> ready;
    auto opened = ready.get_future();
    line->thread_ = std::thread([raw = line.get(), &ready] { raw->run(ready); });
    auto r = opened.get();
    if (!r) return jaus::unexpected(r.error());
    return line;
  }
  ~DelayLine() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  DelayLine(const DelayLine&) = delete;
  DelayLine& operator=(const DelayLine&) = delete;

  Counters counters() const {
    return {received_.load(), forwarded_.load(), dropped_.load(), reordered_.load()};
  }

 private:
  using Clock = std::chrono::steady_clock;
  enum Direction { to_vehicle = 0, to_ocu = 1 };
  struct Pending {
    Clock::time_point due;
    std::uint64_t index;  // order of arrival within its direction
    Direction direction;
    std::vector<std::uint8_t> bytes;
  };

  explicit DelayLine(DelayLineOptions options) : options_(std::move(options)), random_(options_.seed) {}

  static jaus::Unexpected<jaus::Error> failure(const std::string& what) {
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::io, what + ": " + std::strerror(errno)));
  }

  // Both sockets, made inside the namespace (this thread stays there).
  jaus::Expected<void> open() {
    auto entered = InNamespace::enter(options_.name_space);
    if (!entered) return jaus::unexpected(entered.error());
    in_namespace_ = std::move(*entered);
    ocu_side_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    vehicle_side_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (ocu_side_ < 0 || vehicle_side_ < 0) return failure("socket");
    if (::bind(ocu_side_, reinterpret_cast<const sockaddr*>(&options_.listen), sizeof options_.listen) != 0)
      return failure("bind the delay line's listening socket");
    sockaddr_in any = options_.listen;
    any.sin_port = 0;
    if (::bind(vehicle_side_, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0)
      return failure("bind the delay line's vehicle-side socket");
    return {};
  }

  void run(std::promise<jaus::Expected<void>>& ready) {
    auto opened = open();
    const bool ok = static_cast<bool>(opened);
    ready.set_value(std::move(opened));  // `ready` is gone after this
    if (ok) loop();
    if (ocu_side_ >= 0) ::close(ocu_side_);
    if (vehicle_side_ >= 0) ::close(vehicle_side_);
    in_namespace_.reset();
  }

  void loop() {
    std::uniform_int_distribution<long> jitter_ms(0, options_.jitter.count());
    std::bernoulli_distribution drop(options_.drop_probability);
    std::uint64_t next_index[2] = {0, 0};
    std::uint64_t latest_delivered[2] = {0, 0};  // index + 1 of the latest-received datagram delivered
    std::vector<std::uint8_t> buffer(65536);
    while (!stop_) {
      auto timeout = std::chrono::milliseconds(10);  // at most this long before `stop_` is looked at
      const auto now = Clock::now();
      for (const auto& p : pending_)
        timeout = std::min(timeout, std::chrono::ceil<std::chrono::milliseconds>(std::max(p.due - now, Clock::duration{})));
      pollfd fds[2] = {{ocu_side_, POLLIN, 0}, {vehicle_side_, POLLIN, 0}};
      ::poll(fds, 2, static_cast<int>(timeout.count()));
      for (int side = 0; side < 2; ++side) {
        if (!(fds[side].revents & POLLIN)) continue;
        sockaddr_in from{};
        socklen_t from_size = sizeof from;
        const auto n = ::recvfrom(fds[side].fd, buffer.data(), buffer.size(), MSG_DONTWAIT,
                                  reinterpret_cast<sockaddr*>(&from), &from_size);
        if (n < 0) continue;
        const auto direction = side == 0 ? to_vehicle : to_ocu;
        if (direction == to_vehicle) ocu_ = from;
        ++received_;
        const auto index = next_index[direction]++;
        if (drop(random_)) {
          ++dropped_;
          continue;
        }
        const auto delay = options_.base + std::chrono::milliseconds(jitter_ms(random_));
        pending_.push_back({Clock::now() + delay, index, direction,
                            std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + n)});
      }
      // Due datagrams go out in the order of their due times.
      std::stable_sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) { return a.due < b.due; });
      const auto due_now = Clock::now();
      auto first_not_due = pending_.begin();
      for (; first_not_due != pending_.end() && first_not_due->due <= due_now; ++first_not_due) {
        const Pending& p = *first_not_due;
        if (p.index + 1 < latest_delivered[p.direction]) ++reordered_;
        latest_delivered[p.direction] = std::max(latest_delivered[p.direction], p.index + 1);
        const bool to_the_vehicle = p.direction == to_vehicle;
        if (!to_the_vehicle && ocu_.sin_family != AF_INET) continue;  // nobody to answer yet
        if (to_the_vehicle && options_.on_delivery_to_vehicle) options_.on_delivery_to_vehicle(p.bytes);
        const int socket = to_the_vehicle ? vehicle_side_ : ocu_side_;
        const sockaddr_in& to = to_the_vehicle ? options_.vehicle : ocu_;
        if (::sendto(socket, p.bytes.data(), p.bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) >= 0)
          ++forwarded_;
      }
      pending_.erase(pending_.begin(), first_not_due);
    }
  }

  DelayLineOptions options_;
  std::mt19937 random_;
  std::unique_ptr<InNamespace> in_namespace_;
  int ocu_side_ = -1;
  int vehicle_side_ = -1;
  sockaddr_in ocu_{};
  std::vector<Pending> pending_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> received_{0}, forwarded_{0}, dropped_{0}, reordered_{0};
};

}  // namespace jaus::test::network
