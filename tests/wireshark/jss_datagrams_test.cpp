// AS5669A datagrams dissected by tshark with the generated plugin, compared
// field by field with the JSS codec (jss::decode_judp_datagram and
// jss::contents_to_json) in-process: the byte examples of docs/jss.md, an
// instance of every JSS message with every field present and one with random
// fields, an ACK, two transport messages in one datagram, a large message
// reassembled on its last packet; malformed AS5669A ends in expert info.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "../jss/codec/jss_values.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/jss/catalogue.hpp"
#include "jaus/jss/large_message.hpp"
#include "pcap_writer.hpp"
#include "tshark_session.hpp"

namespace jaus::test {
namespace jss_tshark {

namespace msg = jaus::jss::msg;

std::vector<std::uint8_t> hex(const std::string& text) {
  auto out = jaus::parse_hex(text);
  EXPECT_TRUE(out) << text;
  return out ? *out : std::vector<std::uint8_t>{};
}

std::vector<std::uint8_t> datagram_of(const std::vector<std::uint8_t>& contents, std::uint16_t sequence,
                                      jss::JudpAckNak ack_nak = jss::JudpAckNak::none) {
  jss::JudpHeader h;
  h.destination = {1, 1, 33};
  h.source = {42, 1, 1};
  h.sequence = sequence;
  h.ack_nak = ack_nak;
  return jss::make_judp_datagram(h, contents);
}

// The codec's contents JSON as dissector keys: fields under
// jaus.jss.<message>.<path>; an embedded message's fields under its own
// message's prefix, its ID in jaus.jss.message_id like the outer one's.
void flatten_contents(const Json& message, FieldValues& out);
void flatten_fields(const Json& j, const std::string& path, FieldValues& out) {
  if (j.is_object() && j.contains("fields") && j.contains("name") && j.contains("id")) {
    flatten_contents(j, out);
  } else if (j.is_object() && j.contains("hex")) {  // bytes that are not a message we know
    if (j.contains("id")) out["jaus.jss.message_id"].push_back(std::stoul(j["id"].get<std::string>(), nullptr, 16));
    out[path + ".hex"].push_back(j["hex"]);
  } else if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten_fields(v, path + "." + k, out);
  } else if (j.is_array()) {
    for (const auto& e : j) flatten_fields(e, path, out);
  } else {
    out[path].push_back(j);
  }
}
void flatten_contents(const Json& message, FieldValues& out) {
  out["jaus.jss.message_id"].push_back(std::stoul(message["id"].get<std::string>(), nullptr, 16));
  flatten_fields(message["fields"], "jaus.jss." + slug(message["name"].get<std::string>()), out);
}

// Problems between what tshark showed of `datagram` and what the codec decodes.
std::vector<std::string> check_datagram(const Json& layer, const std::vector<std::uint8_t>& datagram,
                                        const std::vector<std::uint8_t>* reassembled = nullptr) {
  const auto packets = jss::decode_judp_datagram(datagram);
  if (!packets) return {"the codec refuses the datagram: " + packets.error().message()};
  FieldValues expected;
  expected["jaus.as5669a.version"].push_back(datagram[0]);
  for (const auto& p : *packets) {
    const auto& h = p.header;
    expected["jaus.as5669a.message_type"].push_back(h.message_type);
    expected["jaus.as5669a.hc_flags"].push_back(0);
    expected["jaus.as5669a.properties"].push_back(datagram[static_cast<std::size_t>(p.contents.data() - datagram.data()) - 9]);
    expected["jaus.as5669a.priority"].push_back(static_cast<int>(h.priority));
    expected["jaus.as5669a.broadcast"].push_back(static_cast<int>(h.broadcast));
    expected["jaus.as5669a.ack_nak"].push_back(static_cast<int>(h.ack_nak));
    expected["jaus.as5669a.data_flag"].push_back(static_cast<int>(h.data_flag));
    expected["jaus.as5669a.destination"].push_back(h.destination.to_string());
    expected["jaus.as5669a.source"].push_back(h.source.to_string());
    expected["jaus.as5669a.sequence"].push_back(h.sequence);
    expected["jaus.as5669a.data_size"].push_back(jss::kMinDataSize + p.contents.size());
    std::span<const std::uint8_t> contents = p.contents;
    if (h.data_flag != jss::JudpDataFlag::single && !contents.empty() &&
        !(h.data_flag == jss::JudpDataFlag::last && reassembled != nullptr))
      expected["jaus.jss.contents"].push_back(jaus::to_hex(contents));  // a packet of a large message
    if (h.data_flag == jss::JudpDataFlag::last && reassembled != nullptr) contents = *reassembled;
    else if (h.data_flag != jss::JudpDataFlag::single || contents.empty()) continue;
    const auto json = jss::contents_to_json(contents);
    if (!json) return {"the codec refuses the contents: " + json.error().message()};
    flatten_contents(*json, expected);
  }
  FieldValues shown;
  flatten_tshark(layer, "", shown);
  // Items that hold others and no value of their own (an embedded message, a transport message).
  for (auto it = shown.begin(); it != shown.end();) {
    const bool container = expected.count(it->first) == 0 &&
                           std::all_of(it->second.begin(), it->second.end(), [](const Json& v) { return v == ""; });
    it = container ? shown.erase(it) : std::next(it);
  }
  auto problems = compare_fields(expected, shown, "jaus.jss");
  for (const auto& p : compare_fields(expected, shown, "jaus.as5669a")) problems.push_back(p);
  if (shown.count("jaus.malformed") || shown.count("jaus.as5669a.bad_header") || shown.count("jaus.trailing"))
    problems.push_back("expert info on a good datagram: " + layer.dump());
  return problems;
}

// Every JSS message: all fields present, then random ones (fixed seed).
template <class... Ms>
void add_every_message(std::vector<std::vector<std::uint8_t>>& out, msg::TypeList<Ms...>) {
  Rng rng(0x7555);
  (([&] {
     for (int i = 0; i < 2; ++i) {
       Ms m{};
       wire::CodecContext ctx{wire::Dialect::ra, {}};
       randomize(static_cast<typename Ms::body_type&>(m), rng, ctx, i == 0);
       out.push_back(jss::encode_contents(m));
     }
   }()),
   ...);
}

TEST(TsharkJss, DatagramsShowWhatTheCodecDecodes) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("jss");
  const UdpEndpoint ocu{{127, 0, 0, 62}, 3794};
  const UdpEndpoint node{{127, 0, 0, 60}, 3794};

  std::vector<std::vector<std::uint8_t>> datagrams;
  // The worked example and the IOP node manager's query (docs/jss.md, "The bytes
  // on the wire"), as they are.
  datagrams.push_back(hex("02 00 11 00 01 01 01 01 00 01 01 2a 00 00 2b 02 00 00"));
  datagrams.push_back(hex("02 00 11 00 09 ff ff ff ff c8 40 96 00 00 2b 04 ed 0d"));
  // The contents of docs/jss.md's "Byte examples".
  std::vector<std::vector<std::uint8_t>> contents = {
      hex("f0 01 01 00 2c 01 04 00 00 00 03 24 ff 01"),
      hex("f1 41 00 07 0c 00 00 00 03 44 03 00 dc 46 03 80 91 5c fe 7f"),
      hex("00 4b 02 11 27 05 48 75 73 6b 79"),
      jss::encode_contents(msg::ReportServices{{{{1, {{33, 0, {{"urn:jaus:jss:core:Transport", 1, 1},
                                                                 {"urn:jaus:jss:mobility:PrimitiveDriver", 1, 0}}}}}}}}),
      hex("05 04 21 00 ff bf 00 60"),
      hex("0d 04 00 dc 46 03 80 91 5c fe 7f"),
      hex("1a 04 07 01 01 00 00 00 00 00 00 0b 00 0d 04 00 dc 46 03 80 91 5c fe 7f"),
      hex("1e 04 01 2c 01 01 00"),
  };
  add_every_message(contents, AllJssMessages{});
  std::uint16_t sequence = 100;
  for (const auto& c : contents) datagrams.push_back(datagram_of(c, sequence++, jss::JudpAckNak::ack_requested));
  // An ACK, and two transport messages in one datagram.
  jss::JudpHeader ack;
  ack.ack_nak = jss::JudpAckNak::ack;
  ack.source = {1, 1, 33};
  ack.destination = {42, 1, 1};
  ack.sequence = 100;
  datagrams.push_back(jss::make_judp_datagram(ack, {}));
  auto two = datagram_of(contents[4], 7);
  const auto second = datagram_of(contents[5], 8);
  two.insert(two.end(), second.begin() + 1, second.end());
  datagrams.push_back(two);
  // A large message: a Report Service List in three packets.
  msg::ReportServiceList list;
  for (std::uint16_t s = 1; s <= 12; ++s)
    list.subsystems.push_back({s, {{1, {{33, 0, {{"urn:jaus:jss:mobility:PrimitiveDriver", 1, 0},
                                                 {"urn:jaus:jss:core:Management", 1, 1}}}}}}});
  const auto large = jss::encode_contents(list);
  jss::JudpHeader lh;
  lh.source = {1, 1, 1};
  lh.destination = {42, 1, 1};
  lh.sequence = 500;
  const auto parts = jss::make_judp_datagrams(lh, large, (large.size() + 2) / 3);
  ASSERT_TRUE(parts);
  ASSERT_EQ(parts->size(), 3u);
  const std::size_t large_first = datagrams.size();
  for (const auto& p : *parts) datagrams.push_back(p);

  PcapWriter pcap((session.dir() / "jss.pcap").string());
  for (std::size_t i = 0; i < datagrams.size(); ++i) pcap.add(i % 2 ? node : ocu, i % 2 ? ocu : node, datagrams[i]);
  pcap.close();
  std::string failure;
  const auto layers = session.dissect(session.dir() / "jss.pcap", {}, failure);
  ASSERT_EQ(layers.size(), datagrams.size()) << failure;
  for (std::size_t i = 0; i < datagrams.size(); ++i) {
    ASSERT_FALSE(layers[i].is_null()) << "packet " << i + 1 << " is not JAUS to tshark";
    EXPECT_EQ(layers[i]["jaus.framing"], "AS5669A");
    const bool last_of_large = i == large_first + 2;
    for (const auto& problem : check_datagram(layers[i], datagrams[i], last_of_large ? &large : nullptr))
      ADD_FAILURE() << "packet " << i + 1 << " (" << jaus::to_hex(datagrams[i]).substr(0, 60) << "): " << problem;
  }
}

TEST(TsharkJss, MalformedAs5669aEndsInExpertInfo) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("jss-malformed");
  struct Case {
    std::string what;
    std::vector<std::uint8_t> datagram;
    std::string expert;
  };
  const std::vector<Case> cases = {
      {"header compression", hex("02 40 11 00 01 01 01 01 00 01 01 2a 00 00 2b 02 00 00"), "jaus.as5669a.bad_header"},
      {"data size beyond the datagram", hex("02 00 30 00 01 01 01 01 00 01 01 2a 00 00 2b 02 00 00"),
       "jaus.as5669a.bad_header"},
      {"unknown message ID", datagram_of(hex("34 12 01"), 1), "jaus.jss.unknown_id"},
      {"reserved presence bits", datagram_of(hex("05 04 00 10"), 2), "jaus.malformed"},
      {"embedded count beyond the bytes", datagram_of(hex("f1 41 00 07 ff 00 00 00 03 44"), 3), "jaus.malformed"},
      {"unknown variant tag", datagram_of(hex("f0 21 09 00"), 4), "jaus.malformed"},
      {"trailing bytes", datagram_of(hex("02 20 00"), 5), "jaus.trailing"},
  };
  PcapWriter pcap((session.dir() / "jss-malformed.pcap").string());
  for (const auto& c : cases) pcap.add({{127, 0, 0, 62}, 3794}, {{127, 0, 0, 60}, 3794}, c.datagram);
  pcap.close();
  std::string failure;
  const auto layers = session.dissect(session.dir() / "jss-malformed.pcap", {}, failure);
  ASSERT_EQ(layers.size(), cases.size()) << failure;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].what);
    ASSERT_FALSE(layers[i].is_null()) << "not dissected";
    FieldValues shown;
    flatten_tshark(layers[i], "", shown);
    EXPECT_EQ(shown.count(cases[i].expert), 1u) << layers[i].dump();
    for (const auto& message : shown["_ws.expert.message"])
      EXPECT_EQ(message.dump().find("dissector error"), std::string::npos) << message.dump();
  }
}

}  // namespace jss_tshark
}  // namespace jaus::test
