#include "jaus/transport/framing.hpp"

#include <algorithm>
#include <string>

namespace jaus::transport {

namespace {
constexpr std::uint8_t kJudpVersion = 0x01;
}

std::string_view to_string(Framing framing) { return framing == Framing::judp ? "judp" : "opc"; }

std::string_view to_string(DropReason reason) {
  switch (reason) {
    case DropReason::unknown_framing: return "unknown framing";
    case DropReason::truncated: return "truncated";
    case DropReason::length_mismatch: return "length mismatch";
    case DropReason::bad_header: return "bad header";
    case DropReason::oversized: return "oversized";
    case DropReason::not_allowed: return "source not allowed";
    case DropReason::from_self: return "own datagram";
    case DropReason::invalid_source: return "invalid source ID";
    case DropReason::route_claim: return "node ID claimed from a second endpoint";
    case DropReason::count_: break;
  }
  return "unknown";
}

Expected<Unframed, FramingError> unframe(std::span<const std::uint8_t> datagram) {
  if (datagram.size() > kMaxDatagramSize)
    return unexpected(FramingError{DropReason::oversized, std::to_string(datagram.size()) + " bytes, at most " +
                                                              std::to_string(kMaxDatagramSize) + " are JAUS"});
  Framing framing;
  std::span<const std::uint8_t> message;
  if (datagram.size() >= kOpcPrefix.size() && std::equal(kOpcPrefix.begin(), kOpcPrefix.end(), datagram.begin())) {
    framing = Framing::opc;
    message = datagram.subspan(kOpcPrefix.size());
  } else if (!datagram.empty() && datagram[0] == kJudpVersion) {
    if (datagram.size() < kJudpPrefixSize)
      return unexpected(FramingError{DropReason::truncated, "JUDP prefix cut at " + std::to_string(datagram.size()) +
                                                                " bytes"});
    if (datagram[1] != 0 || datagram[2] != 0)
      return unexpected(FramingError{DropReason::unknown_framing, "JUDP header compression is not supported"});
    framing = Framing::judp;
    message = datagram.subspan(kJudpPrefixSize);
    const std::size_t declared = (std::size_t{datagram[3]} << 8) | datagram[4];
    if (declared != message.size())
      return unexpected(FramingError{DropReason::length_mismatch, "JUDP length " + std::to_string(declared) +
                                                                      ", datagram carries " +
                                                                      std::to_string(message.size()) + " bytes"});
  } else {
    return unexpected(FramingError{DropReason::unknown_framing, "neither \"JAUS01.0\" nor a JUDP prefix"});
  }
  if (message.size() < kHeaderSize)
    return unexpected(FramingError{DropReason::truncated, "message of " + std::to_string(message.size()) +
                                                              " bytes, a header needs 16"});
  auto packet = decode_packet(message);
  if (!packet) {
    const DropReason reason =
        packet.error().code == ErrorCode::data_size_mismatch ? DropReason::length_mismatch : DropReason::bad_header;
    return unexpected(FramingError{reason, packet.error().message()});
  }
  return Unframed{framing, *packet};
}

FramePrefix frame_prefix(Framing framing, std::size_t message_size) {
  FramePrefix p;
  if (framing == Framing::opc) {
    std::copy(kOpcPrefix.begin(), kOpcPrefix.end(), p.bytes.begin());
    p.size = kOpcPrefix.size();
  } else {
    p.bytes = {kJudpVersion, 0x00, 0x00, static_cast<std::uint8_t>(message_size >> 8),
               static_cast<std::uint8_t>(message_size & 0xFF)};
    p.size = kJudpPrefixSize;
  }
  return p;
}

}  // namespace jaus::transport
