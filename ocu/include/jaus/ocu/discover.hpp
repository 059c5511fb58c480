// Discovery over a session: heartbeats and replies feed the Discovery model,
// whose queries are sent as they come, for `wait`; every 0.5 s the first
// broadcast and the questions still unanswered go again (a lossy link loses
// some, or their answers). What jausctl discover
// prints and what the conformance runner starts from.
#pragma once

#include "jaus/ocu/discovery.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::ocu {

// A snapshot: everything heard within `wait`, nothing after (or less, when
// the session is interrupted).
Discovery discover(OcuSession& session, rt::Duration wait);

}  // namespace jaus::ocu
