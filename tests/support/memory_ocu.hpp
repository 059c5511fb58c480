// An OCU session attached to a link of a jaus::testing memory network under
// virtual time: what it sends goes on `link`, what reaches `link` goes to
// it, and its waits let the virtual clock pass a millisecond at a time.
#pragma once

#include <functional>
#include <memory>
#include <span>

#include "jaus/ocu/session.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::test_support {

inline Expected<std::unique_ptr<ocu::OcuSession>> attach_ocu(rt::VirtualTime& time, testing::MemoryLink& link,
                                                             ocu::SessionOptions options) {
  return ocu::OcuSession::attach(
      std::move(options),
      ocu::SessionEnvironment{&time, &time, &link,
                              [&link](std::function<void(std::span<const std::uint8_t>)> receiver) {
                                link.on_receive(std::move(receiver));
                              },
                              testing::stepper(time)});
}

// The same on a link of its own at the session's node (options.self).
inline Expected<std::unique_ptr<ocu::OcuSession>> attach_ocu(rt::VirtualTime& time, testing::MemoryNetwork& network,
                                                             ocu::SessionOptions options) {
  auto& link = network.attach(options.self.subsystem, options.self.node);
  return attach_ocu(time, link, std::move(options));
}

}  // namespace jaus::test_support
