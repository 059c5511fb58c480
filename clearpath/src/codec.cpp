#include "jaus/clearpath/codec.hpp"

#include "detail/payload_reader.hpp"
#include "detail/payload_writer.hpp"
#include "detail/range_checker.hpp"

namespace jaus::clearpath {

Expected<std::vector<std::uint8_t>> encode_payload(const AnyMessage& message) {
  std::vector<std::uint8_t> out;
  detail::PayloadWriter writer(out);
  visit([&](const auto& m) { std::remove_cvref_t<decltype(m)>::describe(m, writer); }, message);
  if (writer.error) return unexpected(*writer.error);
  if (out.size() > kMaxPayload)
    return unexpected(Error{ErrorCode::payload_too_large, out.size(), "",
                 std::to_string(out.size()) + " bytes, at most " + std::to_string(kMaxPayload)});
  return out;
}

Expected<AnyMessage> decode_payload(std::uint16_t type, std::span<const std::uint8_t> payload, Direction direction) {
  const MessageKind kind = kind_of(type);
  const bool is_ack =
      direction == Direction::from_platform && (kind == MessageKind::command || kind == MessageKind::request);
  std::optional<AnyMessage> message = is_ack ? std::optional<AnyMessage>(Ack{}) : make_message(type);
  if (!message) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%04X", type);
    return unexpected(Error{ErrorCode::unknown_message, 0, "", hex});
  }
  detail::PayloadReader reader(payload);
  visit(
      [&](auto& m) {
        using M = std::remove_cvref_t<decltype(m)>;
        if constexpr (requires { M::prepare_decode(m, payload.size()); }) M::prepare_decode(m, payload.size());
        M::describe(m, reader);
      },
      *message);
  if (reader.error) return unexpected(*reader.error);
  if (reader.remaining() != 0)
    return unexpected(Error{ErrorCode::trailing_bytes, reader.position(), "",
                 std::to_string(reader.remaining()) + " bytes after the last field"});
  return std::move(*message);
}

Expected<std::size_t> append_encoded(std::vector<std::uint8_t>& out, const Envelope& envelope) {
  auto payload = encode_payload(envelope.message);
  if (!payload) return unexpected(payload.error());
  FrameHeader header = envelope.header;
  if (const auto type = type_of(envelope.message)) header.type = *type;
  return append_frame(out, header, *payload);
}

Expected<std::vector<std::uint8_t>> encode(const Envelope& envelope) {
  std::vector<std::uint8_t> out;
  auto written = append_encoded(out, envelope);
  if (!written) return unexpected(written.error());
  return out;
}

Expected<Envelope> decode(const Frame& frame, Direction direction) {
  auto message = decode_payload(frame.header.type, frame.payload, direction);
  if (!message) {
    Error e = message.error();
    e.offset += kFrameHeaderSize;  // report positions within the frame
    return unexpected(std::move(e));
  }
  return Envelope{frame.header, std::move(*message)};
}

Expected<void> check_ranges(const AnyMessage& message) {
  detail::RangeChecker checker;
  visit([&](const auto& m) { std::remove_cvref_t<decltype(m)>::describe(m, checker); }, message);
  if (checker.error) return unexpected(std::move(*checker.error));
  return {};
}

}  // namespace jaus::clearpath
