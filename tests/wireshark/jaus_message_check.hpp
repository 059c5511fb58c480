// One JAUS message as tshark showed it, checked against the codec's JSON of
// the same bytes (`jausctl msg decode`): name, code, every header field,
// every body field, and the message inside an Event or Create/Update Event.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "field_values.hpp"
#include "jaus/base/hex.hpp"
#include "tshark_session.hpp"

namespace jaus::test {

inline FieldValues header_values(const Json& decoded) {
  static const std::vector<std::string> ack_nak = {"none", "ack_requested", "nak", "ack"};
  static const std::map<std::string, int> data_flags = {
      {"single", 0}, {"first", 1}, {"middle", 2}, {"retransmitted", 4}, {"last", 8}};
  FieldValues out;
  const auto& h = decoded["header"];
  out["jaus.name"] = {decoded["name"]};
  out["jaus.code"] = {decoded["code"]};
  for (const char* key :
       {"priority", "service_connection", "experimental", "version", "destination", "source", "data_size", "sequence"})
    out[std::string("jaus.") + key] = {h[key]};
  for (std::size_t i = 0; i < ack_nak.size(); ++i)
    if (h["ack_nak"] == ack_nak[i]) out["jaus.ack_nak"] = {static_cast<int>(i)};
  out["jaus.data_flag"] = {data_flags.at(h["data_flag"].get<std::string>())};
  return out;
}

// The message inside: the outer header with the inner code and size, then the inner payload.
inline std::string inner_message_hex(const std::vector<std::uint8_t>& outer, std::uint16_t code,
                                     const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> message(outer.begin(), outer.begin() + 16);
  message[2] = static_cast<std::uint8_t>(code);
  message[3] = static_cast<std::uint8_t>(code >> 8);
  message[12] = static_cast<std::uint8_t>(payload.size());
  message[13] = static_cast<std::uint8_t>((payload.size() >> 8) & 0x0F);
  message.insert(message.end(), payload.begin(), payload.end());
  return jaus::to_hex(message);
}

// Problems found (empty: tshark shows what the codec decodes).
inline std::vector<std::string> check_jaus_message(TsharkSession& session, const Json& layer,
                                                   const std::vector<std::uint8_t>& message,
                                                   const std::string& dialect) {
  std::string failure;
  const Json decoded = session.jausctl_json({"msg", "decode", jaus::to_hex(message), "--dialect", dialect}, failure);
  if (decoded.is_null()) return {failure};
  FieldValues shown;
  flatten_tshark(layer, "", shown);
  auto problems = compare_fields(header_values(decoded), shown, "jaus.header");
  FieldValues body;
  const std::string prefix = "jaus." + slug(decoded["name"].get<std::string>());
  flatten_decoded(decoded["fields"], prefix, body);
  const auto body_problems = compare_fields(body, shown, prefix);
  problems.insert(problems.end(), body_problems.begin(), body_problems.end());

  // Event: the report inside; Create/Update Event: the query inside.
  const auto& fields = decoded["fields"];
  std::string inner_hex;
  std::uint16_t inner_code = 0;
  if (fields.contains("report_message") && fields.contains("report_code")) {
    inner_hex = fields["report_message"].get<std::string>();
    inner_code = fields["report_code"].get<std::uint16_t>();
  } else if (fields.contains("query_message") && fields.contains("report_code")) {
    inner_hex = fields["query_message"].get<std::string>();
    inner_code = static_cast<std::uint16_t>(fields["report_code"].get<std::uint16_t>() - 0x2000);
  }
  if (!inner_hex.empty()) {
    const auto parsed = jaus::parse_hex(inner_hex);
    const std::vector<std::uint8_t> payload = parsed ? *parsed : std::vector<std::uint8_t>{};
    const Json inner = session.jausctl_json(
        {"msg", "decode", inner_message_hex(message, inner_code, payload), "--dialect", dialect}, failure);
    if (inner.is_null()) return {"inner message: " + failure};
    FieldValues inner_fields;
    const std::string inner_prefix = "jaus." + slug(inner["name"].get<std::string>());
    flatten_decoded(inner["fields"], inner_prefix, inner_fields);
    const auto inner_problems = compare_fields(inner_fields, shown, inner_prefix);
    for (const auto& p : inner_problems) problems.push_back("inside: " + p);
  }
  return problems;
}

}  // namespace jaus::test
