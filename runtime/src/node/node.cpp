#include "jaus/node/node.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "jaus/node/ack_reply.hpp"
#include "jaus/node/large_data_set_splitter.hpp"

namespace jaus::node {

namespace {
// How often liveness and reassembly timeouts are looked at (retransmissions
// have their own timer).
constexpr rt::Duration kHousekeepingPeriod = std::chrono::milliseconds(100);
constexpr std::uint8_t kNodeManager = 1;
constexpr std::uint8_t kCommunicator = 35;
}  // namespace

Node::Node(NodeConfig config, rt::Clock& clock, rt::Scheduler& scheduler, Link& link, rt::LogFn log)
    : config_(config),
      clock_(clock),
      scheduler_(scheduler),
      link_(link),
      log_(log ? std::move(log) : [](rt::LogLevel, const std::string&) {}),
      inbound_(PriorityQueue<Inbound>::Options{config.inbound_queue_capacity}),
      assembler_(config.large_data_sets),
      acks_(config.acks),
      duplicates_(config.duplicates),
      liveness_(config.liveness),
      sequences_(config.sequences),
      lines_(clock_, scheduler_, [this](rt::LogLevel level, const std::string& text) { this->log(level, text); }) {
  schedule_housekeeping();
}

Node::~Node() {
  if (housekeeping_timer_ != rt::kNoTimer) scheduler_.cancel(housekeeping_timer_);
  if (ack_timer_ != rt::kNoTimer) scheduler_.cancel(ack_timer_);
  components_.clear();  // before the queues they may still send into
}

void Node::log(rt::LogLevel level, const std::string& text) const {
  log_(level, "node " + std::to_string(config_.subsystem) + "." + std::to_string(config_.node) + ": " + text);
}

rt::Environment Node::environment() { return rt::Environment{clock_, scheduler_, *this, log_}; }

rt::Component& Node::add(std::unique_ptr<rt::Component> component) {
  rt::Component& c = *component;
  components_.push_back(std::move(component));
  if (auto* observer = dynamic_cast<rt::ConfigurationObserver*>(&c)) {
    configuration_holder_ = &c;
    configuration_observer_ = observer;
  }
  c.start();
  log(rt::LogLevel::info, "hosts " + c.name() + " " + c.address().to_string());
  if (configuration_observer_) configuration_observer_->configuration_changed();
  return c;
}

void Node::remove(const Address& address) {
  const auto it = std::find_if(components_.begin(), components_.end(),
                               [&](const auto& c) { return c->address() == address; });
  if (it == components_.end()) return;
  if (it->get() == configuration_holder_) {
    configuration_holder_ = nullptr;
    configuration_observer_ = nullptr;
  }
  components_.erase(it);
  log(rt::LogLevel::info, "removed " + address.to_string());
  if (configuration_observer_) configuration_observer_->configuration_changed();
}

void Node::shutdown(std::string_view why) {
  // The node manager (the configuration observer) goes last, so its peers
  // hear the others leave first.
  for (auto& c : components_)
    if (c.get() != configuration_holder_) c->shutdown(why);
  if (configuration_holder_) configuration_holder_->shutdown(why);
  configuration_holder_ = nullptr;
  configuration_observer_ = nullptr;
  components_.clear();
}

rt::Component* Node::find(const Address& address) const {
  for (const auto& c : components_)
    if (c->address() == address) return c.get();
  return nullptr;
}

std::vector<const rt::Component*> Node::local_components() const {
  std::vector<const rt::Component*> out;
  for (const auto& c : components_) out.push_back(c.get());
  return out;
}

std::vector<Address> Node::known_subsystems() const {
  // Per subsystem, who speaks for it: a node manager heard (lowest node),
  // else a communicator heard, else the node manager of the lowest node heard
  // (every node has one). One pass per level: the entries come in address order.
  std::array<std::optional<Address>, 256> manager, communicator, lowest_node;
  for (const auto& c : liveness_.known(LivenessLevel::component)) {
    const Address& a = c.address;
    if (!manager[a.subsystem] && a.component == kNodeManager && a.instance == 1) manager[a.subsystem] = a;
    if (!communicator[a.subsystem] && a.component == kCommunicator) communicator[a.subsystem] = a;
  }
  for (const auto& n : liveness_.known(LivenessLevel::node))
    if (!lowest_node[n.address.subsystem])
      lowest_node[n.address.subsystem] = Address{n.address.subsystem, n.address.node, kNodeManager, 1};
  std::vector<Address> out{Address{config_.subsystem, config_.node, kNodeManager, 1}};
  for (const auto& subsystem : liveness_.known(LivenessLevel::subsystem)) {
    const std::uint8_t id = subsystem.address.subsystem;
    if (id == config_.subsystem) continue;
    out.push_back(manager[id]        ? *manager[id]
                  : communicator[id] ? *communicator[id]
                  : lowest_node[id]  ? *lowest_node[id]
                                     : Address{id, 1, kNodeManager, 1});
  }
  return out;
}

bool Node::holds_state_for(std::uint8_t subsystem, std::uint8_t node) const {
  const Address whole_node{subsystem, node, 0, 0};  // 0 below: every component of it (Address::covers)
  return std::any_of(components_.begin(), components_.end(),
                     [&](const auto& c) { return c->keeps_state_for(whole_node); });
}

bool Node::hosts_component(std::uint8_t component_id) const {
  return std::any_of(components_.begin(), components_.end(),
                     [&](const auto& c) { return c->address().component == component_id; });
}

void Node::subsystems_changed() {
  if (configuration_observer_) configuration_observer_->subsystems_changed();
}

bool Node::is_local(const Address& d) const {
  return (d.subsystem == config_.subsystem || d.subsystem == Address::kBroadcast) &&
         (d.node == config_.node || d.node == Address::kBroadcast);
}

bool Node::reaches_elsewhere(const Address& d) const {
  return d.subsystem != config_.subsystem || d.node != config_.node;
}

std::size_t Node::local_matches(const Address& destination, const Address& exclude) const {
  std::size_t n = 0;
  for (const auto& c : components_)
    if (destination.matches(c->address()) && c->address() != exclude) ++n;
  return n;
}

std::optional<Address> Node::first_local_match(const Address& destination) const {
  for (const auto& c : components_)
    if (destination.matches(c->address())) return c->address();
  return std::nullopt;
}

// ---- from the network ------------------------------------------------------------

void Node::receive_bytes(std::span<const std::uint8_t> bytes) {
  auto decoded = decode_packet(bytes);
  if (!decoded) {
    ++counters_.packets_received;
    ++counters_.malformed;
    lines_.write("malformed packets dropped", rt::LogLevel::warn,
                 [&] { return "dropped a malformed packet: " + decoded.error().message(); });
    return;
  }
  receive(*decoded);
}

void Node::receive(const PacketView& packet, rt::SenderStanding standing) {
  ++counters_.packets_received;
  const Header& h = packet.header;
  const Address& s = h.source;
  if (!s.is_valid() || s.is_broadcast()) {
    ++counters_.invalid_source;
    lines_.write("packets from invalid sources dropped", rt::LogLevel::warn,
                 [&] { return "dropped a packet from invalid source " + s.to_string(); });
    return;
  }
  if (s.subsystem == config_.subsystem && s.node == config_.node) {
    // Our own broadcast looped back (multicast), or a peer misconfigured with our ID.
    ++counters_.from_self;
    return;
  }
  if (auto* peer = peers_.of(s)) ++peer->packets_received;
  const rt::TimePoint now = clock_.now();
  const HeardResult heard = liveness_.heard(s, now);
  if (heard.new_subsystem && s.subsystem != config_.subsystem) {
    lines_.write({"subsystems found", rt::kNoteworthyBurst}, rt::LogLevel::info,
                 [&] { return "subsystem " + std::to_string(s.subsystem) + " found (" + s.to_string() + ")"; });
    subsystems_changed();
  }
  // What a sender leaves behind ends when its node (or subsystem) falls
  // silent (peer_lost); a silent component alone ends nothing. So a sender
  // is unrecorded when its node is not in the table: a new component of a
  // known node, refused a component entry by a full table, still is.
  if (!heard.recorded && !liveness_.find_node(s)) {
    standing = rt::SenderStanding::unrecorded;
    ++counters_.unrecorded_senders;
    lines_.write("packets from senders the liveness table cannot record", rt::LogLevel::warn, [&] {
      return "liveness table full: " + s.to_string() + " not recorded; what it asks may not outlive it";
    });
  }
  if (!is_local(h.destination)) {
    ++counters_.not_for_this_node;
    return;
  }
  // ACK and NAK answer our own ACK-requested messages.
  if (h.ack_nak == AckNak::ack || h.ack_nak == AckNak::nak) {
    const auto resolution = acks_.on_reply(h, now);
    if (!resolution) return;
    if (auto* peer = peers_.of(s))
      ++(resolution->outcome == AckOutcome::acknowledged ? peer->acknowledged : peer->refused);
    if (resolution->outcome != AckOutcome::acknowledged)
      lines_.write("packets to unresolved destinations dropped", rt::LogLevel::warn, [&] {
        return "0x" + wire::detail::hex_u32(h.command_code) + " to " + s.to_string() + " " +
               std::string(to_string(resolution->outcome));
      });
    resolve(*resolution);  // last: the callback may send, or end the node
    return;
  }
  auto assembled = assembler_.feed(h, packet.payload, now, rt::doubt_of(standing));
  switch (assembled.status) {
    case AssemblyStatus::single:
      enqueue(Inbound{h, copy_payload(packet.payload), Address{}, standing});
      return;
    case AssemblyStatus::complete: {
      // As trusted as its least trusted packet, whichever completed it.
      const auto least = rt::standing_of_doubt(assembled.message->doubt);
      enqueue(Inbound{assembled.message->header, std::move(assembled.message->payload), Address{}, least});
      return;
    }
    case AssemblyStatus::pending:
      return;
    case AssemblyStatus::dropped:
      lines_.write("large data set packets dropped", rt::LogLevel::warn, [&] {
        return "large data set packet 0x" + wire::detail::hex_u32(h.command_code) + " from " + s.to_string() +
               " dropped: " + std::string(to_string(assembled.issue));
      });
      return;
  }
}

void Node::enqueue(Inbound message) {
  const std::uint8_t priority = message.header.priority;
  auto pushed = inbound_.push(priority, std::move(message));
  if (pushed.dropped) {
    ++counters_.queue_dropped;
    lines_.write("inbound queue full", rt::LogLevel::warn, [&] {
      return "inbound queue full: dropped a priority " + std::to_string(pushed.dropped_priority) + " message";
    });
  }
  if (drain_posted_) return;
  drain_posted_ = true;
  // Posted, not timed: no timer armed per message. The node may be gone
  // when it runs (a host stopped in between): `alive` says.
  scheduler_.post([this, alive = std::weak_ptr<const char>(alive_)] {
    if (alive.lock()) drain();
  });
}

void Node::drain() {
  drain_posted_ = false;
  // Highest priority first; safety-critical (12-15) before everything queued.
  while (auto message = inbound_.pop()) {
    const Header& h = message->header;
    // Checked here, not on arrival: a first copy the full queue dropped was
    // never delivered, so its retransmission is not a duplicate; and of two
    // copies queued together only the first acts.
    const DuplicateVerdict verdict = message->exclude == Address{}
                                         ? duplicates_.check(h, message->payload, clock_.now())
                                         : DuplicateVerdict::not_filtered;
    if (verdict == DuplicateVerdict::new_session)
      lines_.write({"senders restarted", rt::kNoteworthyBurst}, rt::LogLevel::info, [&] {
        return h.source.to_string() + " restarted (sequence number " + std::to_string(h.sequence) + " to " +
               h.destination.to_string() + " begins a new session): its earlier messages forgotten";
      });
    if (is_dropped(verdict)) {
      ++counters_.duplicates_filtered;
      if (auto* peer = peers_.of(h.source)) ++peer->duplicates;
      answer_ack_request(h, first_local_match(h.destination));  // the ACK of the first copy was lost
      recycle_payload(std::move(message->payload));
      continue;
    }
    bool delivered = false;
    Address first_receiver;  // answers an ACK request: a broadcast's sender matches the ACK against it
    for (std::size_t i = 0; i < components_.size(); ++i) {
      rt::Component* c = components_[i].get();
      if (!h.destination.matches(c->address()) || c->address() == message->exclude) continue;
      if (!delivered) first_receiver = c->address();
      c->receive(h, message->payload, config_.dialect, message->standing);
      delivered = true;
      ++counters_.delivered;
      // A component that shut down leaves the node (after this message).
      if (c->state() == msg::PrimaryStatus::shutdown) {
        const Address gone = c->address();
        scheduler_.call_at(clock_.now(), [this, gone] { remove(gone); });
      }
    }
    if (!delivered && !h.destination.is_broadcast()) {
      ++counters_.undeliverable;
      lines_.write("messages for no local component", rt::LogLevel::debug, [&] {
        return "no component " + h.destination.to_string() + " for 0x" + wire::detail::hex_u32(h.command_code) +
               " from " + h.source.to_string();
      });
    }
    if (h.ack_nak == AckNak::ack_requested && message->exclude == Address{})
      answer_ack_request(h, delivered ? std::optional<Address>(first_receiver) : std::nullopt);
    recycle_payload(std::move(message->payload));
  }
}

std::vector<std::uint8_t> Node::copy_payload(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> copy;
  if (!spare_payloads_.empty()) {
    copy = std::move(spare_payloads_.back());
    spare_payloads_.pop_back();
  }
  copy.assign(payload.begin(), payload.end());  // within the spare's capacity once traffic has been seen
  return copy;
}

void Node::recycle_payload(std::vector<std::uint8_t> payload) {
  // Large data sets' buffers are not kept: the spares stay a few kilobytes.
  if (payload.capacity() == 0 || payload.capacity() > kMaxPayloadSize || spare_payloads_.size() >= kSparePayloads)
    return;
  payload.clear();
  spare_payloads_.push_back(std::move(payload));
}

void Node::answer_ack_request(const Header& h, std::optional<Address> receiver) {
  const bool delivered = receiver.has_value();
  // A broadcast no component here took may be another node's to take: a
  // NAK from here would settle it at its sender before that node's ACK.
  if (!delivered && h.destination.is_broadcast()) return;
  const Address responder = delivered ? *receiver : h.destination;
  const auto reply = ack_reply_for(h, responder, delivered ? Delivery::delivered : Delivery::undeliverable);
  if (!reply) return;
  ++(delivered ? counters_.acks_sent : counters_.naks_sent);
  transmit(*reply, {});
}

// ---- from local components -----------------------------------------------------

void Node::send(const Header& given, std::span<const std::uint8_t> payload) {
  Header h = given;
  // Service connection reports carry their own per-SC sequence numbers.
  if (!h.service_connection) h.sequence = sequences_.take({h.source, h.destination});
  if (is_local(h.destination) && local_matches(h.destination, h.source) > 0)
    enqueue(Inbound{h, copy_payload(payload), h.source});
  if (!reaches_elsewhere(h.destination)) return;
  if (h.ack_nak == AckNak::ack_requested && payload.size() > kMaxPayloadSize) {
    // An ACK answers one packet; a large data set is not tracked as a whole.
    lines_.write("ACK requests on large data sets ignored", rt::LogLevel::debug,
                 [&] { return "ACK request on a large data set ignored"; });
    h.ack_nak = AckNak::none;
  }
  if (h.ack_nak == AckNak::ack_requested) {
    const auto tracked = acks_.track(h, payload, clock_.now());
    if (tracked == TrackResult::full) {
      ++counters_.send_failures;
      lines_.write("too many messages awaiting ACK", rt::LogLevel::warn, [&] {
        return "too many messages awaiting ACK: 0x" + wire::detail::hex_u32(h.command_code) + " to " +
               h.destination.to_string() + " not sent";
      });
      return;
    }
    arm_ack_timer();
  }
  // A message that must arrive keeps whole packets: its copies go again as
  // one packet (transmit), so its first transmission does too.
  const std::size_t piece = h.ack_nak == AckNak::ack_requested
                                ? kMaxPayloadSize
                                : std::clamp<std::size_t>(config_.large_data_set_piece, 1, kMaxPayloadSize);
  if (payload.size() <= piece) {
    transmit(h, payload);
    return;
  }
  // The common RA 3.3 peer drops a large data set whose first packet is not
  // numbered 0 (the RA leaves the start free): for it, every set starts at 0.
  if (config_.dialect == wire::Dialect::openjaus) h.sequence = 0;
  auto splitter = LargeDataSetSplitter::create(h, payload, piece);
  if (!splitter) {
    ++counters_.send_failures;
    lines_.write("messages that cannot be split", rt::LogLevel::error, [&] {
      return "cannot split 0x" + wire::detail::hex_u32(h.command_code) + ": " + splitter.error().message();
    });
    return;
  }
  // A large data set numbers its packets s, s+1, ...: reserve the rest.
  if (splitter->packet_count() > 1 && config_.dialect == wire::Dialect::ra)
    sequences_.take({h.source, h.destination}, static_cast<std::uint16_t>(splitter->packet_count() - 1));
  for (std::size_t i = 0; i < splitter->packet_count(); ++i) {
    const PacketView packet = splitter->packet(i);
    auto size = splitter->encode(i, tx_buffer_);
    if (!size) {
      ++counters_.send_failures;
      return;
    }
    ++counters_.packets_sent;
    if (auto* peer = peers_.of(packet.header.destination)) ++peer->packets_sent;
    link_.transmit(packet.header, std::span(tx_buffer_).first(*size));
  }
}

AckKey Node::send_acknowledged(const Header& given, std::span<const std::uint8_t> payload, AckPolicy policy,
                               AckCallback on_resolved) {
  Header h = given;
  h.ack_nak = AckNak::ack_requested;
  if (!h.service_connection) h.sequence = sequences_.take({h.source, h.destination});
  const AckKey key = ack_key_of_sent(h);
  if (payload.size() > kMaxPayloadSize) {
    ++counters_.send_failures;
    lines_.write("ACK requests on large data sets refused", rt::LogLevel::warn, [&] {
      return "0x" + wire::detail::hex_u32(h.command_code) + " to " + h.destination.to_string() +
             " not sent: an ACK answers one packet, not a large data set";
    });
    resolve_soon(std::move(on_resolved), {key, AckOutcome::exhausted, 0});
    return key;
  }
  const std::size_t here = is_local(h.destination) ? local_matches(h.destination, h.source) : 0;
  if (!reaches_elsewhere(h.destination)) {
    if (here > 0) enqueue(Inbound{h, copy_payload(payload), h.source});
    resolve_soon(std::move(on_resolved), {key, here > 0 ? AckOutcome::acknowledged : AckOutcome::refused, 0});
    return key;
  }
  if (acks_.track(h, payload, clock_.now(), policy) != TrackResult::tracked) {
    ++counters_.send_failures;
    lines_.write("too many messages awaiting ACK", rt::LogLevel::warn, [&] {
      return "too many messages awaiting ACK: 0x" + wire::detail::hex_u32(h.command_code) + " to " +
             h.destination.to_string() + " not sent";
    });
    resolve_soon(std::move(on_resolved), {key, AckOutcome::exhausted, 0});
    return key;
  }
  if (on_resolved) ack_callbacks_[key] = std::move(on_resolved);
  if (here > 0) enqueue(Inbound{h, copy_payload(payload), h.source});
  transmit(h, payload);
  arm_ack_timer();
  return key;
}

std::optional<std::uint32_t> Node::forget_acknowledged(const AckKey& key) {
  ack_callbacks_.erase(key);
  return acks_.forget(key);
}

void Node::resolve(const AckResolution& resolution) {
  const auto it = ack_callbacks_.find(resolution.key);
  if (it == ack_callbacks_.end()) return;
  // Out of the table before the call: the callback may send again.
  AckCallback on_resolved = std::move(it->second);
  ack_callbacks_.erase(it);
  on_resolved(resolution);
}

void Node::resolve_soon(AckCallback on_resolved, const AckResolution& resolution) {
  if (!on_resolved) return;
  scheduler_.post([alive = std::weak_ptr<const char>(alive_), on_resolved = std::move(on_resolved), resolution] {
    if (alive.lock()) on_resolved(resolution);
  });
}

void Node::transmit(const Header& header, std::span<const std::uint8_t> payload) {
  if (payload.size() > kMaxPayloadSize) {  // callers split first; never write past the buffer
    ++counters_.send_failures;
    return;
  }
  Header h = header;
  h.data_size = static_cast<std::uint16_t>(payload.size());
  encode_header_unchecked(h, std::span(tx_buffer_).first<kHeaderSize>());
  std::copy(payload.begin(), payload.end(), tx_buffer_.begin() + kHeaderSize);
  ++counters_.packets_sent;
  if (auto* peer = peers_.of(h.destination)) ++peer->packets_sent;
  link_.transmit(h, std::span(tx_buffer_).first(kHeaderSize + payload.size()));
}

// ---- timers ----------------------------------------------------------------------

void Node::schedule_housekeeping() {
  housekeeping_timer_ = scheduler_.call_at(clock_.now() + kHousekeepingPeriod, [this] { housekeeping(); });
}

void Node::housekeeping() {
  housekeeping_timer_ = rt::kNoTimer;
  const rt::TimePoint now = clock_.now();
  bool subsystem_lost = false;
  for (const auto& gone : liveness_.expire(now)) {
    // A silent component whose node still heartbeats is normal: an OCU that
    // only receives reports sends nothing from its component. Losing its node
    // (or subsystem) is what ends its service connections and control; a
    // silent controller on a live node is caught by the component's own
    // controller liveness check (Query Component Status).
    if (gone.level == LivenessLevel::component) {
      lines_.write("silent peers forgotten", rt::LogLevel::debug,
                   [&] { return gone.address.to_string() + " silent: forgotten"; });
      continue;
    }
    lines_.write({"peers lost", rt::kNoteworthyBurst}, rt::LogLevel::info, [&] {
      return std::string(gone.level == LivenessLevel::node ? "node " : "subsystem ") + gone.address.to_string() +
             " silent: lost";
    });
    for (const auto& c : components_) c->peer_lost(gone.address);
    subsystem_lost |= gone.level == LivenessLevel::subsystem && gone.address.subsystem != config_.subsystem;
  }
  if (subsystem_lost) subsystems_changed();
  for (const auto& discarded : assembler_.expire(now)) {
    lines_.write("large data sets discarded", rt::LogLevel::warn, [&] {
      return "large data set 0x" + wire::detail::hex_u32(discarded.key.message) + " from " +
             discarded.key.source.to_string() + " discarded: " + std::string(to_string(discarded.reason));
    });
  }
  schedule_housekeeping();
}

void Node::arm_ack_timer() {
  const auto deadline = acks_.next_deadline();
  if (!deadline) return;
  if (ack_timer_ != rt::kNoTimer) {
    if (ack_timer_due_ <= *deadline) return;
    scheduler_.cancel(ack_timer_);
  }
  ack_timer_due_ = *deadline;
  ack_timer_ = scheduler_.call_at(*deadline, [this] {
    ack_timer_ = rt::kNoTimer;
    service_acks();
  });
}

void Node::service_acks() {
  auto poll = acks_.poll(clock_.now());
  for (const auto& again : poll.retransmit) {
    if (auto* peer = peers_.of(again.header.destination)) ++peer->retransmissions;
    transmit(again.header, again.payload);
  }
  const std::weak_ptr<const char> alive = alive_;
  for (const auto& failed : poll.failed) {
    if (auto* peer = peers_.of(failed.key.peer)) ++peer->unacknowledged;
    lines_.write({"messages never acknowledged", rt::kNoteworthyBurst}, rt::LogLevel::warn, [&] {
      return "no ACK for 0x" + wire::detail::hex_u32(failed.key.command_code) + " to " + failed.key.peer.to_string() +
             " after " + std::to_string(failed.transmissions) + " transmissions";
    });
    resolve(failed);
    if (alive.expired()) return;  // a callback ended the node
  }
  arm_ack_timer();
}

}  // namespace jaus::node
