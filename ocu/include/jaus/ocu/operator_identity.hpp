// The operator's JAUS ID, kept (issue 49): one per user and host, so an
// emergency hold set by one jausctl run is cleared by the next one without
// --as. Chosen once, 254.N.40.1 with N random (1..254), and written to
// $XDG_STATE_HOME/jaus/operator-id (else ~/.local/state/jaus/operator-id),
// one line "254.N.40.1"; the operator may edit it. Two operators collide with
// a chance of 1 in 254 (the node then refuses the second's claim while the
// first holds state there, and the message says so): an edit or --as settles it.
//
// One ID is one (subsystem, node) at the vehicle, whose replies go to the
// port it last heard that ID from: two processes acting as one ID at once
// get each other's replies. An IdentityLock (flock on
// <state dir>/jaus/in-use/<ID>.lock, released by the kernel when the process
// ends, however it ends) tells a second process the ID is in use, and
// IdUse says what it then does (docs/talk-to-your-node.md, "Who you are").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "jaus/core/address.hpp"
#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::ocu {

// $XDG_STATE_HOME/jaus (an absolute path), else $HOME/.local/state/jaus;
// none when neither is set.
std::optional<std::filesystem::path> operator_state_directory();

// A fresh 254.N.40.1 (N random in 1..254).
jaus::Address fresh_operator_address();

// The ID in <directory>/operator-id, made (with its directory) when missing.
// Errors: the file is not an OCU address S.N.C.I (component 1 is a node
// manager's), or cannot be read or written: the error names the file.
jaus::Expected<jaus::Address> load_operator_id(const std::filesystem::path& directory);

class IdentityLock {
 public:
  // Takes <directory>/in-use/<address>.lock for this process. Held by another
  // process: a `refused` error naming it ("in use by pid 4242"); a lock that
  // cannot be made: an `io` error naming the file.
  static jaus::Expected<IdentityLock> take(const std::filesystem::path& directory, const jaus::Address& address);
  IdentityLock(IdentityLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  IdentityLock& operator=(IdentityLock&& other) noexcept;
  ~IdentityLock();

 private:
  explicit IdentityLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// What a command does with its ID, which decides what happens while another
// process acts as it (the rules of docs/talk-to-your-node.md, "Who you are").
enum class IdUse {
  looks,   // discover, status, query, subscribe: a fresh ID of its own node (no reply mixed;
           // nothing it leaves needs clearing)
  shares,  // emergency set and clear, `send` of a command: the same ID, shared (OperatorId::shared:
           // only its own ACK is read as its answer). Safety: a stop is never refused, and the
           // hold it leaves is the kept ID's, cleared by a plain `clear`. Also how a route is
           // sent under the ID of a `control` that holds the driver.
  holds,   // control, the console: refused (the error names the ID, the process and --as)
};

struct OperatorId {
  jaus::Address address;
  std::optional<IdentityLock> lock;  // held while the command runs
  bool shared = false;  // another process acts as it too (IdUse::shares): its replies may come here
  std::string note;  // one line for stderr when the ID is not the one asked for (or not kept), else empty
};

// `as`: --as, else the kept ID (load_operator_id), else (no state directory)
// a fresh one for this run. Errors: a bad ID file (invalid_argument), the ID
// in use for `holds` (refused).
jaus::Expected<OperatorId> choose_operator_id(const std::optional<jaus::Address>& as, IdUse use);

}  // namespace jaus::ocu
