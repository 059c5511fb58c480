// What a component is given by its node: time, timers, a way out, a log.
#pragma once

#include <span>

#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"

namespace jaus::rt {

// Where a component's messages go: the node in production, a recorder in tests.
// The node stamps sequence numbers; the component fills everything else.
// send() copies what it keeps and never delivers back into a component before
// it returns (delivery is queued), so callers may reuse their buffers.
class Outbox {
 public:
  virtual ~Outbox() = default;
  virtual void send(const Header& header, std::span<const std::uint8_t> payload) = 0;
  // The rate what is sent here may leave at, bits a second (a field radio's
  // send budget); 0: not limited. A component that can make its data
  // smaller (a camera's JPEG quality) reads it.
  virtual std::uint64_t link_bits_per_second() const { return 0; }
};

struct Environment {
  Clock& clock;
  Scheduler& scheduler;
  Outbox& outbox;
  LogFn log = silent_log();
};

}  // namespace jaus::rt
