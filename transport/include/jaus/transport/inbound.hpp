// One received datagram, decoded once whatever its framing (docs/wire-format.md,
// "Node-to-node transport"; docs/jss.md, "Transport: one port, three
// framings"): OPC and JUDP carry one RA message, AS5669A one or more SAE JAUS
// transport messages of one sender. The UDP link applies one set of rules to
// what this says (udp_link.cpp, on_datagram: allow-list, own datagrams, source
// checks, route claims, endpoint verification, standing) and hands the
// decoded messages on: the RA node and the JSS face never parse the bytes
// again. Sans-I/O.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/transport/framing.hpp"

namespace jaus::transport {

// The two ID spaces a sender can be named in: RA (subsystem 1-254, node) or
// SAE JAUS (subsystem 1-65534, node). The link keeps a route table and an
// endpoint guard for each: one peer may be a node in both.
enum class IdSpace : std::uint8_t { ra, jss };
inline constexpr IdSpace id_space_of(Framing framing) {
  return framing == Framing::as5669a ? IdSpace::jss : IdSpace::ra;
}

struct Inbound {
  std::span<const std::uint8_t> bytes;  // the whole datagram
  Framing framing = Framing::opc;
  // The sender's node, in the ID space of the framing.
  std::uint16_t subsystem = 0;
  std::uint8_t node = 0;
  // No 0 (invalid) or broadcast octet: one sender, who can be answered.
  bool one_sender = false;
  // OPC, JUDP: the message (header decoded, payload a view into the datagram).
  PacketView ra;
  // AS5669A: its transport messages, in order (contents view the datagram).
  std::vector<jss::JudpPacket> jss;

  // What it asks of the node, for the endpoint rules (amplification_guard.hpp):
  // an answer (ACK or NAK) acts on nothing; a command acts and may be
  // answered; a stop (Shutdown, Standby, Set Emergency) always acts.
  bool is_answer = false;      // the (first) message is an ACK or NAK
  bool carries_command = false;  // a command other than a stop
  bool carries_stop = false;
  std::uint16_t command_code = 0;  // the first command other than a stop (for log lines)

  IdSpace id_space() const { return id_space_of(framing); }
  // The sender as a log line names it: "1.1.40.1" (RA), "42.1.1" (JSS).
  std::string source_text() const;
};

// Detects the framing (a first byte 0x02 is AS5669A), checks it and decodes
// the header(s). An error's offset is in the datagram; drop_reason() names
// the counter it counts in.
Expected<Inbound> decode_datagram(std::span<const std::uint8_t> datagram);
// The counter a decode_datagram() error of `datagram` counts in.
DropReason drop_reason(std::span<const std::uint8_t> datagram, const Error& decode_error);

// The message classes the endpoint rules tell apart (RA and AS5669A alike).
// Stops: Shutdown, Standby, Set Emergency.
bool is_stop(std::uint16_t code);
// The command class (0x0000-0x1FFF).
bool is_command(std::uint16_t code);

}  // namespace jaus::transport
