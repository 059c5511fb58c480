// A user-space UDP relay that delays, reorders and drops datagrams (issue
// 32): this machine's kernel has no netem. It runs on a thread of the test
// process inside a lab namespace, listens on `listen` there, forwards every
// datagram from the OCU to a fixed vehicle endpoint from a socket of its own,
// and every datagram from the vehicle back to the OCU endpoint it last heard
// from. Each datagram waits base + uniform(0, jitter) before it goes on (so a
// jitter larger than the spacing of two datagrams reorders them) unless it
// is dropped, with probability drop_probability.
//
// It can also be a field radio (issue 45, step 3; the same model as the
// virtual radio of jaus::testing::MemoryLink::set_rate and set_burst_loss,
// so what bench_radio_link measures in virtual time can be compared): each
// way a radio of `bits_per_second` sends what it holds one datagram after
// another (its size plus `overhead_bytes` at that rate), drops a datagram
// that finds `buffer_bytes` already waiting, and fades: each way alternates
// good and faded periods of random length (exponentially distributed, means
// mean_good and mean_fade) and a datagram whose last bit leaves in a fade is
// lost. The delay (base + jitter) starts when the datagram has left the
// radio. drop_out(d) loses everything, both ways, for d (a radio out of
// range): what is received meanwhile and what falls due meanwhile.
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
#include <optional>
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
  // The radio, each way; bits_per_second 0: no limit (nor buffer).
  std::uint64_t bits_per_second = 0;
  std::size_t buffer_bytes = 32 * 1024;
  std::size_t overhead_bytes = 36;  // IP and UDP headers and the radio's framing, per datagram
  // Fades, each way; mean_fade zero: none. 20 % of the time lost: 600 and 150 ms.
  std::chrono::milliseconds mean_good{600};
  std::chrono::milliseconds mean_fade{0};
  // Called on the relay's thread with each datagram as it goes on to the
  // vehicle and how long it was in the line (a test's look at what arrived
  // in which order, and when); may be empty.
  std::function<void(std::span<const std::uint8_t>, std::chrono::steady_clock::duration)> on_delivery_to_vehicle;
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
    std::uint64_t faded = 0;       // lost in a fade
    std::uint64_t overflowed = 0;  // dropped by a radio whose buffer was full
    std::uint64_t dropped_out = 0;  // lost in a drop-out
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
    return {received_.load(), forwarded_.load(), dropped_.load(), reordered_.load(),
            faded_.load(),    overflowed_.load(), dropped_out_.load()};
  }

  // Everything lost, both ways, from now for `d`.
  void drop_out(std::chrono::milliseconds d) {
    drop_out_until_.store((Clock::now() + d).time_since_epoch().count());
  }

 private:
  using Clock = std::chrono::steady_clock;
  enum Direction { to_vehicle = 0, to_ocu = 1 };
  struct Pending {
    Clock::time_point received;
    Clock::time_point due;
    std::uint64_t index;  // order of arrival within its direction
    Direction direction;
    std::vector<std::uint8_t> bytes;
  };

  // One way's radio: when it has sent all it holds, and its fades.
  struct Radio {
    Clock::time_point free_at{};
    bool faded = false;
    Clock::time_point period_ends{};  // of the good or faded period under way
  };

  explicit DelayLine(DelayLineOptions options)
      : options_(std::move(options)), random_(options_.seed), fade_random_(options_.seed + 1) {}

  bool dropped_out(Clock::time_point at) const { return at.time_since_epoch().count() < drop_out_until_.load(); }

  // A period's length: exponentially distributed with this mean.
  Clock::duration period_of(std::chrono::milliseconds mean) {
    std::exponential_distribution<double> length(1.0);
    return std::chrono::duration_cast<Clock::duration>(mean * length(fade_random_));
  }
  // Whether what leaves the radio at `at` is lost in a fade (`at` never goes back for one radio).
  bool faded(Radio& radio, Clock::time_point at) {
    if (options_.mean_fade <= std::chrono::milliseconds::zero()) return false;
    if (radio.period_ends == Clock::time_point{}) radio.period_ends = at + period_of(options_.mean_good);
    while (at >= radio.period_ends) {
      radio.faded = !radio.faded;
      radio.period_ends += period_of(radio.faded ? options_.mean_fade : options_.mean_good);
    }
    return radio.faded;
  }
  // When a datagram of `size` bytes has left `radio`, handed to it now;
  // nullopt: the radio's buffer is full.
  std::optional<Clock::time_point> through_radio(Radio& radio, std::size_t size, Clock::time_point now) {
    if (options_.bits_per_second == 0) return now;
    const double rate = static_cast<double>(options_.bits_per_second);
    const auto backlog = std::max(radio.free_at - now, Clock::duration::zero());
    const double held_bytes = std::chrono::duration<double>(backlog).count() * rate / 8;
    const std::size_t cost = size + options_.overhead_bytes;
    if (held_bytes + static_cast<double>(cost) > static_cast<double>(options_.buffer_bytes)) return std::nullopt;
    radio.free_at = now + backlog +
                    std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(static_cast<double>(cost) * 8 / rate));
    return radio.free_at;
  }

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
        const auto received_at = Clock::now();
        if (dropped_out(received_at)) {
          ++dropped_out_;
          continue;
        }
        if (drop(random_)) {
          ++dropped_;
          continue;
        }
        const auto left_radio = through_radio(radios_[direction], static_cast<std::size_t>(n), received_at);
        if (!left_radio) {
          ++overflowed_;
          continue;
        }
        if (faded(radios_[direction], *left_radio)) {
          ++faded_;
          continue;
        }
        const auto delay = options_.base + std::chrono::milliseconds(jitter_ms(random_));
        pending_.push_back({received_at, *left_radio + delay, index, direction,
                            std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + n)});
      }
      // Due datagrams go out in the order of their due times.
      std::stable_sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) { return a.due < b.due; });
      const auto due_now = Clock::now();
      auto first_not_due = pending_.begin();
      for (; first_not_due != pending_.end() && first_not_due->due <= due_now; ++first_not_due) {
        const Pending& p = *first_not_due;
        if (dropped_out(due_now)) {
          ++dropped_out_;
          continue;
        }
        if (p.index + 1 < latest_delivered[p.direction]) ++reordered_;
        latest_delivered[p.direction] = std::max(latest_delivered[p.direction], p.index + 1);
        const bool to_the_vehicle = p.direction == to_vehicle;
        if (!to_the_vehicle && ocu_.sin_family != AF_INET) continue;  // nobody to answer yet
        if (to_the_vehicle && options_.on_delivery_to_vehicle) options_.on_delivery_to_vehicle(p.bytes, due_now - p.received);
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
  std::mt19937 fade_random_;
  Radio radios_[2];
  std::atomic<Clock::rep> drop_out_until_{0};
  std::unique_ptr<InNamespace> in_namespace_;
  int ocu_side_ = -1;
  int vehicle_side_ = -1;
  sockaddr_in ocu_{};
  std::vector<Pending> pending_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> received_{0}, forwarded_{0}, dropped_{0}, reordered_{0};
  std::atomic<std::uint64_t> faded_{0}, overflowed_{0}, dropped_out_{0};
};

}  // namespace jaus::test::network
