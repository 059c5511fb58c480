// A node's link held to a radio's rate, stops first (issue 45, step 2).
//
// A field radio carries 64 kbit/s to a few Mbit/s. Handed packets faster, it
// queues them in its own first-in-first-out buffer, so a Set Emergency sent
// after a camera frame waits behind the whole frame, seconds at those rates.
// The budgeted link stands between a node and its link and hands the link no
// more than `bits_per_second` (a token bucket: the link may go over by one
// packet, then waits until the time that packet takes has passed), so the
// radio's buffer stays short; what has to wait waits here, in five classes
// that leave strictly in this order:
//
//   stop        Set Emergency, Clear Emergency, Shutdown, Standby, Resume and
//               anything of priority 12-15, with their ACKs and NAKs: never
//               waits (charged to the budget all the same). Resume and Clear
//               Emergency travel with the stops so none overtakes another.
//   command     every other command (control, motion, ...) and its ACK/NAK,
//               however large (a command is never dropped for a newer one).
//   status      queries, reports that answer them, events, node management.
//   connection  service-connection reports: of each (source, destination,
//               code) only the newest waits; it replaces the older in place.
//   bulk        packets of large data sets (images) and single packets over
//               `bulk_threshold` bytes, commands aside: of each (source, destination, code)
//               the set already on its way is finished (a frame cut short is
//               a frame lost) and only the newest other one waits. So a
//               camera's rate falls to what the budget leaves it, whole
//               frames and the newest, instead of a queue that grows.
//
// A stop (Set Emergency, Shutdown, Standby) to a component also drops the
// commands to that component still waiting: issued before the stop, they
// would arrive after it and could undo it.
//
// Each class holds at most `queue_bytes`; what does not fit is dropped and
// counted (a command that must arrive is sent again by the ACK tracker).
// Sans-I/O: time from the injected clock, the wake-up from the injected
// scheduler, so tests and benchmarks run it under virtual time.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"
#include "jaus/node/node.hpp"

namespace jaus::node {

enum class SendClass : std::uint8_t { stop, command, status, connection, bulk };
inline constexpr std::size_t kSendClasses = 5;
std::string_view to_string(SendClass send_class);

struct SendBudgetOptions {
  // The rate the link may use; 0: no budget (the node sends through at once).
  std::uint64_t bits_per_second = 0;
  // How far ahead of the rate a burst may go; 0: 20 ms of the rate, at least
  // 512 bytes.
  std::size_t burst_bytes = 0;
  // What each packet costs beyond its JAUS bytes: IPv4 and UDP headers (28)
  // and the transport header.
  std::size_t overhead_bytes = 32;
  // Most bytes waiting in each class.
  std::size_t queue_bytes = 256 * 1024;
  // A single packet larger than this is bulk (a large data set's packets
  // always are), unless it is a command.
  std::size_t bulk_threshold = 1024;

  bool enabled() const { return bits_per_second > 0; }
};

// The most payload a packet should carry at this budget's rate: what the air
// carries in 50 ms, 512 to 4080 bytes (NodeConfig::large_data_set_piece), so
// a stop that follows a camera's packet waits at most that long in the radio.
std::size_t piece_size_for(const SendBudgetOptions& options);

// The class a packet with this header and size travels in.
SendClass send_class_of(const Header& header, std::size_t packet_size, const SendBudgetOptions& options);

struct SendBudgetCounters {
  struct PerClass {
    std::uint64_t sent = 0;        // packets handed to the link
    std::uint64_t bytes_sent = 0;  // their JAUS bytes
    std::uint64_t waited = 0;      // of those, how many waited here first
    std::uint64_t dropped = 0;     // the class's queue was full
    std::uint64_t superseded = 0;  // replaced by a newer one, or dropped by a stop
  };
  std::array<PerClass, kSendClasses> classes{};
  std::size_t queued_packets = 0;  // waiting now
  std::size_t queued_bytes = 0;
  std::size_t most_queued_bytes = 0;
  rt::Duration longest_wait{};  // of a packet that was sent

  const PerClass& of(SendClass c) const { return classes[static_cast<std::size_t>(c)]; }
};

class BudgetedLink final : public Link {
 public:
  // `inner` and the clock and scheduler outlive this link.
  BudgetedLink(Link& inner, rt::Clock& clock, rt::Scheduler& scheduler, SendBudgetOptions options);
  ~BudgetedLink() override;
  BudgetedLink(const BudgetedLink&) = delete;
  BudgetedLink& operator=(const BudgetedLink&) = delete;

  void transmit(const Header& header, std::span<const std::uint8_t> packet) override;
  std::uint64_t bits_per_second() const override { return options_.bits_per_second; }
  // Sends everything waiting now, class by class, whatever the budget: a
  // node's last words before its process exits.
  void flush();

  const SendBudgetOptions& options() const { return options_; }
  const SendBudgetCounters& counters() const { return counters_; }
  // One line for a log: "send budget 256 kbit/s: 40 of 900 packets waited
  // (longest 310 ms), 12 replaced by newer, 0 dropped".
  std::string summary() const;

 private:
  struct Waiting {
    Header header;
    std::vector<std::uint8_t> packet;
    rt::TimePoint since;
  };
  // The packets of one large data set (or one big single packet), sent
  // together; `started` once the first of them went.
  struct BulkUnit {
    Header first;  // what the set is known by: source, destination, code
    std::deque<Waiting> packets;
    bool started = false;
    bool complete = false;  // its last packet is here
  };

  void offer(SendClass send_class, const Header& header, std::span<const std::uint8_t> packet, rt::TimePoint now);
  void offer_bulk(const Header& header, std::span<const std::uint8_t> packet, rt::TimePoint now);
  void drop_commands_to(const Address& destination);
  // Counts the packet as waiting in its class if the class has room.
  bool fits(SendClass send_class, std::size_t bytes);
  void refill(rt::TimePoint now);
  // Sends what the budget allows now; arms the wake-up for the rest.
  void drain(bool whatever_the_budget = false);
  void send(const Header& header, std::span<const std::uint8_t> packet, SendClass send_class);
  void sent_after_wait(const Waiting& w, SendClass send_class, rt::TimePoint now);
  bool anything_waiting() const;
  // A packet that was waiting in this class no longer is.
  void forget(SendClass send_class, std::size_t bytes);

  Link& inner_;
  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  SendBudgetOptions options_;
  double bytes_per_second_;
  double burst_;
  double tokens_;  // bytes the link may still send now; negative: in debt
  rt::TimePoint refilled_at_;
  rt::TimerId wake_ = rt::kNoTimer;
  // command, status, connection: first in first out.
  std::array<std::deque<Waiting>, 3> fifo_;
  std::array<std::size_t, kSendClasses> queued_bytes_{};
  std::deque<BulkUnit> bulk_;
  SendBudgetCounters counters_;
};

}  // namespace jaus::node
