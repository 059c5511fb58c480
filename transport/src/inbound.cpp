#include "jaus/transport/inbound.hpp"

#include "jaus/core/stop_commands.hpp"

namespace jaus::transport {

bool is_stop(std::uint16_t code) { return is_stop_command(code); }

bool is_command(std::uint16_t code) { return code < 0x2000; }

namespace {

bool is_later_piece(const jss::JudpHeader& header) {
  return header.data_flag == jss::JudpDataFlag::middle || header.data_flag == jss::JudpDataFlag::last;
}

// The message ID of an AS5669A transport message (the first two bytes of its
// contents); none for an ACK or NAK (header only), a later piece of a large
// message (its contents go on from the piece before) or contents too short.
std::optional<std::uint16_t> jss_message_id(const jss::JudpPacket& packet) {
  if (packet.header.ack_nak == jss::JudpAckNak::ack || packet.header.ack_nak == jss::JudpAckNak::nak ||
      is_later_piece(packet.header) || packet.contents.size() < 2)
    return std::nullopt;
  return jss::message_id_of(packet.contents);
}

void classify(Inbound& in, std::uint16_t code) {
  if (!is_command(code)) return;
  if (is_stop(code)) {
    in.carries_stop = true;
  } else if (!in.carries_command) {
    in.carries_command = true;
    in.command_code = code;
  }
}

Expected<Inbound> decode_ra(std::span<const std::uint8_t> datagram) {
  auto unframed = unframe(datagram);
  if (!unframed) return unexpected(unframed.error());
  Inbound in;
  in.framing = unframed->framing;
  in.ra = unframed->packet;
  const Header& h = in.ra.header;
  in.subsystem = h.source.subsystem;
  in.node = h.source.node;
  in.one_sender = h.source.is_valid() && !h.source.is_broadcast();
  in.is_answer = h.ack_nak == AckNak::ack || h.ack_nak == AckNak::nak;
  if (!in.is_answer) classify(in, h.command_code);
  return in;
}

Expected<Inbound> decode_jss(std::span<const std::uint8_t> datagram) {
  auto packets = jss::decode_judp_datagram(datagram);
  if (!packets) return unexpected(packets.error());
  if (packets->empty()) return unexpected(make_error(ErrorCode::truncated, "no transport message"));
  // One sender per datagram: every message in it must name the same source
  // (nobody packs several; a mix would let one claim ride on another's route).
  const jss::JssId source = packets->front().header.source;
  for (const auto& packet : *packets)
    if (packet.header.source != source)
      return unexpected(make_error(ErrorCode::bad_frame, "messages from " + source.to_string() + " and " +
                                                             packet.header.source.to_string() + " in one datagram"));
  Inbound in;
  in.framing = Framing::as5669a;
  in.subsystem = source.subsystem;
  in.node = source.node;
  in.one_sender = source.is_valid() && !source.is_broadcast();
  const auto first = packets->front().header.ack_nak;
  in.is_answer = first == jss::JudpAckNak::ack || first == jss::JudpAckNak::nak;
  for (const auto& packet : *packets) {
    if (const auto id = jss_message_id(packet)) {
      classify(in, *id);
    } else if (is_later_piece(packet.header) && !in.is_answer) {
      // Safety (issue 43): a later piece may complete a command whose ID
      // came in an earlier datagram, so it is taken for one (its code
      // unknown): it needs its reply's budget as any command does. No stop
      // is ever that large.
      in.carries_command = true;
    }
  }
  in.jss = std::move(*packets);
  return in;
}

}  // namespace

std::string Inbound::source_text() const {
  if (framing == Framing::as5669a) return jss.empty() ? std::string("?") : jss.front().header.source.to_string();
  return ra.header.source.to_string();
}

Expected<Inbound> decode_datagram(std::span<const std::uint8_t> datagram) {
  auto in = !datagram.empty() && datagram[0] == jss::kAs5669aVersion ? decode_jss(datagram) : decode_ra(datagram);
  if (in) in->bytes = datagram;
  return in;
}

DropReason drop_reason(std::span<const std::uint8_t> datagram, const Error& decode_error) {
  if (!datagram.empty() && datagram[0] == jss::kAs5669aVersion) return DropReason::jss_malformed;
  return drop_reason(decode_error);
}

}  // namespace jaus::transport
