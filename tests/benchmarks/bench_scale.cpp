// How the system grows with its size (issue 32), measured (prints, asserts
// nothing): S subsystems (default 10, 50 and 100), each one or more in-process
// nodes (jaus::host::NodeHost) on one jaus::testing memory network under
// virtual time, every node with its node manager, node 1 also with a
// communicator, a primitive driver and a global pose sensor (a vehicle), the
// further nodes of a subsystem a velocity state sensor; then one or more OCUs
// that discover them with the logic of `jausctl discover` (ocu::Discovery).
//
// Per run:
// - convergence (virtual time): until every vehicle node's subsystem list
//   (Report Subsystem List) names every vehicle subsystem, and then, from the
//   OCUs' start, until each OCU lists every subsystem with its nodes and
//   components, each identified and with its services;
// - heap (a replaced global operator new counts the bytes in use): per
//   subsystem as built, what the vehicles' tables grew by while they learnt
//   each other per peer entry (per ordered pair of subsystems: S*(S-1)), and
//   what an OCU grew by per subsystem it lists;
// - steady state (10 s after discovery): JAUS messages a second handed to the
//   network and delivered, in total, per node and by message;
// - the real (wall-clock) time each run took.
//
// Two fabrics: `routed` is the memory network as it is (a message reaches the
// nodes its destination names: a UDP deployment whose broadcasts go to the
// known peers of the addressed subsystem, broadcast_to_peers); `multicast`
// gives every broadcast to every node (transport.multicast: the group hears
// each subsystem's own heartbeats too, and every node's liveness table
// records their senders).
//
//   bench_scale [--subsystems 10,50,100] [--nodes 1] [--ocus 1]
//               [--fabric routed|multicast|both] [--latency-ms 1] [--jitter-us 0]
//               [--steady-s 10]
#include <malloc.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/catalogue.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/ocu/discovery.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

// ---- heap in use: every operator new / delete of the process ---------------------

namespace {
std::atomic<std::int64_t> g_heap_bytes{0};
std::atomic<std::uint64_t> g_allocations{0};

[[gnu::noinline]] void* counted_malloc(std::size_t size) noexcept {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p) {
    g_heap_bytes.fetch_add(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return p;
}
[[gnu::noinline]] void counted_free(void* p) noexcept {
  if (!p) return;
  g_heap_bytes.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}
}  // namespace

// Not inlined: inlined into a caller, GCC takes the free() for a mismatched
// delete of new's pointer (as tests/load/steady_state_allocation_test.cpp says).
[[gnu::noinline]] void* operator new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t size) { return operator new(size); }
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
[[gnu::noinline]] void operator delete(void* p) noexcept { counted_free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { counted_free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { counted_free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_free(p); }

namespace {

using namespace jaus;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

std::int64_t heap_bytes() { return g_heap_bytes.load(std::memory_order_relaxed); }
double seconds(rt::Duration d) { return std::chrono::duration<double>(d).count(); }
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// How long the OCUs may take to list everything: five times `jausctl
// discover`'s default --wait, which asks each question once.
constexpr rt::Duration kDiscoveryLimit = 10s;
constexpr std::uint8_t kOperatorAuthority = 5;  // above the vehicles' components (0)

enum class Fabric { routed, multicast };
const char* fabric_name(Fabric f) { return f == Fabric::routed ? "routed" : "multicast"; }

struct Options {
  std::vector<int> subsystems{10, 50, 100};
  int nodes_per_subsystem = 1;
  int ocus = 1;
  std::vector<Fabric> fabrics{Fabric::routed, Fabric::multicast};
  rt::Duration latency = 1ms;
  rt::Duration jitter{};
  rt::Duration steady = 10s;
};

// ---- traffic: what each node hands the network and what reaches it ------------

struct Traffic {
  std::map<std::uint16_t, std::uint64_t> sent_by_code;
  std::map<std::uint16_t, std::uint64_t> delivered_by_code;
  std::uint64_t sent = 0;
  std::uint64_t delivered = 0;
};

std::uint16_t code_of(std::span<const std::uint8_t> packet) {
  const auto decoded = decode_packet(packet);
  return decoded ? decoded->header.command_code : 0;
}

// A node's way onto the memory network: counts what it sends, and in the
// multicast fabric hands every broadcast to every node, as a multicast group
// does. With jitter, each message leaves up to `jitter` later (in its
// sender's order), as processing and the wire spread a burst of replies; without,
// every reply to one wave of queries arrives at the same instant.
class FabricLink final : public node::Link {
 public:
  struct Jitter {
    rt::Clock* clock = nullptr;
    rt::Scheduler* scheduler = nullptr;
    rt::Duration most{};
    std::mt19937* random = nullptr;
  };
  FabricLink(testing::MemoryLink& link, Fabric fabric, Traffic& traffic, Jitter jitter)
      : link_(link), fabric_(fabric), traffic_(traffic), jitter_(jitter) {}

  void transmit(const Header& header, std::span<const std::uint8_t> packet) override {
    ++traffic_.sent;
    ++traffic_.sent_by_code[header.command_code];
    if (!link_.connected()) return;  // the network is down now, not when the message would leave
    if (jitter_.most <= rt::Duration::zero()) return forward(header, packet);
    std::uniform_int_distribution<rt::Duration::rep> spread(0, jitter_.most.count());
    const rt::TimePoint when = std::max(leaves_, jitter_.clock->now() + rt::Duration(spread(*jitter_.random)));
    leaves_ = when;
    jitter_.scheduler->call_at(when, [this, header, bytes = std::vector<std::uint8_t>(packet.begin(), packet.end())] {
      forward(header, bytes);
    });
  }
  // What reaches this node goes to `receiver`, counted.
  void deliver(std::function<void(std::span<const std::uint8_t>)> receiver) {
    if (!receiver) return link_.on_receive({});
    link_.on_receive([this, receiver = std::move(receiver)](std::span<const std::uint8_t> packet) {
      ++traffic_.delivered;
      ++traffic_.delivered_by_code[code_of(packet)];
      receiver(packet);
    });
  }
  void set_connected(bool connected) { link_.set_connected(connected); }

 private:
  void forward(const Header& header, std::span<const std::uint8_t> packet) {
    const bool broadcast =
        header.destination.subsystem == Address::kBroadcast || header.destination.node == Address::kBroadcast;
    if (fabric_ == Fabric::multicast && broadcast)
      link_.transmit_to_every_link(header, packet);
    else
      link_.transmit(header, packet);
  }

  testing::MemoryLink& link_;
  Fabric fabric_;
  Traffic& traffic_;
  Jitter jitter_;
  rt::TimePoint leaves_{};  // when this sender's latest message leaves
};

// ---- the system under test ----------------------------------------------------

struct ComponentPlan {
  std::string kind;
  std::uint8_t id = 0;
};

std::uint8_t id_of(const char* kind) {
  const host::ComponentKind* k = host::find_component_kind(kind);
  if (!k) throw std::invalid_argument(std::string("no component kind ") + kind);
  return k->default_id;
}

// Node 1 of a subsystem is the vehicle's main computer; the others each add a sensor.
std::vector<ComponentPlan> components_of_node(int node) {
  std::vector<ComponentPlan> plan{{"node_manager", 1}};
  if (node == 1) {
    plan.push_back({"communicator", id_of("communicator")});
    plan.push_back({"primitive_driver", id_of("primitive_driver")});
    plan.push_back({"global_pose_sensor", id_of("global_pose_sensor")});
  } else {
    plan.push_back({"velocity_state_sensor", id_of("velocity_state_sensor")});
  }
  return plan;
}

host::HostConfig vehicle_config(std::uint8_t subsystem, std::uint8_t node) {
  host::HostConfig c;
  c.node.subsystem = subsystem;
  c.node.node = node;
  c.settings.identity.subsystem_name = "vehicle-" + std::to_string(subsystem);
  c.settings.identity.node_name = "computer-" + std::to_string(node);
  for (const auto& p : components_of_node(node))
    c.components.push_back(host::ComponentSpec{p.kind, p.id, 1, 0, "", {}, 0, {}});
  return c;
}

std::uint8_t ocu_subsystem(int index) { return static_cast<std::uint8_t>(254 - index); }

struct Ocu {
  std::unique_ptr<FabricLink> link;
  std::unique_ptr<ocu::OcuSession> session;
  std::unique_ptr<ocu::Discovery> discovery;
  ocu::OcuSession::ListenerId watcher = 0;
  ocu::OcuSession::ListenerId listener = 0;
  std::optional<rt::Duration> complete_after;
};

// What `jausctl discover` sends for each query (ocu/src/discover.cpp).
void send_queries(ocu::OcuSession& session, const std::vector<ocu::DiscoveryQuery>& queries) {
  using Kind = ocu::DiscoveryQuery::Kind;
  for (const auto& q : queries) {
    switch (q.kind) {
      case Kind::identification:
        session.send(q.to, msg::QueryIdentification{{q.field}});
        break;
      case Kind::configuration:
        session.send(q.to, msg::QueryConfiguration{{q.field}});
        break;
      case Kind::services:
        session.send(q.to, msg::QueryServices{});
        break;
      case Kind::subsystem_list:
        session.send(q.to, msg::QuerySubsystemList{});
        break;
    }
  }
}

struct RunFigures {
  int subsystems = 0;
  std::optional<rt::Duration> mesh_converged;  // from power-on
  std::optional<rt::Duration> ocus_complete;   // from the OCUs' start, the slowest
  double heap_per_subsystem_bytes = 0;         // as built
  double heap_per_subsystem_pair_bytes = 0;    // the vehicles' growth while learning each other, per ordered pair
  double ocu_heap_per_subsystem_bytes = 0;     // an OCU's growth while discovering
  double liveness_entries_per_node = 0;        // mean, vehicle nodes, steady state
  std::size_t liveness_entries_max = 0;
  std::uint64_t liveness_rejected_full = 0;    // newcomers refused, all nodes
  std::uint64_t queue_dropped = 0;             // inbound queue full, all nodes
  std::size_t ocu_liveness_entries = 0;        // the first OCU's, when it listed everything
  double discovery_wall_ms = 0;                // real time the OCUs' discovery took, in this one process
  std::string control;                         // what the first OCU's Request Component Control of 1.1.33.1 got
  Traffic discovery;                           // from the OCUs' start until every OCU listed everything
  Traffic steady;                              // over the steady window
  double steady_s = 0;
  int vehicle_nodes = 0;
  int all_nodes = 0;
  double wall_s = 0;
};

class System {
 public:
  System(const Options& o, Fabric fabric, int subsystems)
      : options_(o), fabric_(fabric), subsystems_(subsystems), network_(time_, time_, o.latency) {}
  ~System() {
    for (auto& o : ocus_) {
      if (o.session) {
        o.session->unlisten(o.watcher);
        o.session->unlisten(o.listener);
      }
      o.session.reset();
      o.link->deliver({});
    }
    for (auto& h : hosts_) h->stop("benchmark over");
    for (auto& l : links_) l->deliver({});
  }
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  RunFigures run() {
    RunFigures f;
    f.subsystems = subsystems_;
    f.vehicle_nodes = subsystems_ * options_.nodes_per_subsystem;
    f.all_nodes = f.vehicle_nodes + options_.ocus;
    const auto wall_start = Clock::now();

    // Built with the network down, so that what is measured as built holds
    // nothing heard and nothing in flight; then the network comes up for all.
    const auto heap_before_vehicles = heap_bytes();
    build_vehicles();
    const auto heap_built = heap_bytes();
    f.heap_per_subsystem_bytes = static_cast<double>(heap_built - heap_before_vehicles) / subsystems_;

    for (auto& link : links_) link->set_connected(true);
    const auto power_on = time_.now();
    if (testing::run_until(time_, [&] { return every_vehicle_lists_every_subsystem(); }, 60s, 10ms))
      f.mesh_converged = time_.now() - power_on;
    // Past the first heartbeats of everyone: the tables hold what they will hold.
    testing::run_for(time_, 3s);
    const auto heap_learnt = heap_bytes();
    const double ordered_pairs = static_cast<double>(subsystems_) * (subsystems_ - 1);
    f.heap_per_subsystem_pair_bytes =
        ordered_pairs > 0 ? static_cast<double>(heap_learnt - heap_built) / ordered_pairs : 0;

    attach_ocus();
    const auto heap_ocus_attached = heap_bytes();
    const Traffic before_discovery = traffic_;
    const auto discovery_wall_start = Clock::now();
    const auto ocus_start = time_.now();
    for (auto& o : ocus_) send_queries(*o.session, o.discovery->start());
    testing::run_until(
        time_,
        [&] {
          bool all = true;
          for (auto& o : ocus_) {
            if (!o.complete_after && lists_everything(*o.discovery)) {
              o.complete_after = time_.now() - ocus_start;
              if (&o == &ocus_.front()) f.ocu_liveness_entries = o.session->node().liveness().size();
            }
            all = all && o.complete_after.has_value();
          }
          return all;
        },
        kDiscoveryLimit);
    f.discovery_wall_ms = seconds_since(discovery_wall_start) * 1000;
    if (!ocus_.front().complete_after) f.ocu_liveness_entries = ocus_.front().session->node().liveness().size();
    f.discovery = difference(traffic_, before_discovery);
    bool every_ocu_complete = true;
    rt::Duration slowest{};
    for (const auto& o : ocus_) {
      if (!o.complete_after) every_ocu_complete = false;
      else slowest = std::max(slowest, *o.complete_after);
    }
    if (every_ocu_complete) f.ocus_complete = slowest;
    f.ocu_heap_per_subsystem_bytes =
        static_cast<double>(heap_bytes() - heap_ocus_attached) / options_.ocus / subsystems_;

    f.control = try_control();

    // Steady state: the discovery replies are in, the OCUs stay on the network.
    testing::run_for(time_, 2s);
    const Traffic at_start = traffic_;
    const auto steady_start = time_.now();
    testing::run_for(time_, options_.steady);
    f.steady_s = seconds(time_.now() - steady_start);
    f.steady = difference(traffic_, at_start);

    std::size_t entries = 0;
    for (const auto& h : hosts_) {
      const auto& liveness = h->node().liveness();
      entries += liveness.size();
      f.liveness_entries_max = std::max(f.liveness_entries_max, liveness.size());
      f.liveness_rejected_full += liveness.counters().rejected_full;
      f.queue_dropped += h->node().counters().queue_dropped;
    }
    for (const auto& o : ocus_) {
      f.liveness_rejected_full += o.session->node().liveness().counters().rejected_full;
      f.queue_dropped += o.session->node().counters().queue_dropped;
    }
    f.liveness_entries_per_node = static_cast<double>(entries) / static_cast<double>(hosts_.size());
    f.wall_s = seconds_since(wall_start);
    return f;
  }

 private:
  FabricLink& new_link(std::uint8_t subsystem, std::uint8_t node) {
    links_.push_back(std::make_unique<FabricLink>(network_.attach(subsystem, node), fabric_, traffic_, jitter()));
    return *links_.back();
  }

  void build_vehicles() {
    for (int s = 1; s <= subsystems_; ++s)
      for (int n = 1; n <= options_.nodes_per_subsystem; ++n) {
        FabricLink& link = new_link(static_cast<std::uint8_t>(s), static_cast<std::uint8_t>(n));
        link.set_connected(false);
        auto host = host::NodeHost::attach(vehicle_config(static_cast<std::uint8_t>(s), static_cast<std::uint8_t>(n)),
                                           link, time_, time_);
        if (!host) throw std::runtime_error(host.error().message());
        node::Node& node = (*host)->node();
        link.deliver([&node](std::span<const std::uint8_t> packet) { node.receive_bytes(packet); });
        hosts_.push_back(std::move(*host));
      }
  }

  // Whether an operator can still take control once the system is this
  // large: a vehicle whose liveness table is full treats a new OCU as
  // unrecorded and refuses it. Released at once (no controller traffic later).
  std::string try_control() {
    ocu::OcuSession& s = *ocus_.front().session;
    const Address driver{1, 1, id_of("primitive_driver"), 1};
    auto reply =
        s.request(driver, msg::RequestComponentControl{{kOperatorAuthority}}, {msg::ConfirmComponentControl::code}, 1s);
    if (!reply) return "no reply";
    msg::ConfirmComponentControl confirm{};
    if (!wire::decode_payload_into(reply->payload, confirm, wire::Dialect::ra, kHeaderSize)) return "garbled";
    if (confirm.response_code != msg::control_response::kAccepted) return "refused";
    s.send(driver, msg::ReleaseComponentControl{});
    testing::run_for(time_, 100ms);
    return "yes";
  }

  FabricLink::Jitter jitter() { return {&time_, &time_, options_.jitter, &random_}; }

  bool every_vehicle_lists_every_subsystem() const {
    for (const auto& h : hosts_) {
      std::size_t vehicles = 0;
      for (const Address& a : h->node().known_subsystems())
        if (a.subsystem <= subsystems_) ++vehicles;
      if (vehicles < static_cast<std::size_t>(subsystems_)) return false;
    }
    return true;
  }

  void attach_ocus() {
    for (int i = 0; i < options_.ocus; ++i) {
      Ocu o;
      o.link = std::make_unique<FabricLink>(network_.attach(ocu_subsystem(i), 1), fabric_, traffic_, jitter());
      ocu::SessionOptions session;
      session.self = Address{ocu_subsystem(i), 1, 40, 1};
      session.authority = kOperatorAuthority;
      FabricLink* link = o.link.get();
      auto attached = ocu::OcuSession::attach(
          session, ocu::SessionEnvironment{&time_, &time_, link,
                                           [link](std::function<void(std::span<const std::uint8_t>)> receiver) {
                                             link->deliver(std::move(receiver));
                                           },
                                           testing::stepper(time_)});
      if (!attached) throw std::runtime_error(attached.error().message());
      o.session = std::move(*attached);
      o.discovery = std::make_unique<ocu::Discovery>(o.session->self());
      ocu::OcuSession& s = *o.session;
      ocu::Discovery& d = *o.discovery;
      const auto dialect = s.options().dialect;
      // As discover() wires them: heartbeats and replies feed the model, its queries go out.
      o.watcher = s.watch([&s, &d](const Header& h) { send_queries(s, d.heard(h.source)); });
      o.listener = s.listen(
          [&s, &d, dialect](const ocu::Received& r) { send_queries(s, d.received(r.header, r.payload, dialect)); });
      ocus_.push_back(std::move(o));
    }
  }

  // Every vehicle subsystem identified, each of its nodes identified with
  // every component, each component identified and with its services.
  bool lists_everything(const ocu::Discovery& d) const {
    const auto& listed = d.subsystems();
    for (int s = 1; s <= subsystems_; ++s) {
      const auto subsystem = listed.find(static_cast<std::uint8_t>(s));
      if (subsystem == listed.end() || !subsystem->second.identification) return false;
      for (int n = 1; n <= options_.nodes_per_subsystem; ++n) {
        const auto node = subsystem->second.nodes.find(static_cast<std::uint8_t>(n));
        if (node == subsystem->second.nodes.end() || !node->second.identification) return false;
        if (node->second.components.size() != components_of_node(n).size()) return false;
        for (const auto& [key, component] : node->second.components)
          if (!component.identification || ocu::Discovery::services_of(node->second, component).empty()) return false;
      }
    }
    return true;
  }

  static Traffic difference(const Traffic& now, const Traffic& before) {
    Traffic d;
    d.sent = now.sent - before.sent;
    d.delivered = now.delivered - before.delivered;
    for (const auto& [code, n] : now.sent_by_code) {
      const auto b = before.sent_by_code.find(code);
      d.sent_by_code[code] = n - (b == before.sent_by_code.end() ? 0 : b->second);
    }
    for (const auto& [code, n] : now.delivered_by_code) {
      const auto b = before.delivered_by_code.find(code);
      d.delivered_by_code[code] = n - (b == before.delivered_by_code.end() ? 0 : b->second);
    }
    return d;
  }

  const Options& options_;
  Fabric fabric_;
  int subsystems_;
  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  Traffic traffic_;
  std::mt19937 random_{32};  // the same spread every run
  std::vector<std::unique_ptr<FabricLink>> links_;
  std::vector<std::unique_ptr<host::NodeHost>> hosts_;
  std::vector<Ocu> ocus_;
};

// ---- output --------------------------------------------------------------------

std::string duration_text(const std::optional<rt::Duration>& d) {
  if (!d) return "> " + std::to_string(static_cast<int>(seconds(kDiscoveryLimit)));
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", seconds(*d));
  return text;
}

std::string message_name(std::uint16_t code) {
  const msg::MessageInfo* info = msg::find_message(wire::Dialect::ra, code);
  if (info) return std::string(info->name);
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", code);
  return text;
}

void print_run(const RunFigures& f) {
  const double per_s = f.steady_s > 0 ? 1.0 / f.steady_s : 0;
  std::printf("%4d %5d | %6s %6s %7.1f %7s | %8.1f %6.1f %9.1f | %6.1f %5zu %5zu %6llu | %6llu %7llu %5llu | %7.0f "
              "%8.0f %6.1f %7.1f | %6.2f\n",
              f.subsystems, f.all_nodes, duration_text(f.mesh_converged).c_str(),
              duration_text(f.ocus_complete).c_str(), f.discovery_wall_ms, f.control.c_str(),
              f.heap_per_subsystem_bytes / 1024.0,
              f.heap_per_subsystem_pair_bytes, f.ocu_heap_per_subsystem_bytes, f.liveness_entries_per_node,
              f.liveness_entries_max, f.ocu_liveness_entries,
              static_cast<unsigned long long>(f.liveness_rejected_full),
              static_cast<unsigned long long>(f.discovery.sent), static_cast<unsigned long long>(f.discovery.delivered),
              static_cast<unsigned long long>(f.queue_dropped),
              static_cast<double>(f.steady.sent) * per_s, static_cast<double>(f.steady.delivered) * per_s,
              static_cast<double>(f.steady.sent) * per_s / f.all_nodes,
              static_cast<double>(f.steady.delivered) * per_s / f.all_nodes, f.wall_s);
}

void print_header() {
  std::printf("%4s %5s | %-30s | %-26s | %-25s | %-20s | %-33s | %6s\n", "", "", "converged", "heap (bytes)",
              "liveness table entries", "discovery messages", "steady state, messages/s", "wall");
  std::printf("%4s %5s | %6s %6s %7s %7s | %8s %6s %9s | %6s %5s %5s %6s | %6s %7s %5s | %7s %8s %6s %7s | %6s\n",
              "S", "nodes", "mesh s", "OCU s", "OCU ms", "control", "KiB/subs", "B/pair", "OCU B/sub", "mean", "max",
              "OCU", "refusd", "sent", "deliverd", "qdrop", "sent", "deliverd", "snt/nd", "rcvd/nd", "s");
}

void print_by_message(const RunFigures& f) {
  const double per_s = f.steady_s > 0 ? 1.0 / f.steady_s : 0;
  std::printf("  S=%d by message: discovery (messages sent, delivered), steady state (per second: sent, delivered, "
              "delivered per node)\n",
              f.subsystems);
  std::map<std::uint16_t, bool> codes;
  for (const auto* t : {&f.discovery, &f.steady})
    for (const auto& [code, n] : t->delivered_by_code)
      if (n > 0) codes[code] = true;
  const auto count = [](const std::map<std::uint16_t, std::uint64_t>& m, std::uint16_t code) {
    const auto it = m.find(code);
    return it == m.end() ? std::uint64_t{0} : it->second;
  };
  for (const auto& [code, unused] : codes) {
    std::printf("    %-26s %7llu %7llu   %7.1f %8.1f %7.2f\n", message_name(code).c_str(),
                static_cast<unsigned long long>(count(f.discovery.sent_by_code, code)),
                static_cast<unsigned long long>(count(f.discovery.delivered_by_code, code)),
                static_cast<double>(count(f.steady.sent_by_code, code)) * per_s,
                static_cast<double>(count(f.steady.delivered_by_code, code)) * per_s,
                static_cast<double>(count(f.steady.delivered_by_code, code)) * per_s / f.all_nodes);
  }
}

// ---- command line ---------------------------------------------------------------

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(std::stoi(item));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--subsystems") {
      o.subsystems = parse_list(value());
    } else if (arg == "--nodes") {
      o.nodes_per_subsystem = std::stoi(value());
    } else if (arg == "--ocus") {
      o.ocus = std::stoi(value());
    } else if (arg == "--fabric") {
      const std::string f = value();
      if (f == "routed") o.fabrics = {Fabric::routed};
      else if (f == "multicast") o.fabrics = {Fabric::multicast};
      else if (f == "both") o.fabrics = {Fabric::routed, Fabric::multicast};
      else throw std::invalid_argument("--fabric is routed, multicast or both");
    } else if (arg == "--latency-ms") {
      o.latency = std::chrono::microseconds(static_cast<std::int64_t>(std::stod(value()) * 1000));
    } else if (arg == "--jitter-us") {
      o.jitter = std::chrono::microseconds(std::stoll(value()));
    } else if (arg == "--steady-s") {
      o.steady = std::chrono::milliseconds(static_cast<std::int64_t>(std::stod(value()) * 1000));
    } else {
      throw std::invalid_argument("usage: bench_scale [--subsystems 10,50,100] [--nodes N] [--ocus N] "
                                  "[--fabric routed|multicast|both] [--latency-ms MS] [--jitter-us US] [--steady-s S]");
    }
  }
  if (o.nodes_per_subsystem < 1 || o.nodes_per_subsystem > 254) throw std::invalid_argument("--nodes is 1..254");
  if (o.ocus < 1 || o.ocus > 100) throw std::invalid_argument("--ocus is 1..100");
  for (const int s : o.subsystems)
    if (s < 2 || s > 254 - o.ocus)
      throw std::invalid_argument("--subsystems: each 2.." + std::to_string(254 - o.ocus) +
                                  " (the OCUs take the IDs from 254 down)");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::printf("bench_scale: S subsystems of %d node(s) each (node 1: node manager, communicator, primitive driver, "
                "global pose sensor; others: node manager, velocity state sensor), %d OCU(s) discovering them as "
                "jausctl discover does; heartbeats 1 Hz, network latency %.1f ms (+ up to %.0f us per message), "
                "virtual time\n",
                o.nodes_per_subsystem, o.ocus, seconds(o.latency) * 1000, seconds(o.jitter) * 1e6);
    std::printf("  converged: mesh, every vehicle node's subsystem list names every vehicle subsystem (from the "
                "network coming up for all at once); OCU, every OCU lists every subsystem, node and component, "
                "identified, with services (from its start; OCU ms: the real time that took in this process); control: "
                "the first OCU's Request Component Control of 1.1.33.1 afterwards\n");
    std::printf("  heap: bytes in use (operator new); KiB/subs: per subsystem as built; B/pair: growth while the "
                "vehicles learnt each other / (S*(S-1)); OCU B/sub: an OCU's growth while discovering / S\n");
    std::printf("  steady state: %.0f s after discovery, JAUS messages handed to the network (sent) and delivered "
                "to nodes, per node = / all nodes (OCUs included); refusd: liveness newcomers refused (table full), "
                "all nodes; qdrop: messages a full inbound queue dropped, all nodes, whole run\n",
                seconds(o.steady));
    for (const Fabric fabric : o.fabrics) {
      std::printf("\nfabric %s%s\n", fabric_name(fabric),
                  fabric == Fabric::routed ? " (a broadcast reaches the nodes it names: UDP, broadcast_to_peers)"
                                           : " (every broadcast reaches every node: UDP multicast group)");
      print_header();
      std::vector<RunFigures> runs;
      for (const int s : o.subsystems) {
        System system(o, fabric, s);
        runs.push_back(system.run());
        print_run(runs.back());
        std::fflush(stdout);
      }
      for (const auto& f : runs) print_by_message(f);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scale: %s\n", e.what());
    return 1;
  }
  return 0;
}
