#include "jaus/ocu/wildcard_command.hpp"

#include <algorithm>

#include "jaus/core/stop_commands.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;

constexpr std::uint8_t kAny = jaus::Address::kBroadcast;
constexpr std::uint8_t kNodeManager = 1;

bool is_real_id(std::uint8_t v) { return v != 0 && v != kAny; }

}  // namespace

bool is_stop(std::uint16_t command_code) { return is_stop_command(command_code); }

std::vector<jaus::Address> WildcardResult::confirmed() const {
  std::vector<jaus::Address> out;
  for (const auto& m : members)
    if (m.outcome == Arrival::acknowledged) out.push_back(m.address);
  return out;
}

std::vector<jaus::Address> WildcardResult::unconfirmed() const {
  std::vector<jaus::Address> out;
  for (const auto& m : members)
    if (m.outcome != Arrival::acknowledged) out.push_back(m.address);
  return out;
}

WildcardCommand::WildcardCommand(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                 std::vector<std::uint8_t> payload, WildcardPolicy policy, Done done)
    : session_(session),
      to_(to),
      header_(header),
      payload_(std::move(payload)),
      policy_(policy),
      done_(std::move(done)),
      stop_(is_stop(header.command_code)) {
  policy_.repeat_every = std::max<jaus::rt::Duration>(policy_.repeat_every, 1ms);
  policy_.ask_every = std::max<jaus::rt::Duration>(policy_.ask_every, policy_.repeat_every);
}

WildcardCommand::~WildcardCommand() {
  session_.scheduler().cancel(timer_);
  if (listener_) session_.unlisten(listener_);
  if (watcher_) session_.unlisten(watcher_);
}

jaus::Header WildcardCommand::header_to(const jaus::Address& to) const {
  jaus::Header h = header_;
  h.destination = to;
  h.source = session_.self();
  h.ack_nak = jaus::AckNak::none;
  h.data_size = static_cast<std::uint16_t>(std::min(payload_.size(), std::size_t{0xFFFF}));
  return h;
}

bool WildcardCommand::in_scope(std::uint8_t subsystem, std::uint8_t node) const {
  const jaus::Address& self = session_.self();
  if (subsystem == self.subsystem && node == self.node) return false;  // the OCU's own node
  return (to_.subsystem == kAny || to_.subsystem == subsystem) && (to_.node == kAny || to_.node == node);
}

void WildcardCommand::start() {
  if (started_) return;
  started_ = true;
  started_at_ = session_.clock().now();
  last_news_ = started_at_;
  listener_ = session_.listen([this](const Received& r) { received(r); });
  watcher_ = session_.watch([this](const jaus::Header& h) { heard(h.source); });
  // Safety first: the stop goes out before anything is asked (a vehicle that
  // gets it stops now; finding out who did comes after).
  if (stop_) send_broadcast();
  ask_subsystems();
  tick();
}

void WildcardCommand::send_broadcast() {
  session_.send_raw(header_to(to_), payload_);
  ++result_.broadcasts;
}

void WildcardCommand::ask_subsystems() {
  next_ask_ = session_.clock().now() + policy_.ask_every;
  // Every node manager the address names says what its subsystem hosts.
  session_.send(jaus::Address{to_.subsystem, to_.node, kNodeManager, 1},
                jaus::msg::QueryConfiguration{{jaus::msg::identification::kSubsystem}});
  // Nodes heard but not described yet are asked themselves (a node manager may know only its own node).
  for (const auto& [node, described] : nodes_)
    if (!described)
      session_.send(jaus::Address{node.subsystem, node.node, kNodeManager, 1},
                    jaus::msg::QueryConfiguration{{jaus::msg::identification::kNode}});
}

void WildcardCommand::tick() {
  timer_ = jaus::rt::kNoTimer;
  if (finished_) return;
  if (session_.interrupted()) return finish(true);
  const auto now = session_.clock().now();
  if (now - started_at_ >= policy_.look_for) return finish(false);
  check_finished();
  if (finished_) return;
  // Again until finished: a vehicle that starts (or whose link comes back)
  // while this runs is stopped by the next copy.
  if (stop_ && now - started_at_ > 0s) send_broadcast();
  if (now >= next_ask_) ask_subsystems();
  timer_ = session_.scheduler().call_at(std::min(now + policy_.repeat_every, started_at_ + policy_.look_for),
                                        [this] { tick(); });
}

void WildcardCommand::heard(const jaus::Address& source) {
  if (finished_ || !is_real_id(source.subsystem) || !is_real_id(source.node)) return;
  if (!in_scope(source.subsystem, source.node)) return;
  const NodeKey key{source.subsystem, source.node};
  if (!nodes_.try_emplace(key, false).second) return;
  last_news_ = session_.clock().now();
  session_.send(jaus::Address{key.subsystem, key.node, kNodeManager, 1},
                jaus::msg::QueryConfiguration{{jaus::msg::identification::kNode}});
}

void WildcardCommand::received(const Received& message) {
  if (finished_ || message.header.command_code != jaus::msg::ReportConfiguration::code) return;
  const auto& from = message.header.source;
  if (!is_real_id(from.subsystem) || !is_real_id(from.node)) return;
  jaus::msg::ReportConfiguration report{};
  if (!jaus::wire::decode_payload_into(message.payload, report, session_.options().dialect, jaus::kHeaderSize)) return;
  if (in_scope(from.subsystem, from.node)) nodes_[NodeKey{from.subsystem, from.node}] = true;
  for (const auto& node : report.nodes) {
    if (!is_real_id(node.node_id) || !in_scope(from.subsystem, node.node_id)) continue;
    // A node listed by another's node manager: asked itself until it answers.
    if (nodes_.try_emplace(NodeKey{from.subsystem, node.node_id}, false).second) last_news_ = session_.clock().now();
    for (const auto& c : node.components) {
      const jaus::Address member{from.subsystem, node.node_id, c.component_id, c.instance};
      if (is_real_id(c.component_id) && is_real_id(c.instance) && to_.matches(member)) add_member(member);
    }
  }
  check_finished();
}

void WildcardCommand::add_member(const jaus::Address& member) {
  if (!members_.insert(member).second) return;
  last_news_ = session_.clock().now();
  // Its own copy, ACK requested: the ACK is the member's confirmation (the
  // node ACKs once the component has acted on it).
  std::weak_ptr<Answers> answers = answers_;
  const MustArrivePolicy policy = policy_.per_member.value_or(MustArrivePolicy::command(session_.options().must_arrive));
  session_.node().send_acknowledged(
      header_to(member), payload_, policy, [answers, member](const jaus::node::AckResolution& resolution) {
        const auto alive = answers.lock();
        if (!alive) return;  // the command is gone
        const Arrival outcome = resolution.outcome == jaus::node::AckOutcome::acknowledged ? Arrival::acknowledged
                                : resolution.outcome == jaus::node::AckOutcome::refused    ? Arrival::refused
                                                                                         : Arrival::unacknowledged;
        alive->by_member[member] = {outcome, resolution.transmissions};
      });
}

void WildcardCommand::check_finished() {
  if (finished_ || members_.empty()) return;
  for (const auto& [node, described] : nodes_)
    if (!described) return;
  for (const auto& member : members_)
    if (!answers_->by_member.contains(member)) return;
  if (session_.clock().now() - last_news_ < policy_.settle) return;
  finish(false);
}

void WildcardCommand::finish(bool interrupted) {
  if (finished_) return;
  finished_ = true;
  session_.scheduler().cancel(timer_);
  timer_ = jaus::rt::kNoTimer;
  result_.interrupted = interrupted;
  result_.elapsed = session_.clock().now() - started_at_;
  result_.members.clear();
  for (const auto& member : members_) {
    WildcardMember m{member, std::nullopt, 0};
    if (const auto it = answers_->by_member.find(member); it != answers_->by_member.end()) {
      m.outcome = it->second.first;
      m.transmissions = it->second.second;
    } else {
      m.outcome = interrupted ? Arrival::interrupted : Arrival::unacknowledged;
    }
    result_.members.push_back(m);
  }
  if (done_) done_(result_);
}

WildcardResult send_to_every_member(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                    std::span<const std::uint8_t> payload, WildcardPolicy policy) {
  WildcardCommand command(session, to, header, {payload.begin(), payload.end()}, policy);
  command.start();
  // The command ends itself at look_for; the margin only bounds a clock that never fires.
  session.run_until([&] { return command.finished() || session.interrupted(); }, policy.look_for + 1s);
  if (!command.finished()) command.stop();  // interrupted (or the backstop)
  return command.result();
}

}  // namespace jaus::ocu
