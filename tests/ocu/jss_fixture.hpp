// ocu::JssSession against a node with its JSS face, both in one process
// under virtual time: a node host (node manager, primitive driver on the
// simulated vehicle, velocity state sensor) attached to a memory link with
// `jss.enabled` as jausd makes it, and sessions attached to the face: what a
// session sends reaches JssFace::receive `latency` later, what the face
// sends reaches the session(s) its JSS ID names. Each way may lose datagrams
// at random (seeded: the same drops every run).
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/ocu/jss_session.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::test {

using namespace std::chrono_literals;

inline const jss::JssId kJssNodeManager{1, 1, 1};
inline const jss::JssId kJssDriver{1, 1, 33};
inline const jss::JssId kJssVelocity{1, 1, 42};
inline const Address kRaDriverAddress{1, 1, 33, 1};

class JssOcuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    host::HostConfig c;
    c.node.subsystem = 1;
    c.node.node = 1;
    c.settings.identity.subsystem_name = "jss-ocu-test";
    c.settings.identity.node_name = "vehicle";
    c.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"primitive_driver", 33, 1, 0, "driver", {}, 0, {}},
                    host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "velocity", {}, 0, {}}};
    c.jss.enabled = true;
    auto attached = host::NodeHost::attach(std::move(c), link_, time, time);
    if (!attached) throw std::runtime_error(attached.error().message());
    host = std::move(*attached);
    link_.deliver_to(host->node());
    host->set_jss_sender([this](const jss::JssId& to, std::span<const std::uint8_t> datagram) {
      face_datagrams.emplace_back(datagram.begin(), datagram.end());
      if (lost(face_to_session_loss)) return;
      time.call_at(time.now() + latency,
                   [this, to, bytes = std::vector<std::uint8_t>(datagram.begin(), datagram.end())] {
                     for (auto& [id, receive] : receivers_)
                       if (to.matches(id) && receive) receive(bytes);
                   });
    });
    testing::run_until(
        time,
        [&] {
          for (const rt::Component* component : host->node().local_components())
            if (component->state() != rt::PrimaryStatus::ready) return false;
          return true;
        },
        10s);
    session = open(ocu::kDefaultJssOcuId);
  }

  void TearDown() override {
    sessions_.clear();
    session = nullptr;
    host->stop("test over");
    link_.on_receive({});
  }

  // A session attached to the face; kept until the test ends.
  ocu::JssSession* open(const jss::JssId& self) {
    ocu::JssSessionOptions options;
    options.self = self;
    ocu::JssEnvironment env;
    env.clock = &time;
    env.scheduler = &time;
    env.transmit = [this, self](const jss::JssId&, std::span<const std::uint8_t> datagram) {
      session_datagrams[self].emplace_back(datagram.begin(), datagram.end());
      if (lost(session_to_face_loss)) return;
      time.call_at(time.now() + latency, [this, bytes = std::vector<std::uint8_t>(datagram.begin(), datagram.end())] {
        host->jss_face()->receive(bytes, rt::SenderStanding::trusted);
      });
    };
    env.connect = [this, self](std::function<void(std::span<const std::uint8_t>)> receive) {
      receivers_[self] = std::move(receive);
    };
    env.wait = testing::stepper(time);
    auto opened = ocu::JssSession::attach(options, std::move(env));
    if (!opened) throw std::runtime_error(opened.error().message());
    sessions_.push_back(std::move(*opened));
    return sessions_.back().get();
  }

  void set_loss(double each_way, std::uint32_t seed) {
    session_to_face_loss = face_to_session_loss = each_way;
    random_.seed(seed);
  }

  rt::Component& ra_driver() { return *host->node().find(kRaDriverAddress); }

  rt::VirtualTime time;
  testing::MemoryNetwork network_{time, time};  // before the host: its node transmits on the link
  testing::MemoryLink& link_ = network_.attach(1, 1);
  rt::Duration latency = 2ms;
  double session_to_face_loss = 0;
  double face_to_session_loss = 0;
  std::unique_ptr<host::NodeHost> host;
  ocu::JssSession* session = nullptr;
  std::vector<std::vector<std::uint8_t>> face_datagrams;                           // everything the face sent
  std::map<jss::JssId, std::vector<std::vector<std::uint8_t>>> session_datagrams;  // what each session sent

 private:
  bool lost(double probability) {
    return probability > 0 && std::uniform_real_distribution<double>(0, 1)(random_) < probability;
  }

  std::mt19937 random_{1};
  std::map<jss::JssId, std::function<void(std::span<const std::uint8_t>)>> receivers_;
  std::vector<std::unique_ptr<ocu::JssSession>> sessions_;
};

}  // namespace jaus::test
