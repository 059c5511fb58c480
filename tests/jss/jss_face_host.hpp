// What the JSS face suites share: a node host with its JSS face under
// virtual time, as jausd makes it (the node's link a FaceLink around a
// memory link, the face made on host->node()), and every datagram the face
// sends decoded and kept: ACKs apart, large messages put back together.
// tests/jss/face (FaceNode: several clients and an RA peer) and
// tests/jss/mobility (JssVehicle: one client on a whole simulated vehicle)
// add their own ways of talking to it.
#pragma once

#include <gtest/gtest.h>

#include <deque>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/jss_translators.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss/large_message.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/testing/components_ready.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::test {

using namespace std::chrono_literals;

struct Received {
  jss::JudpHeader header;
  std::vector<std::uint8_t> contents;
};

class JssFaceHost {
 public:
  JssFaceHost(std::vector<host::ComponentSpec> components, std::string subsystem_name,
              jss_face::FaceConfig config = {})
      : network_(time_, time_), link_(network_.attach(1, 1)), face_link_(link_) {
    host::HostConfig c;
    c.settings.identity.subsystem_name = std::move(subsystem_name);
    c.settings.identity.node_name = "vehicle";
    c.components = std::move(components);
    auto attached = host::NodeHost::attach(std::move(c), face_link_, time_, time_);
    if (!attached) throw std::runtime_error(attached.error().message());
    host_ = std::move(*attached);
    link_.deliver_to(host_->node());
    // The kinds' JSS services, as a node host hands them to its face.
    face_ = std::make_unique<jss_face::JssFace>(
        std::move(config), host::builtin_jss_translators(), host_->node(),
        [this](const jss::JssId&, std::span<const std::uint8_t> datagram) { from_face(datagram); },
        [this](rt::LogLevel, const std::string& line) { log_.push_back(line); });
    face_link_.attach(face_.get());
  }
  ~JssFaceHost() {
    host_->stop("test over");
    face_link_.attach(nullptr);
    face_.reset();
    link_.on_receive({});
    link_.set_connected(false);
  }
  JssFaceHost(const JssFaceHost&) = delete;
  JssFaceHost& operator=(const JssFaceHost&) = delete;

  rt::VirtualTime& time() { return time_; }
  host::NodeHost& host() { return *host_; }
  jss_face::JssFace& face() { return *face_; }
  const jss_face::FaceCounters& counters() const { return face_->counters(); }
  const std::vector<std::string>& log() const { return log_; }
  void run_for(rt::Duration d) { testing::run_for(time_, d); }
  bool run_until(const std::function<bool()>& done, rt::Duration limit = 500ms) {
    return testing::run_until(time_, done, limit);
  }
  bool wait_ready(rt::Duration limit = 10s) {
    return run_until([&] { return testing::all_components_ready(host_->node()); }, limit);
  }
  // One raw datagram to the face.
  void receive(std::span<const std::uint8_t> datagram, rt::SenderStanding standing = rt::SenderStanding::trusted) {
    face_->receive(datagram, standing);
  }
  const std::deque<Received>& received() const { return received_; }
  const std::vector<jss::JudpHeader>& acks() const { return acks_; }
  std::size_t datagrams_sent() const { return datagrams_; }

 protected:
  testing::MemoryLink& link() { return link_; }
  std::deque<Received>& kept() { return received_; }

 private:
  void from_face(std::span<const std::uint8_t> datagram) {
    ++datagrams_;
    auto packets = jss::decode_judp_datagram(datagram);
    if (!packets) {
      ADD_FAILURE() << "the face sent a malformed datagram: " << packets.error().message();
      return;
    }
    for (const auto& p : *packets) {
      if (p.header.ack_nak == jss::JudpAckNak::ack) {
        EXPECT_TRUE(p.contents.empty()) << "an ACK carries no contents";
        acks_.push_back(p.header);
        continue;
      }
      auto assembled = assembler_.feed(p.header, p.contents, time_.now());
      if (assembled.status == AssemblyStatus::dropped) {
        ADD_FAILURE() << "a packet of the face's large message does not fit: " << to_string(assembled.issue);
        continue;
      }
      if (assembled.status == AssemblyStatus::pending) continue;
      if (assembled.status == AssemblyStatus::single)
        received_.push_back(Received{p.header, {p.contents.begin(), p.contents.end()}});
      else
        received_.push_back(Received{assembled.message->header, std::move(assembled.message->payload)});
      if (received_.size() > 4096) received_.pop_front();  // bounded: a test reads what it waits for
    }
  }

  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& link_;
  jss_face::FaceLink face_link_;
  std::unique_ptr<host::NodeHost> host_;
  std::unique_ptr<jss_face::JssFace> face_;
  jss::JssLargeMessageAssembler assembler_;
  std::deque<Received> received_;
  std::vector<jss::JudpHeader> acks_;
  std::size_t datagrams_ = 0;
  std::vector<std::string> log_;
};

}  // namespace jaus::test
