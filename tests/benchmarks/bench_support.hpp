// What the node benchmarks that speak raw JAUS over loopback share: a JAUS
// datagram (OPC framing) as a third-party OCU would send it, and p50 / p99 /
// max of a set of measurements.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "jaus/core/header.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::bench {

template <class M>
std::vector<std::uint8_t> datagram(const Address& from, const Address& to, const M& message, std::uint8_t priority = 6,
                                   AckNak ack_nak = AckNak::none, std::uint16_t sequence = 0) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(message, payload);
  Header h;
  h.priority = priority;
  h.command_code = M::code;
  h.source = from;
  h.destination = to;
  h.data_size = static_cast<std::uint16_t>(*size);
  h.ack_nak = ack_nak;
  h.sequence = sequence;
  std::vector<std::uint8_t> out(transport::kOpcPrefix.begin(), transport::kOpcPrefix.end());
  out.resize(out.size() + kHeaderSize);
  encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(out.data() + out.size() - kHeaderSize, kHeaderSize));
  out.insert(out.end(), payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(*size));
  return out;
}

struct Figures {
  double p50 = 0, p99 = 0, max = 0;
  std::size_t count = 0;
};

inline Figures figures(std::vector<double> values) {
  Figures f;
  f.count = values.size();
  if (values.empty()) return f;
  std::sort(values.begin(), values.end());
  const auto at = [&](double p) { return values[std::min(values.size() - 1, static_cast<std::size_t>(p * values.size()))]; };
  f.p50 = at(0.50);
  f.p99 = at(0.99);
  f.max = values.back();
  return f;
}

}  // namespace jaus::bench
