// How the JSS face's services are written (the contract between the face and
// each service's translator; the face itself: face.hpp).
//
// The face keeps the RA components the only state of the vehicle: a JSS
// client reaches an RA component through an RA alias address (face.hpp), so
// control, authority, emergency holds and the lifecycle are the RA
// component's, one arbitration for both dialects. A translator turns the JSS
// messages of its services into RA messages to the component (send_ra) and
// the component's RA replies to the alias back into JSS (reply); what the RA
// has no message for (discovery's service URIs, event tables, a list's
// elements) it keeps and answers itself, with reply().
//
// ReplyTo names where an answer goes: the client, or one of its events. The
// event engine asks a query through the same from_jss() with origin.event_id
// set, so every query a translator answers can also be an event's; reply()
// wraps the report in Event for it.
//
// The face itself runs the core services (core v1.1); every other service is
// a component kind's, in its folder (components/<name>/jss/), written with the
// helpers of translator_kit.hpp, report_translator.hpp and scaling.hpp, and
// handed to the face as a TranslatorFactory (JssFace's constructor).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"
#include "jaus/core/address.hpp"
#include "jaus/core/header.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/runtime/sender_standing.hpp"

namespace jaus::node {
class Node;
}

namespace jaus::jss_face {

struct FaceConfig;

// Where an answer goes: a JSS client directly, or one of its events.
struct ReplyTo {
  jss::JssId client;
  std::optional<std::uint8_t> event_id;  // set: the answer is wrapped in that event's Event message
  bool operator==(const ReplyTo&) const = default;
};

// A JSS message for one of our components (the face has expanded wildcards:
// one JssInbound per component it reaches).
struct JssInbound {
  jss::JssId our_component;      // the JSS ID of our component it is for
  Address ra_component;          // the RA component behind that JSS ID
  ReplyTo origin;                // who asked, and for what (a client's own message, or its event)
  std::uint16_t message_id = 0;  // the JSS message ID (first two bytes of the contents)
  std::span<const std::uint8_t> body;  // the contents after the message ID
  rt::SenderStanding standing = rt::SenderStanding::trusted;  // what the transport knows of the client
  std::uint8_t priority = 1;     // AS5669A priority 0-3
};

// An RA message from one of our components to a JSS client's alias.
struct RaOutbound {
  const Header& header;                    // source: our RA component; destination: the alias
  std::span<const std::uint8_t> payload;   // RA payload (after the 16-byte header)
  jss::JssId our_component;                // the JSS ID of the source component
  ReplyTo to;                              // the client (and event) the alias stands for
};

// A service as discovery reports it (docs/jss.md, "What is supported").
struct ServiceUri {
  std::string uri;  // "urn:jaus:jss:core:AccessControl"
  std::uint8_t major = 1;
  std::uint8_t minor = 0;
  bool operator==(const ServiceUri&) const = default;
};

// What the face offers a translator.
class FacePort {
 public:
  virtual ~FacePort() = default;
  // Hands `ra_component` an RA message as sent by origin's alias; the node
  // acts on it with `standing` (controller checks, emergency holders and
  // liveness are the alias's, hence the client's).
  virtual void send_ra(const ReplyTo& origin, const Address& ra_component, std::uint16_t ra_code,
                       std::span<const std::uint8_t> ra_payload, rt::SenderStanding standing) = 0;
  // Sends JSS contents (u16 message ID, then the body) from our component to
  // `to`: directly, or wrapped in Event when to.event_id is set.
  virtual void reply(const ReplyTo& to, const jss::JssId& our_component, std::span<const std::uint8_t> contents) = 0;
  // Our JSS ID of an RA component of this node (nullopt: not one of ours).
  virtual std::optional<jss::JssId> jss_id_of(const Address& ra_component) const = 0;
  // The JSS ID an RA address stands for: a client's alias -> the client, one
  // of our components -> its JSS ID, any other RA address -> the same numbers
  // (16-bit subsystem), for Report Control and the like.
  virtual jss::JssId jss_id_for(const Address& ra_address) const = 0;
  virtual const FaceConfig& config() const = 0;
  virtual rt::Clock& clock() = 0;
  virtual rt::Scheduler& scheduler() = 0;
  // The node, for state the RA has no message for (a component's state
  // no RA report carries): read it, never command through it.
  virtual node::Node& node() = 0;
  virtual void log(rt::LogLevel level, const std::string& text) = 0;
  // The services every registered translator lists for a component with
  // this RA component ID, in registration order (Discovery's reports).
  virtual std::vector<ServiceUri> services_of(std::uint8_t ra_component_id) const {
    (void)ra_component_id;
    return {};
  }
  // A client as log lines name it: its own JSS ID, its host when the
  // transport knows it, and its RA alias when it has one ("JSS client
  // 42.1.1 at 10.0.0.5:3794 (alias 250.1.1.1)").
  virtual std::string describe_client(const jss::JssId& client) const { return "JSS client " + client.to_string(); }
  // A request of `client` the face refuses itself (`what` it asked, `why`
  // not): counted (FaceCounters::refused) and logged (repeat-limited) with
  // the client described as above.
  virtual void refused(const jss::JssId& client, const std::string& what, const std::string& why) {
    log(rt::LogLevel::info, what + " from " + describe_client(client) + " refused: " + why);
  }
  // A JSS message whose body does not decode: counted (FaceCounters::
  // malformed) and logged (repeat-limited) with what and why; never acted on.
  virtual void malformed(const std::string& what, const std::string& why) {
    log(rt::LogLevel::warn, "malformed " + what + " ignored: " + why);
  }
};

// One or more JSS services of a component.
class ServiceTranslator {
 public:
  virtual ~ServiceTranslator() = default;
  virtual std::string_view name() const = 0;  // "access control", for logs
  // The services it adds to a component with this RA component ID (empty:
  // none), for Report Services / Report Service List.
  virtual std::vector<ServiceUri> services(std::uint8_t ra_component_id) const = 0;
  // Whether it answers this JSS message ID on a component with this RA
  // component ID (the event engine rejects events on other queries).
  virtual bool handles(std::uint16_t message_id, std::uint8_t ra_component_id) const = 0;
  // A JSS message to our component: true when it was this translator's.
  virtual bool from_jss(const JssInbound& message, FacePort& port) = 0;
  // An RA message from our component to a client's alias: true when it was
  // this translator's to translate.
  virtual bool from_ra(const RaOutbound& message, FacePort& port) = 0;
  // The client is forgotten (its alias ends): drop what is kept for it.
  // `client` names a client node: component 255 (every component of it).
  virtual void forget(const jss::JssId& client) { (void)client; }
};

// A component kind's JSS services: its translators, in the order the face
// asks them (the first whose from_jss()/from_ra() returns true wins).
using Translators = std::vector<std::unique_ptr<ServiceTranslator>>;
// What a kind hands the face: its translators for a face with this
// configuration (called once, when the face is made).
using TranslatorFactory = Translators (*)(const FaceConfig& config);

}  // namespace jaus::jss_face
