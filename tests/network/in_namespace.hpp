// The calling thread moved into a lab host's network namespace (setns) for
// as long as this lives: sockets it opens meanwhile (an in-process OCU's)
// live there and stay there; children it spawns start there.
#pragma once

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <string>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::test::network {

class InNamespace {
 public:
  static jaus::Expected<std::unique_ptr<InNamespace>> enter(const std::string& ns) {
    const int home = ::open("/proc/thread-self/ns/net", O_RDONLY | O_CLOEXEC);
    if (home < 0) return failure("open /proc/thread-self/ns/net");
    const int target = ::open(("/var/run/netns/" + ns).c_str(), O_RDONLY | O_CLOEXEC);
    if (target < 0) {
      ::close(home);
      return failure("open /var/run/netns/" + ns);
    }
    const int entered = ::setns(target, CLONE_NEWNET);
    const int error = errno;
    ::close(target);
    if (entered != 0) {
      ::close(home);
      errno = error;
      return failure("setns into " + ns);
    }
    return std::unique_ptr<InNamespace>(new InNamespace(home));
  }
  ~InNamespace() {
    (void)::setns(home_, CLONE_NEWNET);
    ::close(home_);
  }
  InNamespace(const InNamespace&) = delete;
  InNamespace& operator=(const InNamespace&) = delete;

 private:
  explicit InNamespace(int home) : home_(home) {}
  static jaus::Unexpected<jaus::Error> failure(const std::string& what) {
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::io, what + ": " + std::strerror(errno)));
  }
  int home_;
};

}  // namespace jaus::test::network
