#include "jaus/components/communicator.hpp"

namespace jaus::components {

using namespace rt;

namespace {
constexpr std::uint8_t kNodeManagerComponent = 1;
}  // namespace

Communicator::Communicator(ComponentConfig config, Environment env, CommunicatorConfig options)
    : Component(std::move(config), std::move(env)), heartbeat_period_(options.heartbeat_period) {
  for (std::uint8_t id = 0; id < options.link_count; ++id) links_[id] = data_link::kOn;
  using namespace msg;
  handle<SetDataLinkStatus>(Access::controller, false, [this](const Header& h, const SetDataLinkStatus& m) {
    if (m.state > data_link::kStandby) {
      log_repeated("Set Data Link Status with a reserved state ignored", LogLevel::warn, [&] {
        return "Set Data Link Status " + std::to_string(m.state) + " from " + h.source.to_string() +
               " ignored: reserved state";
      });
      return;
    }
    // Part 3's Set Data Link Status carries no link ID: it applies to the selected link.
    set_link_state(selected_, m.state);
  });
  handle<SetDataLinkSelect>(Access::controller, false, [this](const Header& h, const SetDataLinkSelect& m) {
    if (!links_.contains(m.data_link_id)) {
      log_repeated("Set Data Link Select of an unknown link ignored", LogLevel::warn, [&] {
        return "Set Data Link Select " + std::to_string(m.data_link_id) + " from " + h.source.to_string() +
               " ignored: no such link";
      });
      return;
    }
    selected_ = m.data_link_id;
    log_repeated({"data links selected", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "data link " + std::to_string(selected_) + " selected by " + h.source.to_string(); });
  });
  handle<QueryDataLinkStatus>(Access::anyone, false, [this](const Header& h, const QueryDataLinkStatus& m) {
    send(h.source, ReportDataLinkStatus{{m.data_link_id, link_state(m.data_link_id)}});
  });
  handle<QuerySelectedDataLinkStatus>(Access::anyone, false, [this](const Header& h, const QuerySelectedDataLinkStatus&) {
    send(h.source, ReportSelectedDataLinkStatus{{selected_}});
  });
}

Communicator::~Communicator() {
  if (heartbeat_timer_ != kNoTimer) env().scheduler.cancel(heartbeat_timer_);
}

bool Communicator::initialize() {
  // Initialize runs again after a Reset: one heartbeat timer, not two.
  if (heartbeat_timer_ == kNoTimer && heartbeat_period_ > Duration::zero()) heartbeat();
  return true;
}

void Communicator::heartbeat() {
  // To every subsystem's node managers: the link leaves it out of nothing
  // (255 is accepted by every subsystem), unlike this subsystem's own broadcasts.
  send(Address{Address::kBroadcast, Address::kBroadcast, kNodeManagerComponent, 1}, msg::ReportHeartbeatPulse{});
  heartbeat_timer_ = env().scheduler.call_at(env().clock.now() + heartbeat_period_, [this] { heartbeat(); });
}

std::uint8_t Communicator::link_state(std::uint8_t link) const {
  const auto it = links_.find(link);
  return it == links_.end() ? data_link::kOff : it->second;
}

void Communicator::set_link_state(std::uint8_t link, std::uint8_t state) {
  auto& current = links_[link];
  if (current == state) return;
  // The controller's Set Data Link Status: a loop of them is limited.
  log_repeated({"data link states changed", kNoteworthyBurst}, LogLevel::info, [&] {
    return "data link " + std::to_string(link) + " state " + std::to_string(current) + " -> " + std::to_string(state);
  });
  current = state;
}

}  // namespace jaus::components
