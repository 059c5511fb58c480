// A JAUS peer scripted on a link of a jaus::testing memory network, for
// tests under virtual time that need a node our code did not make: it hands
// each packet that decodes to on_packet(), replies by JAUS address (the
// network routes it), sends to its peers as a UDP peer does (to every other
// node, whatever the address), with timers on the virtual clock.
// The same protected interface as ScriptedUdpPeer, so a script runs on either.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test_support {

class ScriptedMemoryPeer {
 public:
  ScriptedMemoryPeer(rt::VirtualTime& time, testing::MemoryNetwork& network, std::uint8_t subsystem, std::uint8_t node)
      : time_(time), link_(network.attach(subsystem, node)) {
    link_.on_receive([this](std::span<const std::uint8_t> bytes) {
      if (const auto packet = decode_packet(bytes)) on_packet(packet->header, packet->payload);
    });
  }
  virtual ~ScriptedMemoryPeer() { close(); }
  ScriptedMemoryPeer(const ScriptedMemoryPeer&) = delete;
  ScriptedMemoryPeer& operator=(const ScriptedMemoryPeer&) = delete;

 protected:
  virtual void on_packet(const Header& header, std::span<const std::uint8_t> payload) = 0;

  // Nothing in or out from now on, timers included.
  void close() {
    link_.on_receive({});
    link_.set_connected(false);
    alive_.reset();
  }

  // To `to`, wherever it is (the network routes by address).
  template <class M>
  void reply(const Address& from, const Address& to, const M& message) {
    transmit(from, to, message, false);
  }
  // To every other node of the network, whatever `to` names, as a UDP peer
  // sends to each endpoint it is configured with.
  template <class M>
  void send_to_peers(const Address& from, const Address& to, const M& message) {
    transmit(from, to, message, true);
  }

  // Runs `action` once `delay` has passed, unless closed by then.
  void after(rt::Duration delay, std::function<void()> action) {
    std::weak_ptr<char> alive = alive_;
    time_.call_at(time_.now() + delay, [alive, action = std::move(action)] {
      if (!alive.expired()) action();
    });
  }

 private:
  template <class M>
  void transmit(const Address& from, const Address& to, const M& message, bool to_every_link) {
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(message, std::span(packet).subspan(kHeaderSize));
    if (!size) return;
    Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    encode_header_unchecked(h, std::span(packet).template first<kHeaderSize>());
    packet.resize(kHeaderSize + *size);
    if (to_every_link)
      link_.transmit_to_every_link(h, packet);
    else
      link_.transmit(h, packet);
  }

  rt::VirtualTime& time_;
  testing::MemoryLink& link_;
  std::shared_ptr<char> alive_ = std::make_shared<char>(0);
};

}  // namespace jaus::test_support
