#include "jaus/transport/framing.hpp"

#include <algorithm>
#include <string>

namespace jaus::transport {

namespace {
constexpr std::uint8_t kJudpVersion = 0x01;
}

std::string_view to_string(Framing framing) {
  switch (framing) {
    case Framing::opc: return "opc";
    case Framing::judp: return "judp";
    case Framing::as5669a: return "as5669a";
  }
  return "unknown";
}

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
    case DropReason::relayed_copy: return "relayed copy of a direct message";
    case DropReason::jss_malformed: return "malformed AS5669A datagram";
    case DropReason::jss_off: return "AS5669A datagram with JSS off";
    case DropReason::alias_source: return "source in the JSS clients' alias subsystem";
    case DropReason::count_: break;
  }
  return "unknown";
}

namespace {
Error unframing_error(ErrorCode code, std::size_t offset, std::string detail) {
  return Error{code, offset, {}, std::move(detail)};
}
}  // namespace

Expected<Unframed> unframe(std::span<const std::uint8_t> datagram) {
  if (datagram.size() > kMaxDatagramSize)
    return unexpected(unframing_error(ErrorCode::payload_too_large, kMaxDatagramSize,
                                      std::to_string(datagram.size()) + " bytes, at most " +
                                          std::to_string(kMaxDatagramSize) + " are JAUS"));
  Framing framing;
  std::size_t prefix_size;
  if (datagram.size() >= kOpcPrefix.size() && std::equal(kOpcPrefix.begin(), kOpcPrefix.end(), datagram.begin())) {
    framing = Framing::opc;
    prefix_size = kOpcPrefix.size();
  } else if (!datagram.empty() && datagram[0] == kJudpVersion) {
    if (datagram.size() < kJudpPrefixSize)
      return unexpected(unframing_error(ErrorCode::truncated, datagram.size(),
                                        "JUDP prefix cut at " + std::to_string(datagram.size()) + " bytes"));
    if (datagram[1] != 0 || datagram[2] != 0)
      return unexpected(unframing_error(ErrorCode::bad_frame, 1, "JUDP header compression is not supported"));
    framing = Framing::judp;
    prefix_size = kJudpPrefixSize;
    const std::size_t declared = (std::size_t{datagram[3]} << 8) | datagram[4];
    if (declared != datagram.size() - prefix_size)
      return unexpected(unframing_error(ErrorCode::data_size_mismatch, 3,
                                        "JUDP length " + std::to_string(declared) + ", datagram carries " +
                                            std::to_string(datagram.size() - prefix_size) + " bytes"));
  } else {
    return unexpected(unframing_error(ErrorCode::bad_frame, 0, "neither \"JAUS01.0\" nor a JUDP prefix"));
  }
  const auto message = datagram.subspan(prefix_size);
  if (message.size() < kHeaderSize)
    return unexpected(unframing_error(ErrorCode::truncated, datagram.size(),
                                      "message of " + std::to_string(message.size()) + " bytes, a header needs 16"));
  auto packet = decode_packet(message);
  if (!packet) {
    Error error = packet.error();
    error.offset += prefix_size;  // in the datagram, not the message
    return unexpected(std::move(error));
  }
  return Unframed{framing, *packet};
}

DropReason drop_reason(const Error& unframe_error) {
  switch (unframe_error.code) {
    case ErrorCode::payload_too_large: return DropReason::oversized;
    case ErrorCode::truncated: return DropReason::truncated;
    case ErrorCode::bad_frame: return DropReason::unknown_framing;
    case ErrorCode::data_size_mismatch: return DropReason::length_mismatch;
    default: return DropReason::bad_header;  // version, data size over 4080, data flag
  }
}

FramePrefix frame_prefix(Framing framing, std::size_t message_size) {
  FramePrefix p;
  if (framing == Framing::as5669a) return p;  // the datagram is complete
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
