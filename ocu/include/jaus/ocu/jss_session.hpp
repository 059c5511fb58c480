// A SAE JAUS (JSS) operator unit as a library: one JSS endpoint of its own
// speaking AS5669A (docs/jss.md, "The bytes on the wire") on the node's UDP
// transport (transport::UdpLink: one receive path, routes learnt per JSS
// node, the multicast group, static peers), with what a JSS client
// needs to drive a JSS vehicle: sequence numbers, ACK answers to
// ACK-requested messages, large message reassembly, requests resent until
// answered, commands resent until ACKed, and listeners for what arrives
// unasked (Reject Control, Events). Discovery, control and events build on
// it (jss_discovery.hpp, jss_control.hpp, jss_events.hpp).
//
// Two ways to open one, as OcuSession: open() on UDP on an io_context
// (jausctl, jaus-conform); attach() on an injected clock, scheduler and
// datagram path (tests: a JssFace on virtual time, no socket). Listening,
// waiting for replies, the run loop and the stop request are SessionCore's
// (session_core.hpp), as the RA session's.
//
// Single-threaded: everything runs on the thread that calls run_until(),
// but request_stop().
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss/large_message.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/session_core.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::ocu {

// JSS subsystems count up from 1 for vehicles; 200 keeps an operator unit
// clear of them (and of the RA OCU's 254). Node 1, component 1.
inline constexpr jss::JssId kDefaultJssOcuId{200, 1, 1};
// Where JSS nodes (JRM, fkie IOP, jausd's face) send broadcasts and messages
// to IDs they have not heard from.
inline constexpr transport::Ipv4Endpoint kJssMulticastGroup{0xEFFF0001, transport::kJausPort};  // 239.255.0.1
inline constexpr jss::JssId kJssBroadcast{jss::JssId::kAllSubsystems, jss::JssId::kAll, jss::JssId::kAll};
inline constexpr rt::Duration kJssDefaultTimeout = std::chrono::seconds(1);

struct JssSessionOptions {
  jss::JssId self = kDefaultJssOcuId;
  // Static peers: messages to IDs not heard from yet, and broadcasts, go to
  // each (and to the multicast group, when set). Heard IDs are answered at
  // the endpoint they were heard from.
  std::vector<transport::Ipv4Endpoint> to{{0x7F000001, transport::kJausPort}};
  transport::Ipv4Endpoint bind{0, 0};  // any address, any free port
  // The JSS multicast group (kJssMulticastGroup): joined, and used as `to`
  // is. Best effort: a host without a multicast route logs and goes on.
  std::optional<transport::Ipv4Endpoint> multicast;
  // What we answer to Query Identification (type 4, and 2/3 for our own
  // subsystem and node): JSS type 20001 is an OCU.
  std::string name = "jausctl";
  std::uint16_t identification_type = 20001;
  // The first sequence number. JSS nodes drop a message whose source and
  // sequence number they saw in the last 10 s as a duplicate (answered, not
  // acted on), so two runs of one JSS ID must not both start at 0 (a Clear
  // Emergency right after the run that set it would be dropped). None: a
  // random one on UDP, 0 when attached (tests stay deterministic).
  std::optional<std::uint16_t> first_sequence;
  // Larger contents go as a large message (first/middle/last packets).
  std::size_t max_packet_contents = jss::kDefaultMaxPacketContents;
  // Large messages received, put together in any order: bounded in number,
  // bytes and time (dropped ones are counted).
  AssemblyLimits reassembly = jss::JudpLargeMessages::kDefaultLimits;
  // JSS nodes whose endpoint is remembered (the transport's route table:
  // newcomers beyond it are not recorded, silent ones forgotten after 30 s).
  std::size_t max_learnt_endpoints = 1024;
  // How long and how often a message that must arrive is sent again, and
  // the round-trip bounds of its pace (must_arrive_settings.hpp).
  MustArriveSettings must_arrive{};
  rt::LogFn log;
};

// What an attached session runs on instead of a socket and an io_context.
struct JssEnvironment {
  rt::Clock* clock = nullptr;
  rt::Scheduler* scheduler = nullptr;
  // Where the session's datagrams go (a JssFace's receive, in tests).
  std::function<void(const jss::JssId& to, std::span<const std::uint8_t> datagram)> transmit;
  // Hands the environment what takes each datagram for the session; called
  // once by attach(), and with an empty function when the session goes.
  std::function<void(std::function<void(std::span<const std::uint8_t>)>)> connect;
  // Lets time pass up to `until` at most (jaus::testing::stepper).
  std::function<void(rt::TimePoint until)> wait;
};

// A JSS message addressed to us (or broadcast), reassembled when large.
struct JssReceived {
  jss::JudpHeader header;              // of its (first) packet
  std::vector<std::uint8_t> contents;  // u16 message ID, then the body
  std::uint16_t message_id() const { return jss::message_id_of(contents); }
  const jss::JssId& source() const { return header.source; }
  std::uint16_t code() const { return message_id(); }
};

struct JssSessionCounters {
  std::uint64_t datagrams_sent = 0;
  std::uint64_t datagrams_received = 0;
  std::uint64_t malformed = 0;          // not AS5669A, or a bad header (logged, rate-limited)
  std::uint64_t not_for_us = 0;         // destination matches neither us nor a broadcast
  std::uint64_t messages_received = 0;  // delivered to listeners
  std::uint64_t acks_sent = 0;
  std::uint64_t acks_received = 0;
  std::uint64_t large_messages_sent = 0;
  std::uint64_t large_messages_received = 0;
  std::uint64_t large_messages_dropped = 0;  // stray packets, too large, timed out, refused (logged)
};

class JssSession : public SessionCore<JssReceived> {
 public:

  // Binds the socket (joins the multicast group). `io` null: its own.
  // Errors (io, invalid_argument) in one line: "0.0.0.0:3794 is already in use".
  static Expected<std::unique_ptr<JssSession>> open(JssSessionOptions options, boost::asio::io_context* io = nullptr);
  // Errors: an invalid or broadcast ID, an environment with something missing.
  static Expected<std::unique_ptr<JssSession>> attach(JssSessionOptions options, JssEnvironment environment);
  ~JssSession();

  const jss::JssId& self() const;
  const JssSessionOptions& options() const;
  const JssSessionCounters& counters() const;
  // The endpoint `id`'s node was last heard from (UDP only).
  std::optional<transport::Ipv4Endpoint> endpoint_of(const jss::JssId& id) const;

  // Sends contents (message ID + body) to `to`, split into a large message
  // when above max_packet_contents. Returns the sequence number of its
  // (first) packet. Broadcast IDs go without ACK request.
  std::uint16_t send_contents(const jss::JssId& to, std::span<const std::uint8_t> contents,
                              jss::JudpPriority priority = jss::JudpPriority::normal, bool ack_requested = false);
  template <class M>
  std::uint16_t send(const jss::JssId& to, const M& message, jss::JudpPriority priority = jss::JudpPriority::normal) {
    const auto contents = jss::encode_contents(message);
    return send_contents(to, contents, priority);
  }

  // With an ACK request, the same packet (same sequence number) again per
  // `policy` (must_arrive.hpp: at the pace of the round trip measured to
  // `to`'s node; none: the session's must_arrive settings for the message's
  // ID, a stop trying harder than a command) until `to` ACKs (or NAKs: refused) it. A
  // broadcast ID is sent policy.max_transmissions times, policy.
  // retransmit_after apart, and is `unacknowledged`. Contents above max_packet_contents cannot be
  // acknowledged as one packet: unacknowledged, nothing sent.
  ArrivalResult send_contents_must_arrive(const jss::JssId& to, std::span<const std::uint8_t> contents,
                                          jss::JudpPriority priority = jss::JudpPriority::normal,
                                          std::optional<MustArrivePolicy> policy = std::nullopt);
  // The same, going on after request_stop() (clean-up: Release Control).
  ArrivalResult send_contents_must_arrive_through_stop(const jss::JssId& to, std::span<const std::uint8_t> contents,
                                                       jss::JudpPriority priority = jss::JudpPriority::normal,
                                                       std::optional<MustArrivePolicy> policy = std::nullopt);
  template <class M>
  ArrivalResult send_must_arrive(const jss::JssId& to, const M& message,
                                 jss::JudpPriority priority = jss::JudpPriority::normal,
                                 std::optional<MustArrivePolicy> policy = std::nullopt) {
    const auto contents = jss::encode_contents(message);
    return send_contents_must_arrive(to, contents, priority, policy);
  }

  // (SessionCore's listen() hears every message addressed to us, or to a
  // broadcast ID that matches us, after the session answered its ACK
  // request; await_reply() the first from an ID, wildcards matching any.)

  // Sends the query now and every `resend_every` until a reply comes (at most `timeout`).
  Expected<JssReceived> request_contents(const jss::JssId& to, std::span<const std::uint8_t> query,
                                         std::vector<std::uint16_t> reply_ids,
                                         rt::Duration timeout = kJssDefaultTimeout,
                                         rt::Duration resend_every = kQueryResendPeriod);
  // Typed: query<msg::ReportStatus>(to, msg::QueryStatus{}). Errors as
  // request_contents, or the reply's decode error.
  template <class Reply, class Query>
  Expected<Reply> query(const jss::JssId& to, const Query& query, rt::Duration timeout = kJssDefaultTimeout,
                        rt::Duration resend_every = kQueryResendPeriod) {
    const auto contents = jss::encode_contents(query);
    auto reply = request_contents(to, contents, {Reply::code}, timeout, resend_every);
    if (!reply) return unexpected(reply.error());
    return jss::decode_contents<Reply>(reply->contents);
  }

  // An attached session's environment hands datagrams here (open() wires its link itself).
  void receive_datagram(std::span<const std::uint8_t> datagram);

 private:
  struct Impl;
  explicit JssSession(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace jaus::ocu
