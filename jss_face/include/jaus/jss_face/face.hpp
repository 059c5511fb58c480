// The JSS face of a node: SAE JAUS (AS5669A transport, AS5710 core, and the
// services the component kinds translate, components/<name>/jss/) spoken by
// the same components that speak RA 3.x. Sans-I/O: the
// transport hands it AS5669A datagrams and sends what it returns; the node's
// link hands it what the components send to JSS clients (FaceLink).
//
// One arbitration: a JSS client acts on an RA component through an RA alias
// address, `client_alias_subsystem`.<slot>.<client's component>.<channel>,
// slot 1-254 per JSS client node, channel 1 for the client's own messages and
// 2.. for its events' queries. So the RA component's controller, authority
// rule, emergency latch, controller timeout and liveness apply to JSS
// clients exactly as to RA ones; the face and the translators keep only what
// RA has no state for (events, registered services, a service's own tables)
// and translate.
// Each of our RA components is a JSS component (IDs: FaceConfig).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/log.hpp"
#include "jaus/core/header.hpp"
#include "jaus/core/large_message_assembler.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/sender_standing.hpp"

namespace jaus::jss_face {

struct FaceConfig {
  bool enabled = true;
  // JSS subsystem ID of this node's components (1..65534); default: the RA subsystem.
  std::optional<std::uint16_t> subsystem;
  // JSS component ID per RA component ID; components not listed keep their RA ID.
  std::map<std::uint8_t, std::uint8_t> component_ids;
  // The RA subsystem of JSS clients' aliases: no RA peer may use it.
  std::uint8_t client_alias_subsystem = 250;
  std::size_t max_clients = 64;             // JSS client nodes with an alias at once
  std::size_t max_events_per_client = 32;
  std::size_t max_events = 256;             // all clients together
  std::size_t max_registered_services = 256;  // Register Services entries kept
  rt::Duration change_poll_period = std::chrono::milliseconds(100);  // every-change events look this often
  std::uint8_t event_timeout_min = 1;       // Report Event Timeout (core v1.1); 0 = events never expire
  std::size_t max_packet_contents = 1400;   // larger contents go as a large message (data flags)
  // Report Identification (the node manager's identity) and Report Timeout.
  std::string subsystem_name = "jaus-node";
  std::uint16_t subsystem_type = 10001;     // JSS: 10001 vehicle, 20001 OCU, ...
  std::string node_name = "node";
  std::uint8_t controller_timeout_s = 3;    // Report Timeout: the RA components' controller timeout
};

struct FaceCounters {
  std::uint64_t datagrams_received = 0;
  std::uint64_t malformed = 0;            // bad AS5669A header, length, contents
  std::uint64_t not_for_us = 0;           // destination matches none of our JSS components
  std::uint64_t duplicates = 0;           // copies of a message delivered (ACKed, not acted on again)
  std::uint64_t new_sessions = 0;         // a client numbering again from its start: restarted
  std::uint64_t refused = 0;              // requests the face refused itself (Request Control from outside control_from)
  std::uint64_t unsupported = 0;          // a message ID no translator handles on that component
  std::uint64_t clients_refused = 0;      // no alias slot free (every slot's client holds state)
  std::uint64_t messages_to_ra = 0;
  std::uint64_t messages_to_jss = 0;
  std::uint64_t untranslated_from_ra = 0; // an RA message to an alias no translator took
  std::uint64_t acks_sent = 0;
  std::uint64_t large_messages_sent = 0;
  std::uint64_t large_messages_received = 0;
};

class JssFace {
 public:
  // Sends one AS5669A datagram to a JSS ID (the transport routes it: learnt
  // endpoint, else the JSS multicast group).
  using DatagramSender = std::function<void(const jss::JssId& to, std::span<const std::uint8_t> datagram)>;

  // `node` outlives the face; its clock and scheduler are the face's. The
  // face runs the core services itself; `services` are the rest, the
  // component kinds' (translator.hpp), asked in this order after the core's
  // (a node host passes host::jss_translators(): the built-in kinds', then its plugins').
  JssFace(FaceConfig config, const std::vector<TranslatorFactory>& services, node::Node& node, DatagramSender send,
          rt::LogFn log = {});
  ~JssFace();
  JssFace(const JssFace&) = delete;
  JssFace& operator=(const JssFace&) = delete;

  // Where a JSS client's datagrams come from ("a.b.c.d:port"; nullopt: not
  // known), so that log lines about a client name its host (jausd: the
  // transport's JSS route of the client's node).
  using ClientLocator = std::function<std::optional<std::string>(const jss::JssId& client)>;
  void locate_clients_with(ClientLocator locator);

  // A log line with each JSS client's alias address in it followed by the
  // client it stands for: "controlled by 250.1.1.1 (JSS client 42.1.1 at
  // 10.0.0.5:3794) (authority 5)". The RA components know a JSS client only
  // by its alias; jausd passes the node's log lines through this.
  std::string name_clients_in(const std::string& line) const;

  // One AS5669A datagram from the network, as the transport decoded it (its
  // transport messages, one sender's: UdpLink::on_jss_packets), with what the
  // transport knows of its sender.
  void receive_packets(std::span<const jss::JudpPacket> packets, rt::SenderStanding standing);
  // The same from its bytes (first byte 0x02): decoded here. For captures
  // and tests that hand the face datagrams without a transport.
  void receive(std::span<const std::uint8_t> datagram, rt::SenderStanding standing);
  // Whether an RA destination is a JSS client's alias (FaceLink asks).
  bool owns(const Address& ra_destination) const;
  // An RA message from a local component to a JSS client's alias.
  void from_node(const Header& header, std::span<const std::uint8_t> payload);

  // Whether a JSS client node (subsystem, node) holds state here: its alias
  // holds control, an emergency, a service connection, or it has events. The
  // transport pins its route meanwhile (UdpLink::pin_jss_routes_while).
  bool holds_state_for(std::uint16_t subsystem, std::uint8_t node) const;
  // The JSS client an alias address stands for (the client's component),
  // if the alias's slot is in use: who a hold under that alias belongs to.
  std::optional<jss::JssId> client_of_alias(const Address& alias) const;
  // Before anything is received (a restart, issue 42): the alias slot of a
  // JSS client node that held state before the restart is that node's
  // again, so no other client is given it (the caller binds the node's JSS
  // route to its host). false: the slot is beyond max_clients, or taken by
  // another client node.
  bool reserve_client(std::uint8_t slot, const jss::JssId& client_node);
  // Our JSS ID of a local RA component.
  std::optional<jss::JssId> jss_id_of(const Address& ra_component) const;
  const FaceConfig& config() const;
  const FaceCounters& counters() const;
  // Of the large messages received (the one assembler's: jaus/core/large_message_assembler.hpp).
  const AssemblyCounters& large_message_counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The node's link when the face is on: what is addressed to a JSS client's
// alias goes to the face, everything else to `inner` (UDP, or a memory link
// in tests). attach() the face once it exists (the node needs its link first).
class FaceLink final : public node::Link {
 public:
  explicit FaceLink(node::Link& inner) : inner_(inner) {}
  void attach(JssFace* face) { face_ = face; }
  void transmit(const Header& header, std::span<const std::uint8_t> packet) override {
    if (face_ != nullptr && face_->owns(header.destination)) {
      face_->from_node(header, packet.subspan(kHeaderSize));
      return;
    }
    inner_.transmit(header, packet);
  }

 private:
  node::Link& inner_;
  JssFace* face_ = nullptr;
};

}  // namespace jaus::jss_face
