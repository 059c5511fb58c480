#include "model_node.hpp"

#include <stdexcept>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::model {

using namespace std::chrono_literals;

Address address_of(Party p) {
  switch (p) {
    case Party::a: return Address{2, 1, 40, 1};
    case Party::b: return Address{3, 1, 40, 1};
    case Party::c: return Address{4, 1, 40, 1};
    case Party::j: break;
  }
  return Address{};
}

namespace {

constexpr std::uint8_t kJssAliasSubsystem = 250;  // the face's RA aliases for JSS clients

host::HostConfig node_config(const std::filesystem::path& state_directory) {
  host::HostConfig c;
  c.settings.identity.subsystem_name = "model";
  c.settings.identity.node_name = "vehicle";
  c.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                  host::ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}},
                  host::ComponentSpec{"local_vector_driver", 44, 1, 1, "", {}, 0, {}}};
  host::ClearpathSettings p;
  p.sim.vehicle.drive = clearpath::sim::Drive::differential;
  p.vehicle.drive = bridge::DriveMode::differential_output;
  p.vehicle.emergency_flags = 0x08;  // the Husky's: shared with its e-stop
  c.platform = host::clearpath_sim_platform_settings(p);
  c.emergency.state_directory = state_directory.string();
  c.jss.enabled = true;
  return c;
}

PdState pd_state_of(rt::PrimaryStatus s) {
  switch (s) {
    case rt::PrimaryStatus::initialize: return PdState::initialize;
    case rt::PrimaryStatus::ready: return PdState::ready;
    case rt::PrimaryStatus::standby: return PdState::standby;
    case rt::PrimaryStatus::emergency: return PdState::emergency;
    case rt::PrimaryStatus::failure: return PdState::failure;
    case rt::PrimaryStatus::shutdown: return PdState::shutdown;
  }
  return PdState::failure;
}

}  // namespace

ModelNode::ModelNode(std::filesystem::path state_directory)
    : state_directory_(std::move(state_directory)),
      epoch_(time_.now()),
      network_(time_, time_),
      host_link_(network_.attach(1, 1)) {
  for (const Party p : {Party::a, Party::b, Party::c}) {
    const Address a = address_of(p);
    operator_links_.push_back(&network_.attach(a.subsystem, a.node));
  }
  attach();
}

ModelNode::~ModelNode() { detach(); }

void ModelNode::attach() {
  auto attached = host::NodeHost::attach(node_config(state_directory_), host_link_, time_, time_,
                                         [this](rt::LogLevel, const std::string& line) {
                                           log_.push_back(line);
                                           if (log_.size() > 400) log_.erase(log_.begin(), log_.begin() + 200);
                                         });
  if (!attached) throw std::runtime_error("the node does not start: " + attached.error().message());
  host_ = std::move(*attached);
  host_link_.deliver_to(host_->node());
  auto* platform = host_->platform_as<host::ClearpathPlatform>();
  auto* loopback = platform ? dynamic_cast<clearpath::sim::LoopbackClient*>(platform->client()) : nullptr;
  if (!loopback) throw std::runtime_error("no simulated Clearpath platform");
  left_ = right_ = 0;
  // Every motion command jausd writes to the platform, as written.
  loopback->on_written([this](std::span<const std::uint8_t> bytes) {
    const auto frame = clearpath::decode_frame(bytes);
    if (!frame) return;
    const auto envelope = clearpath::decode(*frame, clearpath::Direction::to_platform);
    if (!envelope) return;
    if (const auto* m = envelope->message.get_if<clearpath::SetDifferentialOutput>()) {
      left_ = m->left;
      right_ = m->right;
    }
  });
  // The hardware still holds what was pressed while jausd was away.
  if (estop_) loopback->platform().press(clearpath::sim::HardwareInput::estop, true, time_.now());
  if (pause_) loopback->platform().press(clearpath::sim::HardwareInput::pause, true, time_.now());
}

void ModelNode::detach() {
  if (!host_) return;
  host_->stop("model: restart");
  host_link_.on_receive({});
  host_.reset();
}

Ms ModelNode::now() const {
  return std::chrono::duration_cast<std::chrono::milliseconds>(time_.now() - epoch_).count();
}

void ModelNode::run_for(Ms ms) { time_.advance(std::chrono::milliseconds(ms)); }

void ModelNode::wait_started(Ms limit) {
  for (Ms waited = 0; waited < limit; waited += 10) {
    if (pd_state() != PdState::initialize && vector_state() != PdState::initialize) return;
    run_for(10);
  }
}

template <class M>
bool ModelNode::send_ra(Party p, const Address& to, const M& message) {
  if (!link_up(p)) return false;
  if (p == Party::j) throw std::logic_error("J speaks JSS");
  Header header;
  header.source = address_of(p);
  header.destination = to;
  std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
  const auto size = wire::encode_message(header, message, packet);
  if (!size) throw std::runtime_error("does not encode: " + size.error().message());
  packet.resize(*size);
  header.command_code = M::code;
  header.data_size = static_cast<std::uint16_t>(*size - kHeaderSize);
  const int link = p == Party::a ? 0 : p == Party::b ? 1 : 2;
  operator_links_[static_cast<std::size_t>(link)]->transmit(header, packet);
  return true;
}

template <class M>
bool ModelNode::send_jss(const jss::JssId& to, const M& message) {
  if (!link_up(Party::j)) return false;
  jss::JudpHeader h;
  h.source = kJssClient;
  h.destination = to;
  h.sequence = jss_sequence_++;
  host_->jss_face()->receive(jss::make_judp_datagram(h, jss::encode_contents(message)), rt::SenderStanding::trusted);
  return true;
}

bool ModelNode::request_control(Party p, std::uint8_t authority) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::RequestControl{{authority}});
  return send_ra(p, kPrimitiveDriver, msg::RequestComponentControl{{authority}});
}

bool ModelNode::release_control(Party p) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::ReleaseControl{});
  return send_ra(p, kPrimitiveDriver, msg::ReleaseComponentControl{});
}

bool ModelNode::effort(Party p, double percent) {
  if (p == Party::j) {
    jss::msg::SetWrenchEffort m{};
    m.propulsive_linear_effort_x_percent = percent;
    m.propulsive_rotational_effort_z_percent = 0;
    return send_jss(kJssPrimitiveDriver, m);
  }
  msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = percent;
  m.propulsive_rotational_effort_z_percent = 0;
  return send_ra(p, kPrimitiveDriver, m);
}

bool ModelNode::set_emergency(Party p, Target to) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::SetEmergency{});
  return send_ra(p, to == Target::primitive_driver ? kPrimitiveDriver : kVectorDriver, msg::SetEmergency{});
}

bool ModelNode::clear_emergency(Party p, Target to) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::ClearEmergency{});
  return send_ra(p, to == Target::primitive_driver ? kPrimitiveDriver : kVectorDriver, msg::ClearEmergency{});
}

bool ModelNode::standby(Party p) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::Standby{});
  return send_ra(p, kPrimitiveDriver, msg::Standby{});
}

bool ModelNode::resume(Party p) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::Resume{});
  return send_ra(p, kPrimitiveDriver, msg::Resume{});
}

bool ModelNode::set_authority(Party p, std::uint8_t authority) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::SetAuthority{{authority}});
  return send_ra(p, kPrimitiveDriver, msg::SetComponentAuthority{{authority}});
}

bool ModelNode::shutdown(Party p) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::Shutdown{});
  return send_ra(p, kPrimitiveDriver, msg::Shutdown{});
}

bool ModelNode::reset(Party p) {
  if (p == Party::j) return send_jss(kJssPrimitiveDriver, jss::msg::Reset{});
  return send_ra(p, kPrimitiveDriver, msg::Reset{});
}

bool ModelNode::query_vector_driver(Party p) { return send_ra(p, kVectorDriver, msg::QueryComponentStatus{}); }
bool ModelNode::take_vector(Party p) { return send_ra(p, kVectorDriver, msg::RequestComponentControl{{5}}); }
bool ModelNode::release_vector(Party p) { return send_ra(p, kVectorDriver, msg::ReleaseComponentControl{}); }
bool ModelNode::drive_vector(Party p, double speed_mps) {
  msg::SetLocalVector m;
  m.speed_mps = speed_mps;
  m.heading_rad = 0.5;
  return send_ra(p, kVectorDriver, m);
}

void ModelNode::press(bool estop, bool on) {
  (estop ? estop_ : pause_) = on;
  auto* platform = host_->platform_as<host::ClearpathPlatform>();
  auto* loopback = dynamic_cast<clearpath::sim::LoopbackClient*>(platform->client());
  loopback->platform().press(estop ? clearpath::sim::HardwareInput::estop : clearpath::sim::HardwareInput::pause, on,
                             time_.now());
}

void ModelNode::restart() {
  detach();
  attach();
}

void ModelNode::local_clear() { host_->clear_emergency_holds_locally("model: local clear"); }

std::optional<Party> ModelNode::party_of(const Address& a) const {
  if (a.subsystem == kJssAliasSubsystem) return Party::j;
  for (const Party p : {Party::a, Party::b, Party::c})
    if (a == address_of(p)) return p;
  return std::nullopt;
}

// A component shut down by its controller leaves the node (it is destroyed): Shutdown.
PdState ModelNode::pd_state() {
  const rt::Component* pd = host_->node().find(kPrimitiveDriver);
  return pd ? pd_state_of(pd->state()) : PdState::shutdown;
}
PdState ModelNode::vector_state() {
  const rt::Component* vd = host_->node().find(kVectorDriver);
  return vd ? pd_state_of(vd->state()) : PdState::shutdown;
}

Observation ModelNode::observe() {
  Observation o;
  o.left = left_;
  o.right = right_;
  const rt::Component* pd = host_->node().find(kPrimitiveDriver);
  o.state = pd_state();
  if (!pd) {
    o.controller = Ctl::none;
  } else if (const auto& c = pd->control().controller(); !c) {
    o.controller = Ctl::none;
  } else if (c->address == kVectorDriver) {
    o.controller = Ctl::driver;
  } else if (const auto p = party_of(c->address)) {
    o.controller = ctl_of(*p);
  } else {
    o.unknown += "controller " + c->address.to_string() + "; ";
  }
  if (const rt::Component* vd = host_->node().find(kVectorDriver)) {
    const auto& vc = vd->control().controller();
    o.c_controls_vector = vc && vc->address == address_of(Party::c);
    if (vc && !o.c_controls_vector) o.unknown += "vector driver's controller " + vc->address.to_string() + "; ";
  }
  const rt::EmergencyLatch* latch = host_->emergency_latch("vehicle");
  std::set<Party> holders;
  bool known = latch != nullptr;
  if (latch) {
    for (const Address& a : latch->holders()) {
      if (const auto p = party_of(a)) holders.insert(*p);
      else {
        known = false;
        o.unknown += "holder " + a.to_string() + "; ";
      }
    }
    if (latch->overflowed()) {
      known = false;
      o.unknown += "overflowed latch; ";
    }
  }
  if (known) o.holders = holders;
  return o;
}

}  // namespace jaus::model
