#include "jaus/host/node_host.hpp"

#include <algorithm>

#include "jaus/host/jss_translators.hpp"

namespace jaus::host {

namespace {
// How often a failed write of the emergency holds is tried again (besides at every change).
constexpr rt::Duration kPersistRetry = std::chrono::seconds(2);
// How often jausd says what it dropped (only in a period when it dropped anything).
constexpr rt::Duration kDropSummaryPeriod = std::chrono::minutes(1);
}  // namespace

NodeHost::NodeHost(HostConfig config, rt::LogFn log)
    : config_(std::move(config)), log_(log ? std::move(log) : rt::silent_log()) {
  config_.link.subsystem = config_.node.subsystem;
  config_.link.node = config_.node.node;
  if (config_.jss.enabled) {
    // One identity and one controller timeout for both dialects.
    auto& jss = config_.jss;
    const auto& identity = config_.settings.identity;
    jss.subsystem_name = identity.subsystem_name;
    jss.subsystem_type = identity.subsystem_type;
    jss.node_name = identity.node_name;
    const auto timeout_s = std::chrono::ceil<std::chrono::seconds>(config_.settings.defaults.controller_timeout).count();
    jss.controller_timeout_s = static_cast<std::uint8_t>(std::clamp<long long>(timeout_s, 0, 255));
    config_.link.jss_self = jss_node_manager_id();
    // Issue 42: RA datagrams from the alias subsystem are forgeries of JSS clients; the link refuses them.
    config_.link.alias_subsystem = jss.client_alias_subsystem;
  } else {
    config_.link.alias_subsystem = 0;
  }
}

jss::JssId NodeHost::jss_node_manager_id() const {
  const auto& jss = config_.jss;
  const auto mapped = jss.component_ids.find(1);
  return jss::JssId{jss.subsystem.value_or(config_.node.subsystem), config_.node.node,
                    mapped == jss.component_ids.end() ? std::uint8_t{1} : mapped->second};
}

Expected<std::unique_ptr<NodeHost>> NodeHost::open(HostConfig config, boost::asio::io_context& io, rt::LogFn log) {
  std::unique_ptr<NodeHost> h(new NodeHost(std::move(config), std::move(log)));
  h->asio_runtime_ = std::make_unique<transport::AsioRuntime>(io);
  h->clock_ = h->asio_runtime_.get();
  h->scheduler_ = h->asio_runtime_.get();
  auto link = transport::UdpLink::open(io, *h->asio_runtime_, *h->asio_runtime_, h->config_.link, h->log_);
  if (!link) return unexpected(link.error());
  h->udp_link_ = std::move(*link);
  // Reachable from the network and open to everyone on it: the operator
  // should choose that knowingly. A vehicle's posture only: an OCU's node takes no commands.
  const auto& l = h->config_.link;
  if (!h->config_.operator_unit && (l.bind.address >> 24) != 127 && l.allow.empty() && l.control_from.empty())
    h->log_(rt::LogLevel::warn, "listening on " + transport::to_string(l.bind) +
                                    " with an empty allow-list and control_from: any host on the network may "
                                    "command this node (list the operators' networks in transport.control_from)");
  h->make_node(*h->udp_link_);
  h->udp_link_->on_packet([host = h.get()](const PacketView& packet, transport::Framing, rt::SenderStanding standing) {
    if (host->watcher_) host->watcher_(packet);
    host->node_->receive(packet, standing);
  });
  // No hijack (issue 28): an ID that holds control, an emergency or a
  // service connection here keeps its route to its host while it does. The
  // link asks only on a claim from another address, never per datagram.
  h->udp_link_->pin_routes_while([node = h->node_.get()](std::uint8_t subsystem, std::uint8_t node_id) {
    return node->holds_state_for(subsystem, node_id);
  });
  if (auto added = h->add_components(&io); !added) return unexpected(added.error());
  if (h->config_.jss.enabled) {
    transport::UdpLink* udp = h->udp_link_.get();
    h->make_jss_face([udp](const jss::JssId& to, std::span<const std::uint8_t> datagram) {
      udp->transmit_jss(to, datagram);
    });
    // The link decodes each datagram once; the face takes its messages.
    h->udp_link_->on_jss_packets([face = h->jss_face_.get()](const transport::Inbound& inbound,
                                                             rt::SenderStanding standing) {
      face->receive_packets(inbound.jss, standing);
    });
    // Log lines about a JSS client name its host: where its node's route is.
    h->jss_face_->locate_clients_with([udp](const jss::JssId& client) -> std::optional<std::string> {
      const auto route = udp->jss_routes().route(client.subsystem, client.node);
      if (!route) return std::nullopt;
      return transport::to_string(route->endpoint);
    });
    // No hijack of a JSS client's ID either while its alias holds state here.
    h->udp_link_->pin_jss_routes_while([face = h->jss_face_.get()](std::uint16_t subsystem, std::uint8_t node_id) {
      return face->holds_state_for(subsystem, node_id);
    });
    // Before the link receives: a JSS holder's alias slot and JSS route are its own again.
    h->rebind_jss_holders();
  }
  // What was restored, now with every binding known (issue 42: the holders' hosts).
  h->persist_emergency_holds();
  h->arm_drop_summary();
  h->udp_link_->start();
  return h;
}

Expected<std::unique_ptr<NodeHost>> NodeHost::attach(HostConfig config, node::Link& link, rt::Clock& clock,
                                                     rt::Scheduler& scheduler, rt::LogFn log) {
  std::unique_ptr<NodeHost> h(new NodeHost(std::move(config), std::move(log)));
  h->clock_ = &clock;
  h->scheduler_ = &scheduler;
  h->make_node(link);
  if (auto added = h->add_components(nullptr); !added) return unexpected(added.error());
  if (h->config_.jss.enabled) {
    h->make_jss_face([host = h.get()](const jss::JssId& to, std::span<const std::uint8_t> datagram) {
      if (host->jss_sender_) host->jss_sender_(to, datagram);
    });
    h->rebind_jss_holders();
  }
  h->persist_emergency_holds();
  h->arm_drop_summary();
  return h;
}

void NodeHost::make_node(node::Link& link) {
  node::Link* node_link = &link;
  if (config_.jss.enabled) {
    face_link_ = std::make_unique<jss_face::FaceLink>(link);
    node_link = face_link_.get();
  }
  if (config_.send_budget.enabled()) {
    // Images in pieces the radio carries in 50 ms: a stop is never long behind one.
    config_.node.large_data_set_piece =
        std::min(config_.node.large_data_set_piece, node::piece_size_for(config_.send_budget));
    budgeted_link_ = std::make_unique<node::BudgetedLink>(*node_link, *clock_, *scheduler_, config_.send_budget);
    node_link = budgeted_link_.get();
  }
  rt::LogFn node_log = log_;
  if (config_.jss.enabled) {
    // The components know a JSS client only by its alias: their lines
    // (control refused, a command from a non-controller, ...) name the
    // client's own JSS ID and host after it. The face goes first on
    // destruction (~NodeHost): the node's last lines pass unchanged.
    node_log = [this](rt::LogLevel level, const std::string& text) {
      log_(level, jss_face_ ? jss_face_->name_clients_in(text) : text);
    };
  }
  node_ = std::make_unique<node::Node>(config_.node, *clock_, *scheduler_, *node_link, std::move(node_log));
}

void NodeHost::make_jss_face(jss_face::JssFace::DatagramSender send) {
  // The face's services beyond the core: every kind's (host never names one).
  jss_face_ =
      std::make_unique<jss_face::JssFace>(config_.jss, jss_translators(), *node_, std::move(send), log_);
  face_link_->attach(jss_face_.get());
}

Expected<void> NodeHost::add_components(boost::asio::io_context* io) {
  auto platform = make_platform(config_.platform, SimulationSettings{config_.vehicle, config_.cameras, config_.arm},
                                PlatformEnvironment{*clock_, *scheduler_, io, log_});
  if (!platform) return unexpected(platform.error());
  platform_ = std::move(*platform);
  // The hardware the configured components need (each kind says which
  // interfaces), each made once on the configured platform.
  for (const auto& spec : config_.components)
    if (const ComponentKind* kind = find_component_kind(spec.kind))
      for (const std::string_view interface : kind->needs)
        if (auto provided = platform_->provide(interface, backends_); !provided)
          return unexpected(provided.error());
  std::vector<rt::EmergencyLatch*> estop_latches;  // of the components the platform's e-stop holds
  rt::EmergencyLatch* driver_latch = nullptr;      // the platform's emergency flag mirrors it
  if (auto restored = restore_emergency_holds(); !restored) return unexpected(restored.error());
  for (const auto& spec : config_.components) {
    auto component = make_component(spec, config_.settings, *node_, backends_);
    if (!component) return unexpected(component.error());
    const ComponentKind& kind = *find_component_kind(spec.kind);  // made, so known
    if (!kind.needs.empty()) {
      const auto needs = [&](std::string_view interface) {
        return std::find(kind.needs.begin(), kind.needs.end(), interface) != kind.needs.end();
      };
      // Before it starts: a hold restored from the file puts it in Emergency at once.
      rt::EmergencyLatch& latch = latch_for(spec);
      (*component)->share_emergency(latch);
      // The platform's emergency flag mirrors the latch of what drives the vehicle.
      if (needs(components::Drive::kInterface)) driver_latch = &latch;
      // Every component on the platform's e-stop is held by it.
      const bool on_estop = std::any_of(kind.needs.begin(), kind.needs.end(),
                                        [&](std::string_view interface) { return platform_->on_estop(interface); });
      if (on_estop && std::find(estop_latches.begin(), estop_latches.end(), &latch) == estop_latches.end())
        estop_latches.push_back(&latch);
    } else {
      // No hardware: its holds are not persisted, but the local clear reaches them.
      (*component)->share_emergency(unpersisted_latch_for(spec));
    }
    node_->add(std::move(*component));
  }
  platform_->follow_emergencies(std::move(estop_latches), driver_latch);
  return {};
}

// ---- emergency holds (emergency_holds.hpp) -------------------------------------

Expected<void> NodeHost::restore_emergency_holds() {
  if (config_.operator_unit) return {};  // nothing to persist, and never a vehicle's file (HostConfig)
  holds_file_ = emergency_holds_file(config_.emergency);
  if (!holds_file_) {
    log_(rt::LogLevel::warn, "emergency holds are not persisted (no state_directory): a restart forgets them");
    return {};
  }
  // Fail safe (issue 42): a Set Emergency the node could not keep across a
  // restart would be lost in silence, so a node that cannot write its state
  // directory does not start.
  if (auto writable = check_state_directory(holds_file_->parent_path()); !writable)
    return unexpected(make_error(ErrorCode::io, writable.error().message() +
                                                    ": emergency holds could not be kept across a restart; not started"));
  auto state = read_emergency_holds(*holds_file_);
  if (!state) {
    // Fail safe: who held what is unknown, so everything is held until the local clear.
    holds_unreadable_ = true;
    log_(rt::LogLevel::error, "emergency holds unreadable (" + state.error().message() +
                                  "): every component with hardware is held in Emergency until SIGUSR1 clears it");
    return {};
  }
  holds_generation_ = state->generation;
  if (state->previous_version && !state->holds.empty())
    log_(rt::LogLevel::warn, "emergency holds written by a previous version (no dialects, no hosts): each is held "
                             "until the local clear (SIGUSR1), since its holder's host is unknown");
  bind_restored_holders(std::move(state->holds));
  return {};
}

// Issue 42: a restored holder is bound to the dialect, ID and host it held
// from, before the link receives, so the same holder from the same host (any
// port) clears it and nobody else can:
// - RA: its node's route is reserved to its host (RouteTable::reserve, pinned
//   by the hold), so the ID from another host is a refused claim;
// - JSS: its alias slot is its JSS client node's again (rebind_jss_holders)
//   and that node's JSS route is reserved to its host, so another JSS client
//   is given another slot, and the client's ID from another host is refused.
// A holder bound to nothing (a file of the previous version, a host the node
// did not know, a JSS hold with the face now off or its alias subsystem
// changed, two clients in one slot) cannot be told from a forger: it holds
// as the latch's overflow, released only by the local clear (SIGUSR1).
// An attached host (no network: its caller delivers every message) restores
// holders of a known dialect by ID.
void NodeHost::bind_restored_holders(PersistedHolds holds) {
  const bool opened = udp_link_ != nullptr;
  const std::uint8_t alias_subsystem = config_.jss.enabled ? config_.jss.client_alias_subsystem : 0;
  std::map<std::uint8_t, jss::JssId> slots;  // the JSS holders' slots: one client node each
  for (auto& [latch, hold] : holds) {
    RestoredHold& restored = restored_holds_[latch];
    restored.overflowed = hold.overflowed;
    std::string who;
    const auto add = [&](const std::string& part) { who += (who.empty() ? "" : ", ") + part; };
    for (const PersistedHolder& h : hold.holders) {
      const std::string from = h.host ? " from " + ipv4_to_string(*h.host) : std::string();
      bool bound = false;
      if (h.dialect == HolderDialect::ra && (h.host || !opened) && h.holder.subsystem != alias_subsystem) {
        if (opened) udp_link_->reserve_route(h.holder.subsystem, h.holder.node, *h.host);
        bound = true;
        add(h.holder.to_string() + " (RA" + from + ")");
      } else if (h.dialect == HolderDialect::jss && h.jss_client && (h.host || !opened) && alias_subsystem != 0 &&
                 h.holder.subsystem == alias_subsystem) {
        const jss::JssId client_node{h.jss_client->subsystem, h.jss_client->node, jss::JssId::kAll};
        const auto [slot, fresh] = slots.try_emplace(h.holder.node, client_node);
        bool slot_ours = slot->second == client_node;
        for (const auto& [other_slot, other] : slots)
          if (other == client_node && other_slot != h.holder.node) slot_ours = false;
        if (slot_ours) {
          if (fresh) jss_bindings_.push_back(JssBinding{h.holder.node, client_node, h.host.value_or(0)});
          bound = true;
          add(h.holder.to_string() + " (JSS " + h.jss_client->to_string() + from + ")");
        }
      }
      if (bound) {
        restored.bound.push_back(h.holder);
      } else {
        restored.overflowed = true;
        add(h.holder.to_string() + " (" + to_string(h.dialect) + from +
            ", bound to no host: released only by the local clear)");
      }
    }
    if (hold.overflowed) add("senders beyond the recorded ones");
    log_(rt::LogLevel::warn, "emergency held since before the restart (" + latch + "): " + who);
  }
}

void NodeHost::rebind_jss_holders() {
  if (!jss_face_) return;
  for (const JssBinding& b : jss_bindings_) {
    if (!jss_face_->reserve_client(b.slot, b.client_node)) {
      // Beyond jss.max_clients: no client is ever given that slot, so only the local clear releases its hold.
      log_(rt::LogLevel::error, "JSS client " + b.client_node.to_string() + " held an emergency under alias slot " +
                                    std::to_string(b.slot) + ", which this configuration does not have (jss.max_clients): "
                                    "released only by the local clear");
      continue;
    }
    if (udp_link_) udp_link_->reserve_jss_route(b.client_node.subsystem, b.client_node.node, b.host);
  }
}

rt::EmergencyLatch& NodeHost::latch_for(const ComponentSpec& spec) {
  const std::string name =
      config_.emergency.scope == EmergencyScope::vehicle && moves_hardware(spec.kind)
          ? std::string("vehicle")
          : Address{config_.node.subsystem, config_.node.node, spec.id, spec.instance}.to_string();
  auto& latch = latches_[name];
  if (latch) return *latch;
  latch = std::make_unique<rt::EmergencyLatch>();
  if (holds_unreadable_) latch->restore({}, /*overflowed=*/true);
  // A hold of a latch this configuration no longer has (the scope changed)
  // holds every latch: nobody is forgotten.
  for (const auto& [held, hold] : restored_holds_)
    if (held == name || !latch_configured(held)) latch->restore(hold.bound, hold.overflowed);
  // Written right after the change has taken effect: the stop first, then the disk.
  latch->observe([this](const rt::EmergencyLatch&) { schedule_persisting(); });
  return *latch;
}

rt::EmergencyLatch& NodeHost::unpersisted_latch_for(const ComponentSpec& spec) {
  const Address address{config_.node.subsystem, config_.node.node, spec.id, spec.instance};
  auto& latch = unpersisted_latches_[address.to_string() + " (" + (spec.name.empty() ? spec.kind : spec.name) + ")"];
  latch = std::make_unique<rt::EmergencyLatch>();
  return *latch;
}

bool NodeHost::latch_configured(const std::string& name) const {
  if (name == "vehicle") return config_.emergency.scope == EmergencyScope::vehicle;
  for (const auto& c : config_.components)
    if (has_hardware(c.kind) &&
        Address{config_.node.subsystem, config_.node.node, c.id, c.instance}.to_string() == name)
      return true;
  return false;
}

// A file write (and its fsync) never delays a stop: the members of a latch
// follow its change in the same call, the write comes once that handler is
// done, and a flood of new holders in one batch is one write. Should jausd die
// in between, the platform's emergency flag it left is held as the platform's
// own stop by the next run (fail safe).
void NodeHost::schedule_persisting() {
  if (!holds_file_ || persist_posted_) return;
  persist_posted_ = true;
  scheduler_->post([this, alive = std::weak_ptr<char>(alive_)] {
    if (alive.expired()) return;
    persist_posted_ = false;
    persist_emergency_holds();
  });
}

PersistedHold NodeHost::describe_for_persisting(const rt::EmergencyLatch& latch) const {
  PersistedHold hold;
  hold.overflowed = latch.overflowed();
  for (const Address& a : latch.holders()) {
    PersistedHolder h{a, HolderDialect::ra, std::nullopt, std::nullopt};
    if (jss_face_ && jss_face_->owns(a)) {
      // A JSS client's alias: the client, and the host its JSS route is pinned to.
      h.dialect = HolderDialect::jss;
      h.jss_client = jss_face_->client_of_alias(a);
      if (!h.jss_client) h.dialect = HolderDialect::unknown;  // (its slot is gone: bound to nothing)
      else if (udp_link_) h.host = udp_link_->jss_routes().address_of(h.jss_client->subsystem, h.jss_client->node);
    } else if (udp_link_) {
      h.host = udp_link_->routes().address_of(a.subsystem, a.node);
    }
    hold.holders.push_back(std::move(h));
  }
  return hold;
}

void NodeHost::persist_emergency_holds() {
  if (!holds_file_) return;
  PersistedHolds holds;
  for (const auto& [name, latch] : latches_)
    if (latch->held_by_jaus()) holds[name] = describe_for_persisting(*latch);
  // Nothing changed (a local hold did), unless the last write failed: then
  // the sidecar may be ahead of the holds file, and the retry rewrites both.
  if (holds == written_holds_ && !persisting_fails_) return;
  if (auto written = write_emergency_holds(*holds_file_, holds, ++holds_generation_); !written)
    return persisting_failed(written.error());
  written_holds_ = std::move(holds);
  if (persisting_fails_) persisting_recovered();
}

// Safety (issue 42): while the holds cannot be written, no Clear Emergency
// is taken (EmergencyLatch::refuse_clears; the OCU's component stays in
// Emergency and its status says so): a clear the file does not have would
// undo itself at a restart, and a Set the file does not have must not be
// cleared into a state the disk never saw. Said once per failing streak,
// retried every few seconds and at every change; the local clear still works.
void NodeHost::persisting_failed(const Error& error) {
  if (!persisting_fails_)
    log_(rt::LogLevel::error, "emergency holds not persisted: " + error.message() +
                                  "; every Clear Emergency is refused until they are (retried every " +
                                  std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kPersistRetry).count()) +
                                  " s and at every change; SIGUSR1 still clears locally)");
  persisting_fails_ = true;
  for (const auto& [name, latch] : latches_) latch->refuse_clears(true);
  if (persist_retry_ != rt::kNoTimer) return;
  persist_retry_ = scheduler_->call_at(clock_->now() + kPersistRetry, [this, alive = std::weak_ptr<char>(alive_)] {
    if (alive.expired()) return;
    persist_retry_ = rt::kNoTimer;
    persist_emergency_holds();
  });
}

void NodeHost::persisting_recovered() {
  persisting_fails_ = false;
  for (const auto& [name, latch] : latches_) latch->refuse_clears(false);
  if (persist_retry_ != rt::kNoTimer) scheduler_->cancel(persist_retry_);
  persist_retry_ = rt::kNoTimer;
  log_(rt::LogLevel::info, "emergency holds persisted again: Clear Emergency is taken again");
}

// Safety: the local clear releases every Set Emergency hold (a JAUS sender's,
// recorded or not) on every component: the latches of the components with
// hardware (the vehicle's shared one, each sensor's own) and those of the
// components without (node manager, communicator, drivers). A local hold (the
// platform's own e-stop or pause, its emergency flag not yet confirmed clear)
// is never touched: only the platform clears those.
std::size_t NodeHost::clear_emergency_holds_locally(const std::string& why) {
  std::size_t cleared = 0;
  const auto clear = [&](const std::string& name, rt::EmergencyLatch& latch) {
    if (!latch.held_by_jaus()) return;
    const std::string held = latch.describe_holders();
    cleared += latch.clear_jaus_holders();
    log_(rt::LogLevel::warn, "emergency holds cleared locally (" + why + "), " + name + ": " + held);
    if (latch.active())
      log_(rt::LogLevel::warn, "emergency still held, " + name + ": " + latch.describe_holders() +
                                   " (the platform's own stop: only the platform clears it)");
  };
  for (const auto& [name, latch] : latches_) clear(name, *latch);
  for (const auto& [name, latch] : unpersisted_latches_) clear(name, *latch);
  // What an earlier run left on the platform is ours to clear too; a hardware stop stays.
  if (platform_) platform_->reclaim_stops();
  if (cleared == 0) log_(rt::LogLevel::info, "local clear of emergency holds (" + why + "): none held");
  return cleared;
}

void NodeHost::arm_drop_summary() {
  if (config_.operator_unit || stopped_) return;
  const auto counts = [this] {
    return drop_counts(udp_link_ ? &udp_link_->counters() : nullptr, node_->counters(),
                       budgeted_link_ ? &budgeted_link_->counters() : nullptr);
  };
  drops_seen_ = counts();
  drop_summary_ = scheduler_->call_at(clock_->now() + kDropSummaryPeriod, [this, counts] {
    drop_summary_ = rt::kNoTimer;
    const DropCounts now = counts();
    if (const std::string line = describe_drops(drops_seen_, now); !line.empty()) log_(rt::LogLevel::warn, line);
    arm_drop_summary();
  });
}

const rt::EmergencyLatch* NodeHost::emergency_latch(const std::string& name) const {
  const auto it = latches_.find(name);
  return it == latches_.end() ? nullptr : it->second.get();
}

NodeHost::~NodeHost() {
  stop("host destroyed");
  // The face goes before the node and the links: nothing reaches it after.
  if (face_link_) face_link_->attach(nullptr);
  if (udp_link_) {
    udp_link_->on_jss_packets(nullptr);
    udp_link_->pin_jss_routes_while(nullptr);
  }
  jss_face_.reset();
  if (platform_) platform_->stop();  // a host that never fully opened: its frame thread, before its cameras go
}

Expected<void> NodeHost::run(boost::asio::io_context& io) {
  std::string failure;
  try {
    io.run();
  } catch (const std::exception& e) {
    // Nothing in the libraries throws, but should anything escape the loop
    // (memory exhausted, a bug), the platform still stops before the exit.
    failure = e.what();
  } catch (...) {
    failure = "unknown exception";
  }
  if (failure.empty()) {
    stop("event loop ended");
    return {};
  }
  log_(rt::LogLevel::error, "event loop failed: " + failure + "; stopping");
  stop("exception: " + failure);
  return unexpected(make_error(ErrorCode::interrupted, failure));
}

rt::ComponentConfig NodeHost::component_config(std::string name, std::uint8_t component, std::uint8_t instance) const {
  rt::ComponentConfig c = config_.settings.defaults;
  c.name = std::move(name);
  c.address = Address{config_.node.subsystem, config_.node.node, component, instance};
  return c;
}

void NodeHost::stop(const std::string& why) {
  if (stopped_ || !node_) return;  // stopped, or never fully opened
  stopped_ = true;
  // Safety: the node shuts every component down (platform commanded to stop)
  // while the link can still carry their last messages.
  node_->shutdown(why);
  // Its last messages (Reject Component Control, ...) go now, not at the
  // budget's pace: the loop may not run again.
  if (budgeted_link_) budgeted_link_->flush();
  // No frame is wanted after Shutdown (a frame thread ends here, before
  // anything it was given could go), and the stop's zero setpoint goes out
  // now, before a process exits without running its io_context again.
  if (platform_) platform_->stop();
  persist_emergency_holds();  // a change still waiting for the loop
  if (persist_retry_ != rt::kNoTimer) scheduler_->cancel(persist_retry_);  // nothing keeps the loop after the stop
  persist_retry_ = rt::kNoTimer;
  if (drop_summary_ != rt::kNoTimer) scheduler_->cancel(drop_summary_);
  drop_summary_ = rt::kNoTimer;
  const auto& n = node_->counters();
  const std::string budget = budgeted_link_ ? ", " + budgeted_link_->summary() : "";
  if (!udp_link_) {
    log_(rt::LogLevel::info,
         "stopped (" + why + "): " + std::to_string(n.delivered) + " messages delivered" + budget);
    return;
  }
  const auto& l = udp_link_->counters();
  std::string reasons;
  for (std::size_t r = 0; r < l.dropped.size(); ++r)
    if (l.dropped[r] > 0)
      reasons += std::string(reasons.empty() ? " (" : ", ") + std::to_string(l.dropped[r]) + " " +
                 std::string(transport::to_string(static_cast<transport::DropReason>(r)));
  if (!reasons.empty()) reasons += ")";
  std::string jss;
  if (jss_face_) {
    const auto& f = jss_face_->counters();
    jss = ", JSS: " + std::to_string(l.jss.datagrams_received) + " AS5669A datagrams in, " +
          std::to_string(f.messages_to_ra) + " messages to RA, " + std::to_string(f.messages_to_jss) + " to JSS, " +
          std::to_string(f.duplicates) + " copies not acted on, " + std::to_string(f.refused) + " requests refused";
  }
  log_(rt::LogLevel::info, "stopped (" + why + "): " + std::to_string(l.datagrams_received) + " datagrams in, " +
                               std::to_string(l.dropped_total()) + " dropped" + reasons + ", " +
                               std::to_string(n.delivered) + " messages delivered, " +
                               std::to_string(l.datagrams_sent) + " datagrams out" + jss + budget);
  udp_link_->close();
}

}  // namespace jaus::host
