// A command to a wildcard address (255 in some field: 1.255.255.255, "all")
// that reaches every component it names and says which confirmed it
// (issue 49). A broadcast asks no ACK (every receiver would answer, and the
// first ACK would say nothing of the others: must_arrive.hpp), and before
// this a broadcast stop was "sent" even when it went nowhere: to a vehicle
// not heard yet, a broadcast had no endpoint at all.
//
// How it goes, while it runs (policy.look_for at most):
// - a stop (Set Emergency, Standby, Shutdown: is_stop()) goes as the
//   broadcast at once and again every policy.repeat_every, so a component
//   not found yet stops as soon as any copy reaches it (the session's link
//   sends a subsystem's broadcast to the multicast group, to the nodes heard
//   as the subsystem's and to the configured peers not heard yet:
//   UdpLinkOptions::broadcast_to_unheard_peers);
// - the members are found: Query Configuration (subsystem) to the node
//   managers the address names, asked again every policy.ask_every, and
//   Query Configuration (node) to every node of it heard from; each
//   component a Report Configuration lists that the address names is a member;
// - each member gets its own copy with an ACK request, retransmitted until
//   its node ACKs it (its component acted on it) or policy.per_member gives
//   up: a member is confirmed by its ACK, nothing else.
// It is finished when every member found has answered, every node heard has
// said what it hosts, and nothing new was heard for policy.settle; or when
// policy.look_for has passed (then members still waiting are unconfirmed);
// or when the session is asked to stop. A command to nobody is finished at
// look_for with no member: the caller says none confirmed it.
//
// Not a stop (Clear Emergency, Resume, ...): no broadcast, only the members'
// own copies, so each component acts on it once and confirms it.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::ocu {

struct WildcardPolicy {
  jaus::rt::Duration repeat_every = std::chrono::milliseconds(50);  // the broadcast of a stop
  jaus::rt::Duration ask_every = std::chrono::milliseconds(250);    // Query Configuration again
  jaus::rt::Duration look_for = std::chrono::seconds(3);            // the longest it runs
  jaus::rt::Duration settle = std::chrono::milliseconds(500);       // quiet before it is finished
  // Each member's own copy; none: the session's settings for a command
  // (SessionOptions::must_arrive; the broadcast repeats a stop meanwhile).
  std::optional<MustArrivePolicy> per_member;
};

struct WildcardMember {
  jaus::Address address;
  std::optional<Arrival> outcome;  // none: still waiting (unacknowledged once finished)
  std::uint32_t transmissions = 0;
};

struct WildcardResult {
  std::vector<WildcardMember> members;  // by address
  std::uint32_t broadcasts = 0;         // copies of the broadcast sent (0: not a stop)
  jaus::rt::Duration elapsed{};
  bool interrupted = false;
  std::vector<jaus::Address> confirmed() const;    // ACKed
  std::vector<jaus::Address> unconfirmed() const;  // NAKed, not ACKed, or never answered
};

// Set Emergency, Standby, Shutdown: what a wildcard sends as a broadcast too.
bool is_stop(std::uint16_t command_code);

class WildcardCommand {
 public:
  using Done = std::function<void(const WildcardResult&)>;

  // `header`: the command code and priority are kept; source, destination and
  // size are set here. `to` must be a broadcast address (255 somewhere).
  WildcardCommand(OcuSession& session, const jaus::Address& to, jaus::Header header, std::vector<std::uint8_t> payload,
                  WildcardPolicy policy = {}, Done done = {});
  ~WildcardCommand();
  WildcardCommand(const WildcardCommand&) = delete;
  WildcardCommand& operator=(const WildcardCommand&) = delete;

  void start();
  // Finishes now (the session was asked to stop, the console shuts down):
  // members still waiting are `interrupted`.
  void stop() { finish(true); }
  bool finished() const { return finished_; }
  const WildcardResult& result() const { return result_; }
  const jaus::Address& target() const { return to_; }

 private:
  struct NodeKey {
    std::uint8_t subsystem = 0, node = 0;
    auto operator<=>(const NodeKey&) const = default;
  };
  // What the node calls back with, which may outlive this command.
  struct Answers {
    std::map<jaus::Address, std::pair<Arrival, std::uint32_t>> by_member;
  };

  void tick();
  void ask_subsystems();
  void heard(const jaus::Address& source);
  void received(const Received& message);
  void add_member(const jaus::Address& member);
  void send_broadcast();
  void check_finished();
  void finish(bool interrupted);
  bool in_scope(std::uint8_t subsystem, std::uint8_t node) const;
  jaus::Header header_to(const jaus::Address& to) const;

  OcuSession& session_;
  jaus::Address to_;
  jaus::Header header_;
  std::vector<std::uint8_t> payload_;
  WildcardPolicy policy_;
  Done done_;
  bool stop_ = false;
  bool started_ = false;
  bool finished_ = false;
  jaus::rt::TimePoint started_at_{};
  jaus::rt::TimePoint last_news_{};
  jaus::rt::TimePoint next_ask_{};
  std::map<NodeKey, bool> nodes_;  // heard of -> said what it hosts
  std::set<jaus::Address> members_;
  std::shared_ptr<Answers> answers_ = std::make_shared<Answers>();
  WildcardResult result_;
  jaus::rt::TimerId timer_ = jaus::rt::kNoTimer;
  OcuSession::ListenerId listener_ = 0;
  OcuSession::ListenerId watcher_ = 0;
};

// The blocking form (jausctl): starts it and runs the session until it is finished.
WildcardResult send_to_every_member(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                    std::span<const std::uint8_t> payload, WildcardPolicy policy = {});

template <class M>
WildcardResult send_to_every_member(OcuSession& session, const jaus::Address& to, const M& message,
                                    std::uint8_t priority = jaus::priority::kDefault, WildcardPolicy policy = {}) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  if (!size) return WildcardResult{};
  jaus::Header header;
  header.priority = priority;
  header.command_code = M::code;
  return send_to_every_member(session, to, header, std::span(payload).first(*size), policy);
}

}  // namespace jaus::ocu
