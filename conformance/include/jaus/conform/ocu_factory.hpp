// Where a run's other OCUs come from: the cases that need a second requester
// (takeover, two emergency holders) open one beside the runner's session,
// and the silent-requester case makes it fall silent while what still
// reaches it is heard. jaus-conform's are on UDP beside its session
// (udp_ocu_factory()); tests' on a memory network under virtual time.
#pragma once

#include <functional>
#include <memory>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::conform {

// What hears a silenced OCU's packets: it stops hearing when it goes.
class DeafEndpoint {
 public:
  virtual ~DeafEndpoint() = default;
};

class OcuFactory {
 public:
  using Heard = std::function<void(const PacketView& packet)>;

  virtual ~OcuFactory() = default;
  // Another OCU on the runner's network; `options` are the runner's with an
  // address of its own. Runs whenever the runner's session waits.
  virtual Expected<std::unique_ptr<ocu::OcuSession>> open(ocu::SessionOptions options) = 0;
  // `session`, one of open()'s, falls silent: it neither sends (no
  // heartbeats) nor answers from now on; every packet that still reaches it
  // goes to `heard` instead, never answered, until the endpoint goes (before
  // the session).
  virtual Expected<std::unique_ptr<DeafEndpoint>> silence(ocu::OcuSession& session, Heard heard) = 0;
};

// OCUs on UDP beside `runner` (opened with OcuSession::open, which they
// share an io_context with): a silenced one's port stays bound, so the
// datagrams the component still sends it are heard, not refused.
std::unique_ptr<OcuFactory> udp_ocu_factory(ocu::OcuSession& runner);

}  // namespace jaus::conform
