// The JSS face (face.hpp): AS5669A datagrams in, each message offered to the
// translators for every component its destination reaches; the RA messages
// of those translators enter the node from the client's alias; what the
// components send to aliases goes back through the translators to JSS.
// The transport part (sequence numbers, ACK, duplicates, large messages)
// is done here; events in face_events.cpp; the services in their files.
#include "jaus/jss_face/face.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "aliases.hpp"
#include "core_translators.hpp"
#include "face_text.hpp"
#include "face_events.hpp"
#include "id_map.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss/large_message.hpp"
#include "jaus/node/duplicate_filter.hpp"
#include "jaus/node/sequence_counters.hpp"
#include "jaus/runtime/repeat_limiter.hpp"

namespace jaus::jss_face {

namespace {

// What the duplicate filter needs of a JSS packet: its contents (ID and body)
// and data flag make it this message.
node::PacketIdentity identity_of(const jss::JudpPacket& packet) {
  const jss::JudpHeader& h = packet.header;
  node::PacketIdentity identity;
  identity.source = h.source.packed();
  identity.destination = h.destination.packed();
  identity.sequence = h.sequence;
  identity.ack_requested = h.ack_nak == jss::JudpAckNak::ack_requested;
  identity.piece = h.data_flag != jss::JudpDataFlag::single;
  identity.stop = !identity.piece && packet.contents.size() >= 2 &&
                  node::DuplicateFilter::always_delivered(jss::message_id_of(packet.contents));
  const std::uint8_t flag[1] = {static_cast<std::uint8_t>(h.data_flag)};  // a packet is not a whole message
  if (identity.ack_requested && !identity.stop)
    identity.fingerprint = node::fingerprint_of(packet.contents, node::fingerprint_of(flag));
  identity.size = packet.contents.size();
  return identity;
}

constexpr std::uint16_t kSetEmergency = 0x0006;
// A client not heard from for this long, whose alias holds no state in the
// node, is forgotten (its events end): a bound in time beside the slot bound.
constexpr rt::Duration kForgetSilentClientsAfter = std::chrono::minutes(5);
constexpr rt::Duration kHousekeepingPeriod = std::chrono::seconds(30);

std::string hex16(std::uint16_t v) { return hex_id(v); }

}  // namespace

struct JssFace::Impl final : FacePort, EventEngine::Host {
  Impl(FaceConfig cfg, const std::vector<TranslatorFactory>& services, node::Node& n, DatagramSender sender,
       rt::LogFn log_fn)
      : config_(std::move(cfg)),
        node_(n),
        env_(n.environment()),
        send_(std::move(sender)),
        log_(log_fn ? std::move(log_fn) : rt::silent_log()),
        ids_(config_, n),
        aliases_(config_.client_alias_subsystem, config_.max_clients),
        events_(config_, env_.clock, env_.scheduler, *this, log_),
        lines_(env_.clock, env_.scheduler,
               [this](rt::LogLevel level, const std::string& text) { log(level, text); }) {
    // The core services first, then the kinds' in the order given.
    for (auto& t : core_translators(config_)) translators_.push_back(std::move(t));
    for (TranslatorFactory make : services)
      if (make != nullptr)
        for (auto& t : make(config_)) translators_.push_back(std::move(t));
    schedule_housekeeping();
  }

  ~Impl() override {
    if (housekeeping_ != rt::kNoTimer) env_.scheduler.cancel(housekeeping_);
  }

  // ---- from the network ------------------------------------------------------

  void receive(std::span<const std::uint8_t> datagram, rt::SenderStanding standing) {
    auto packets = jss::decode_judp_datagram(datagram);
    if (!packets) {
      ++counters_.datagrams_received;
      return malformed("AS5669A datagram", packets.error().message());
    }
    receive_packets(*packets, standing);
  }

  void receive_packets(std::span<const jss::JudpPacket> packets, rt::SenderStanding standing) {
    ++counters_.datagrams_received;
    for (const auto& packet : packets) handle_packet(packet, standing);
  }

  void handle_packet(const jss::JudpPacket& packet, rt::SenderStanding standing) {
    const jss::JudpHeader& h = packet.header;
    if (!h.source.is_valid() || h.source.is_broadcast())
      return malformed("AS5669A message", "source ID " + h.source.to_string() + " is not one sender's");
    // An ACK (or NAK) answers a message of ours; the face asks for none (the
    // transport's endpoint challenge is the transport's).
    if (h.ack_nak == jss::JudpAckNak::ack || h.ack_nak == jss::JudpAckNak::nak) return;
    const auto reached = ids_.reached_by(h.destination);
    if (reached.empty()) {
      ++counters_.not_for_us;
      return;
    }
    const rt::TimePoint now = env_.clock.now();
    const bool single = h.data_flag == jss::JudpDataFlag::single;
    if (single && packet.contents.size() < 2)
      return malformed("AS5669A message from " + h.source.to_string(),
                       std::to_string(packet.contents.size()) + " bytes of contents: no message ID");
    // A copy is answered (ACK) but not acted on again; a stop always acts
    // (the filter never takes one for a copy: node/duplicate_filter.hpp).
    const node::DuplicateVerdict verdict = duplicates_.check(identity_of(packet), now);
    if (verdict == node::DuplicateVerdict::new_session) {
      ++counters_.new_sessions;
      lines_.write({"JSS clients restarted", rt::kNoteworthyBurst}, rt::LogLevel::info, [&] {
        return describe_client(h.source) + " restarted (sequence number " + std::to_string(h.sequence) +
               " to " + h.destination.to_string() + " begins a new session): its earlier messages forgotten";
      });
    }
    if (node::is_dropped(verdict)) {
      ++counters_.duplicates;
      lines_.write("JSS copies not acted on", rt::LogLevel::debug, [&] {
        return "JSS message " + hex16(single ? jss::message_id_of(packet.contents) : 0) + " from " +
               describe_client(h.source) + " to " + h.destination.to_string() + ", sequence number " +
               std::to_string(h.sequence) + ": a copy of one delivered" +
               (verdict == node::DuplicateVerdict::late_copy ? ", since followed by a stop" : "") +
               "; acknowledged, not acted on";
      });
    } else if (single) {
      deliver(h, packet.contents, standing, reached);
    } else {
      assemble(packet, now, standing, reached);
    }
    if (h.ack_nak == jss::JudpAckNak::ack_requested && !h.destination.is_broadcast()) send_ack(h);
  }

  // A piece of a large message, in any order (the one assembler: jaus/core/large_message_assembler.hpp).
  void assemble(const jss::JudpPacket& packet, rt::TimePoint now, rt::SenderStanding standing,
                const std::vector<OurComponent>& reached) {
    for (const auto& discarded : assembler_.expire(now))
      lines_.write("large JSS messages discarded", rt::LogLevel::warn, [&] {
        return "large message from " + discarded.key.source.to_string() + " to " +
               discarded.key.destination.to_string() + " discarded: " + std::string(to_string(discarded.reason));
      });
    const jss::JudpHeader& h = packet.header;
    auto assembled = assembler_.feed(h, packet.contents, now, rt::doubt_of(standing));
    if (assembled.issue == AssemblyIssue::duplicate) {
      ++counters_.duplicates;  // a piece held already, or of a message delivered: harmless
      lines_.write("JSS copies not acted on", rt::LogLevel::debug, [&] {
        return "large message packet from " + describe_client(h.source) + " to " + h.destination.to_string() +
               ", sequence number " + std::to_string(h.sequence) + ": a copy of one held or delivered; not taken again";
      });
    } else if (assembled.status == AssemblyStatus::dropped) {
      malformed("large message packet from " + h.source.to_string(),
                std::string(to_string(assembled.issue)) + " (sequence number " + std::to_string(h.sequence) + ")");
    } else if (assembled.status == AssemblyStatus::complete) {
      ++counters_.large_messages_received;
      // As trusted as its least trusted piece, whichever completed it.
      deliver(assembled.message->header, assembled.message->payload, rt::standing_of_doubt(assembled.message->doubt),
              reached);
    }
  }

  void deliver(const jss::JudpHeader& h, std::span<const std::uint8_t> contents, rt::SenderStanding standing,
               const std::vector<OurComponent>& reached) {
    aliases_.heard(h.source, env_.clock.now());
    const std::uint16_t id = jss::message_id_of(contents);
    inbound_priority_ = jss::ra_priority_from_jss(h.priority);
    std::size_t taken = 0;
    for (const OurComponent& ours : reached) {
      const JssInbound inbound{ours.jss,  ours.ra, ReplyTo{h.source, std::nullopt}, id, contents.subspan(2),
                               standing, static_cast<std::uint8_t>(h.priority)};
      if (dispatch(inbound)) ++taken;
    }
    inbound_priority_ = priority::kDefault;
    if (taken > 0) return;
    ++counters_.unsupported;
    lines_.write("JSS messages no service handles", rt::LogLevel::debug, [&] {
      return "JSS message " + hex16(id) + " from " + h.source.to_string() + " to " + h.destination.to_string() +
             ": no service of the component(s) handles it; ignored";
    });
  }

  bool dispatch(const JssInbound& inbound) {
    if (EventEngine::is_events_message(inbound.message_id)) {
      events_.from_jss(inbound);
      return true;
    }
    for (auto& t : translators_)
      if (t->from_jss(inbound, *this)) return true;
    return false;
  }

  void send_ack(const jss::JudpHeader& h) {
    jss::JudpHeader ack;
    ack.priority = h.priority;
    ack.ack_nak = jss::JudpAckNak::ack;
    ack.destination = h.source;
    ack.source = h.destination;
    ack.sequence = h.sequence;
    const auto datagram = jss::make_judp_datagram(ack, {});
    send_(ack.destination, datagram);
    ++counters_.acks_sent;
  }

  // "JSS client 42.1.1 at 10.0.0.5:3794" (the host when known).
  std::string client_and_host(const jss::JssId& client) const {
    std::string text = "JSS client " + client.to_string();
    if (locate_)
      if (const auto host = locate_(client)) text += " at " + *host;
    return text;
  }

  std::string describe_client(const jss::JssId& client) const override {
    std::string text = client_and_host(client);
    if (const auto slot = aliases_.find(client))
      text += " (alias " + aliases_.alias(*slot, ReplyTo{client, std::nullopt}).to_string() + ")";
    return text;
  }

  void refused(const jss::JssId& client, const std::string& what, const std::string& why) override {
    ++counters_.refused;
    lines_.write("JSS requests refused", rt::LogLevel::info,
                 [&] { return what + " from " + describe_client(client) + " refused: " + why; });
  }

  void malformed(const std::string& what, const std::string& why) override {
    ++counters_.malformed;
    lines_.write("malformed JSS input ignored", rt::LogLevel::warn,
                 [&] { return "malformed " + what + " ignored: " + why; });
  }

  // ---- to the node -------------------------------------------------------------

  std::optional<std::uint8_t> slot_for(const jss::JssId& client) {
    const bool known = aliases_.find(client).has_value();
    const auto assigned = aliases_.assign(client, env_.clock.now(), [this](std::uint8_t slot, const jss::JssId& node) {
      return !node_.holds_state_for(aliases_.alias_subsystem(), slot) && !events_.has_events_of(node);
    });
    if (!assigned) return std::nullopt;
    if (!known) {
      // Components log the alias, the only address they know: this line ties it to the client.
      lines_.write({"JSS clients given an alias", rt::kNoteworthyBurst}, rt::LogLevel::info,
                   [&] { return describe_client(client) + ": new client"; });
    }
    if (assigned->forgotten) forget_client(*assigned->forgotten, "its alias slot went to " + client.to_string());
    return assigned->slot;
  }

  void forget_client(const jss::JssId& client_node, const std::string& why) {
    events_.forget(client_node);
    for (auto& t : translators_) t->forget(client_node);
    lines_.write({"JSS clients forgotten", rt::kNoteworthyBurst}, rt::LogLevel::info,
                 [&] { return "JSS client node " + client_node.to_string() + " forgotten: " + why; });
  }

  void send_ra(const ReplyTo& origin, const Address& ra_component, std::uint16_t ra_code,
               std::span<const std::uint8_t> ra_payload, rt::SenderStanding standing) override {
    if (ra_payload.size() > kMaxPayloadSize) {
      lines_.write("RA messages too large", rt::LogLevel::error, [&] {
        return "RA message " + hex16(ra_code) + " for " + ra_component.to_string() + " is over one packet; not sent";
      });
      return;
    }
    Header header;
    header.command_code = ra_code;
    header.destination = ra_component;
    header.data_size = static_cast<std::uint16_t>(ra_payload.size());
    header.priority = inbound_priority_;
    if (ra_code == kSetEmergency) header.priority = std::max(header.priority, priority::kSafetyCritical);
    if (const auto slot = slot_for(origin.client)) {
      header.source = aliases_.alias(*slot, origin);
    } else if (ra_code == kSetEmergency) {
      // No slot free: the stop is obeyed anyway, as from an RA sender the
      // node could not record (a hold only the local clear releases).
      header.source = Address{aliases_.alias_subsystem(), kRefusedClientSlot, origin.client.component, kOwnChannel};
      standing = rt::SenderStanding::unrecorded;
    } else {
      ++counters_.clients_refused;
      lines_.write("JSS clients refused", rt::LogLevel::warn, [&] {
        return describe_client(origin.client) + " refused: all " + std::to_string(aliases_.capacity()) +
               " client slots are held by clients with state (jss.max_clients)";
      });
      return;
    }
    ++counters_.messages_to_ra;
    node_.receive(PacketView{header, ra_payload}, standing);
  }

  // ---- from the node -----------------------------------------------------------

  void from_node(const Header& header, std::span<const std::uint8_t> payload) {
    const auto to = aliases_.client_of(header.destination);
    const auto ours = ids_.jss_id_of(header.source);
    if (!to || !ours || header.data_flag != DataFlag::single) {
      ++counters_.untranslated_from_ra;
      return;
    }
    const RaOutbound outbound{header, payload, *ours, *to};
    for (auto& t : translators_)
      if (t->from_ra(outbound, *this)) return;
    ++counters_.untranslated_from_ra;
    lines_.write("RA messages to JSS clients not translated", rt::LogLevel::debug, [&] {
      return "RA message " + hex16(header.command_code) + " from " + header.source.to_string() + " to JSS client " +
             to->client.to_string() + ": no JSS translation; dropped";
    });
  }

  // ---- to the network ----------------------------------------------------------

  void reply(const ReplyTo& to, const jss::JssId& our_component, std::span<const std::uint8_t> contents) override {
    if (to.event_id) return events_.on_report(to, our_component, contents);
    send_contents(to.client, our_component, contents);
  }

  void send_contents(const jss::JssId& to, const jss::JssId& from, std::span<const std::uint8_t> contents) override {
    jss::JudpHeader h;
    h.priority = jss::JudpPriority::normal;
    if (to.is_broadcast())
      h.broadcast = to.subsystem == jss::JssId::kAllSubsystems ? jss::JudpBroadcast::global : jss::JudpBroadcast::local;
    h.destination = to;
    h.source = from;
    if (contents.size() > config_.max_packet_contents) {
      if (to.is_broadcast()) {
        lines_.write("large JSS broadcasts not sent", rt::LogLevel::error, [&] {
          return "JSS message " + hex16(jss::message_id_of(contents)) + " of " + std::to_string(contents.size()) +
                 " bytes to " + to.to_string() + " not sent: broadcasts are never split";
        });
        return;
      }
      const auto pieces = jss::split_contents(contents, std::max<std::size_t>(config_.max_packet_contents, 2));
      if (!pieces) return;  // (only for a limit below 2, made 2 above)
      std::uint16_t sequence = sequences_.take(to, static_cast<std::uint16_t>(pieces->size()));
      for (const jss::ContentsPiece& piece : *pieces) {
        h.data_flag = piece.data_flag;
        h.sequence = sequence++;
        send_(to, jss::make_judp_datagram(h, piece.bytes));
      }
      ++counters_.large_messages_sent;
    } else {
      h.sequence = sequences_.take(to);
      send_(to, jss::make_judp_datagram(h, contents));
    }
    ++counters_.messages_to_jss;
  }

  // ---- EventEngine::Host ---------------------------------------------------------

  void ask(const JssInbound& query) override {
    if (!dispatch(query)) ++counters_.unsupported;
  }
  bool answers(std::uint16_t query_id, std::uint8_t ra_component_id) const override {
    return std::any_of(translators_.begin(), translators_.end(),
                       [&](const auto& t) { return t->handles(query_id, ra_component_id); });
  }

  // ---- FacePort ------------------------------------------------------------------

  std::optional<jss::JssId> jss_id_of(const Address& ra_component) const override {
    return ids_.jss_id_of(ra_component);
  }
  jss::JssId jss_id_for(const Address& ra_address) const override {
    if (const auto client = aliases_.client_of(ra_address)) return client->client;
    if (const auto ours = ids_.jss_id_of(ra_address)) return *ours;
    return jss::JssId{ra_address.subsystem, ra_address.node, ra_address.component};
  }
  const FaceConfig& config() const override { return config_; }
  rt::Clock& clock() override { return env_.clock; }
  rt::Scheduler& scheduler() override { return env_.scheduler; }
  node::Node& node() override { return node_; }
  void log(rt::LogLevel level, const std::string& text) override { log_(level, "jss: " + text); }
  std::vector<ServiceUri> services_of(std::uint8_t ra_component_id) const override {
    std::vector<ServiceUri> services;
    for (const auto& t : translators_)
      for (auto& service : t->services(ra_component_id))
        if (std::find(services.begin(), services.end(), service) == services.end()) services.push_back(std::move(service));
    return services;
  }

  // ---- housekeeping --------------------------------------------------------------

  void schedule_housekeeping() {
    housekeeping_ = env_.scheduler.call_at(env_.clock.now() + kHousekeepingPeriod, [this] {
      housekeeping_ = rt::kNoTimer;
      forget_silent_clients();
      schedule_housekeeping();
    });
  }

  void forget_silent_clients() {
    const rt::TimePoint now = env_.clock.now();
    std::vector<std::pair<std::uint8_t, jss::JssId>> silent;
    aliases_.for_each([&](std::uint8_t slot, const jss::JssId& client, rt::TimePoint last_heard) {
      if (now - last_heard >= kForgetSilentClientsAfter && !node_.holds_state_for(aliases_.alias_subsystem(), slot))
        silent.emplace_back(slot, client);
    });
    for (const auto& [slot, client] : silent) {
      aliases_.release(slot);
      forget_client(client, "silent for 5 minutes");
    }
  }

  FaceConfig config_;
  node::Node& node_;
  rt::Environment env_;
  DatagramSender send_;
  rt::LogFn log_;
  FaceCounters counters_;
  IdMap ids_;
  AliasTable aliases_;
  Translators translators_;
  EventEngine events_;
  jss::JssLargeMessageAssembler assembler_;
  // Per destination; the bound as the RA node's (a destination least
  // recently sent to starts again at 0 when used again).
  node::BasicSequenceCounters<jss::JssId> sequences_{{.max_streams = 4096}};
  // The node's filter with JSS's window (Jr's own, 3 s) and its large
  // messages' packets filtered too (AS5669A retransmits them one by one).
  node::DuplicateFilter duplicates_{{.window = std::chrono::seconds(3), .max_entries = 4096, .pieces_filtered = true}};
  rt::RepeatedLines lines_;
  std::uint8_t inbound_priority_ = priority::kDefault;  // RA priority of the JSS message being handled
  rt::TimerId housekeeping_ = rt::kNoTimer;
  JssFace::ClientLocator locate_;
};

JssFace::JssFace(FaceConfig config, const std::vector<TranslatorFactory>& services, node::Node& node,
                 DatagramSender send, rt::LogFn log)
    : impl_(std::make_unique<Impl>(std::move(config), services, node, std::move(send), std::move(log))) {}
JssFace::~JssFace() = default;

void JssFace::receive(std::span<const std::uint8_t> datagram, rt::SenderStanding standing) {
  impl_->receive(datagram, standing);
}
void JssFace::receive_packets(std::span<const jss::JudpPacket> packets, rt::SenderStanding standing) {
  impl_->receive_packets(packets, standing);
}
namespace {
// Reads "a.b.c" (three numbers 0-255, each after a dot) at `at`; the end, or npos.
std::size_t read_three_numbers(const std::string& text, std::size_t at, std::array<std::uint8_t, 3>& numbers) {
  for (std::size_t i = 0; i < 3; ++i) {
    if (i > 0) {
      if (at >= text.size() || text[at] != '.') return std::string::npos;
      ++at;
    }
    unsigned value = 0;
    std::size_t digits = 0;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9' && digits < 4) {
      value = value * 10 + static_cast<unsigned>(text[at] - '0');
      ++at;
      ++digits;
    }
    if (digits == 0 || value > 255) return std::string::npos;
    numbers[i] = static_cast<std::uint8_t>(value);
  }
  return at;
}
bool continues_a_number(char c) { return (c >= '0' && c <= '9') || c == '.' || c == ':'; }
}  // namespace

std::string JssFace::name_clients_in(const std::string& line) const {
  const std::string prefix = std::to_string(impl_->aliases_.alias_subsystem()) + ".";
  std::string out;
  std::size_t from = 0;
  for (std::size_t at = line.find(prefix); at != std::string::npos; at = line.find(prefix, at + 1)) {
    if (at < from || (at > 0 && continues_a_number(line[at - 1]))) continue;
    std::array<std::uint8_t, 3> numbers{};
    const std::size_t end = read_three_numbers(line, at + prefix.size(), numbers);
    // An address alone (not an IP address's "a.b.c.d:port", not part of a longer number).
    if (end == std::string::npos || (end < line.size() && continues_a_number(line[end]))) continue;
    const auto client = impl_->aliases_.client_of(
        Address{impl_->aliases_.alias_subsystem(), numbers[0], numbers[1], numbers[2]});
    if (!client) continue;
    out.append(line, from, end - from);
    out += " (" + impl_->client_and_host(client->client) + ")";
    from = end;
  }
  if (from == 0) return line;
  out.append(line, from, std::string::npos);
  return out;
}

void JssFace::locate_clients_with(ClientLocator locator) { impl_->locate_ = std::move(locator); }
bool JssFace::owns(const Address& ra_destination) const { return impl_->aliases_.is_alias(ra_destination); }
void JssFace::from_node(const Header& header, std::span<const std::uint8_t> payload) {
  impl_->from_node(header, payload);
}
bool JssFace::holds_state_for(std::uint16_t subsystem, std::uint8_t node) const {
  const jss::JssId client_node{subsystem, node, jss::JssId::kAll};
  // Events need no slot (a heartbeat's are answered by the face alone).
  if (impl_->events_.has_events_of(client_node)) return true;
  const auto slot = impl_->aliases_.find(client_node);
  return slot && impl_->node_.holds_state_for(impl_->aliases_.alias_subsystem(), *slot);
}
std::optional<jss::JssId> JssFace::client_of_alias(const Address& alias) const {
  const auto client = impl_->aliases_.client_of(alias);
  if (!client) return std::nullopt;
  return client->client;
}
bool JssFace::reserve_client(std::uint8_t slot, const jss::JssId& client_node) {
  return impl_->aliases_.reserve(slot, client_node, impl_->env_.clock.now());
}
std::optional<jss::JssId> JssFace::jss_id_of(const Address& ra_component) const {
  return impl_->ids_.jss_id_of(ra_component);
}
const FaceConfig& JssFace::config() const { return impl_->config_; }
const FaceCounters& JssFace::counters() const { return impl_->counters_; }
const AssemblyCounters& JssFace::large_message_counters() const { return impl_->assembler_.counters(); }

}  // namespace jaus::jss_face
