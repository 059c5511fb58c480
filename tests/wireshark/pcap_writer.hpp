// A capture file written without capturing: each datagram wrapped in
// Ethernet, IPv4 and UDP headers (classic pcap, link type Ethernet), so the
// tests need no capture privileges and the packets are exactly the bytes given.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace jaus::test {

struct UdpEndpoint {
  std::array<std::uint8_t, 4> ip{127, 0, 0, 1};
  std::uint16_t port = 3794;
};

class PcapWriter {
 public:
  explicit PcapWriter(const std::string& path) : out_(path, std::ios::binary) {
    // Magic, version 2.4, UTC offset, accuracy, snapshot length, link type 1 (Ethernet).
    put32(0xA1B2C3D4);
    put16(2);
    put16(4);
    put32(0);
    put32(0);
    put32(65535);
    put32(1);
  }
  bool ok() const { return out_.good(); }

  void add(const UdpEndpoint& from, const UdpEndpoint& to, const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> frame(14, 0);
    frame[12] = 0x08;  // EtherType IPv4
    const std::size_t ip_length = 20 + 8 + payload.size();
    const std::uint8_t ip[20] = {0x45,
                                 0,
                                 static_cast<std::uint8_t>(ip_length >> 8),
                                 static_cast<std::uint8_t>(ip_length),
                                 static_cast<std::uint8_t>(count_ >> 8),
                                 static_cast<std::uint8_t>(count_),
                                 0,
                                 0,
                                 64,
                                 17,
                                 0,
                                 0,
                                 from.ip[0],
                                 from.ip[1],
                                 from.ip[2],
                                 from.ip[3],
                                 to.ip[0],
                                 to.ip[1],
                                 to.ip[2],
                                 to.ip[3]};
    frame.insert(frame.end(), std::begin(ip), std::end(ip));
    const std::size_t udp_length = 8 + payload.size();
    const std::uint8_t udp[8] = {static_cast<std::uint8_t>(from.port >> 8),
                                 static_cast<std::uint8_t>(from.port),
                                 static_cast<std::uint8_t>(to.port >> 8),
                                 static_cast<std::uint8_t>(to.port),
                                 static_cast<std::uint8_t>(udp_length >> 8),
                                 static_cast<std::uint8_t>(udp_length),
                                 0,
                                 0};  // no UDP checksum
    frame.insert(frame.end(), std::begin(udp), std::end(udp));
    frame.insert(frame.end(), payload.begin(), payload.end());
    // One second apart, so frame numbers and times read easily.
    put32(count_);
    put32(0);
    put32(static_cast<std::uint32_t>(frame.size()));
    put32(static_cast<std::uint32_t>(frame.size()));
    out_.write(reinterpret_cast<const char*>(frame.data()), static_cast<std::streamsize>(frame.size()));
    ++count_;
  }
  std::uint32_t packets() const { return count_; }
  void close() { out_.close(); }

 private:
  void put32(std::uint32_t v) {
    const char b[4] = {static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 24)};
    out_.write(b, 4);
  }
  void put16(std::uint16_t v) {
    const char b[2] = {static_cast<char>(v), static_cast<char>(v >> 8)};
    out_.write(b, 2);
  }
  std::ofstream out_;
  std::uint32_t count_ = 0;
};

}  // namespace jaus::test
