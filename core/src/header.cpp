#include "jaus/core/header.hpp"

#include <string>

#include "jaus/core/byte_io.hpp"

namespace jaus {

namespace {
void write_address(ByteWriter& w, const Address& a) {
  // Wire order is instance, component, node, subsystem.
  w.write(a.instance);
  w.write(a.component);
  w.write(a.node);
  w.write(a.subsystem);
}

Address read_address(ByteReader& r) {
  Address a;
  r.read(a.instance);
  r.read(a.component);
  r.read(a.node);
  r.read(a.subsystem);
  return a;
}

bool is_known_data_flag(unsigned flag) { return flag == 0 || flag == 1 || flag == 2 || flag == 4 || flag == 8; }
}  // namespace

void encode_header_unchecked(const Header& h, std::span<std::uint8_t, kHeaderSize> out) {
  ByteWriter w(out);
  const auto properties = static_cast<std::uint16_t>(
      (h.priority & 0x0F) | ((static_cast<unsigned>(h.ack_nak) & 0x03) << 4) | (h.service_connection ? 0x40 : 0) |
      (h.experimental ? 0x80 : 0) | ((h.version & 0x3F) << 8));
  w.write(properties);
  w.write(h.command_code);
  write_address(w, h.destination);
  write_address(w, h.source);
  w.write(static_cast<std::uint16_t>((h.data_size & 0x0FFF) | ((static_cast<unsigned>(h.data_flag) & 0x0F) << 12)));
  w.write(h.sequence);
}

Expected<std::array<std::uint8_t, kHeaderSize>, Error> encode_header(const Header& h) {
  auto fail = [](std::string_view field, ErrorCode code, std::string detail) {
    return unexpected(Error{code, 0, field, std::move(detail)});
  };
  if (h.priority > 15) return fail("priority", ErrorCode::bad_value, "0-15");
  if (static_cast<unsigned>(h.ack_nak) > 3) return fail("ack_nak", ErrorCode::bad_value, "0-3");
  if (h.version > 0x3F) return fail("version", ErrorCode::bad_value, "0-63");
  if (h.data_size > kMaxPayloadSize) return fail("data_size", ErrorCode::data_size_too_large, {});
  if (!is_known_data_flag(static_cast<unsigned>(h.data_flag))) return fail("data_flag", ErrorCode::bad_data_flag, {});
  std::array<std::uint8_t, kHeaderSize> out{};
  encode_header_unchecked(h, out);
  return out;
}

Expected<Header, Error> decode_header(std::span<const std::uint8_t> bytes) {
  ByteReader r(bytes);
  Header h;
  std::uint16_t properties = 0;
  std::uint16_t data_control = 0;
  r.set_field("header");
  r.read(properties);
  r.read(h.command_code);
  h.destination = read_address(r);
  h.source = read_address(r);
  r.read(data_control);
  r.read(h.sequence);
  if (r.failed()) return unexpected(*r.error());

  h.priority = properties & 0x0F;
  h.ack_nak = static_cast<AckNak>((properties >> 4) & 0x03);
  h.service_connection = (properties & 0x40) != 0;
  h.experimental = (properties & 0x80) != 0;
  h.version = static_cast<std::uint8_t>((properties >> 8) & 0x3F);
  h.data_size = data_control & 0x0FFF;
  const unsigned flag = data_control >> 12;

  if (h.version != kVersionRa30 && h.version != kVersionRa32)
    return unexpected(Error{ErrorCode::unsupported_version, 1, "version",
                            std::to_string(h.version) + ", expected 1 (RA 3.0/3.1) or 2 (RA 3.2/3.3)"});
  if (!is_known_data_flag(flag))
    return unexpected(Error{ErrorCode::bad_data_flag, 13, "data_flag", std::to_string(flag)});
  if (h.data_size > kMaxPayloadSize)
    return unexpected(Error{ErrorCode::data_size_too_large, 12, "data_size", std::to_string(h.data_size)});
  h.data_flag = static_cast<DataFlag>(flag);
  return h;
}

Expected<PacketView, Error> decode_packet(std::span<const std::uint8_t> bytes) {
  auto header = decode_header(bytes);
  if (!header) return unexpected(header.error());
  const std::size_t payload_size = bytes.size() - kHeaderSize;
  if (header->data_size != payload_size)
    return unexpected(Error{ErrorCode::data_size_mismatch, 12, "data_size",
                            "header says " + std::to_string(header->data_size) + " bytes, packet carries " +
                                std::to_string(payload_size)});
  return PacketView{*header, bytes.subspan(kHeaderSize)};
}

}  // namespace jaus
