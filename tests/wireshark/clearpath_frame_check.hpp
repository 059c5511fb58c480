// One Clearpath frame as tshark showed it, checked against `jausctl clearpath
// decode --from host|platform` of the same bytes: type, name, kind, header,
// ACK result and every payload field.
#pragma once

#include <string>
#include <vector>

#include "field_values.hpp"
#include "jaus/base/hex.hpp"
#include "tshark_session.hpp"

namespace jaus::test {

inline std::vector<std::string> check_clearpath_frame(TsharkSession& session, const Json& layer,
                                                      const std::vector<std::uint8_t>& frame, bool from_platform) {
  std::string failure;
  const Json decoded = session.jausctl_json(
      {"clearpath", "decode", jaus::to_hex(frame), "--from", from_platform ? "platform" : "host"}, failure);
  if (decoded.is_null()) return {failure};
  FieldValues expected, shown;
  for (const char* key : {"type", "name", "kind", "timestamp", "flags", "version", "acknowledges", "result_text"})
    if (decoded.contains(key)) expected[std::string("clearpath.") + key] = {decoded[key]};
  const std::string prefix = "clearpath." + decoded["name"].get<std::string>();
  flatten_decoded(decoded["fields"], prefix, expected);
  flatten_tshark(layer, "", shown);
  auto problems = compare_fields(expected, shown, prefix);
  if (shown.count("clearpath.bad_crc") != 0) problems.push_back("CRC flagged bad");
  return problems;
}

}  // namespace jaus::test
