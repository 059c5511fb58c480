#include "jaus/core/header.hpp"

#include <string>

#include "jaus/core/byte_io.hpp"

namespace jaus {

Expected<std::array<std::uint8_t, kHeaderSize>, Error> encode_header(const Header& h) {
  auto fail = [](std::string_view field, ErrorCode code, std::string detail) {
    return unexpected(Error{code, 0, std::string(field), std::move(detail)});
  };
  if (h.priority > 15) return fail("priority", ErrorCode::bad_value, "0-15");
  if (static_cast<unsigned>(h.ack_nak) > 3) return fail("ack_nak", ErrorCode::bad_value, "0-3");
  if (h.version > 0x3F) return fail("version", ErrorCode::bad_value, "0-63");
  if (h.data_size > kMaxPayloadSize) return fail("data_size", ErrorCode::data_size_too_large, {});
  if (!detail::is_known_data_flag(static_cast<unsigned>(h.data_flag)))
    return fail("data_flag", ErrorCode::bad_data_flag, {});
  std::array<std::uint8_t, kHeaderSize> out{};
  encode_header_unchecked(h, out);
  return out;
}

namespace detail {

Error header_error(std::span<const std::uint8_t> bytes, const Header& h, unsigned flag) {
  if (bytes.size() < kHeaderSize)
    return Error{ErrorCode::truncated, bytes.size(), "header",
                 "needs 16 bytes, " + std::to_string(bytes.size()) + " given"};
  if (h.version != kVersionRa30 && h.version != kVersionRa32)
    return Error{ErrorCode::unsupported_version, 1, "version",
                 std::to_string(h.version) + ", expected 1 (RA 3.0/3.1) or 2 (RA 3.2/3.3)"};
  if (!is_known_data_flag(flag)) return Error{ErrorCode::bad_data_flag, 13, "data_flag", std::to_string(flag)};
  return Error{ErrorCode::data_size_too_large, 12, "data_size", std::to_string(h.data_size)};
}

Error packet_size_error(const Header& header, std::size_t payload_size) {
  return Error{ErrorCode::data_size_mismatch, 12, "data_size",
               "header says " + std::to_string(header.data_size) + " bytes, packet carries " +
                   std::to_string(payload_size)};
}

}  // namespace detail

}  // namespace jaus
