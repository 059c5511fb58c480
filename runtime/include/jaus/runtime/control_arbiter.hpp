// Control arbitration (Request/Release/Confirm/Reject Component Control), as
// the RA says and the RA 3.3 peers get wrong:
//   uncontrolled:   accept a request whose authority >= our own authority;
//   controlled by A, request from B:
//     B == A               -> accept, A's authority updated
//     authority(B) > A's   -> accept B, Reject Component Control to A
//     otherwise            -> Confirm 2 (not accepted), or Reject if configured
//   Release from the controller -> uncontrolled; from anyone else -> ignored.
// Pure decision logic: the component sends the replies and logs the changes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "jaus/core/address.hpp"

namespace jaus::rt {

struct Controller {
  Address address;
  std::uint8_t authority = 0;
};

// "1.1.40.1 (authority 5)", for logs.
inline std::string to_string(const Controller& c) {
  return c.address.to_string() + " (authority " + std::to_string(c.authority) + ")";
}

class ControlArbiter {
 public:
  struct RequestOutcome {
    bool accepted = false;
    std::optional<Controller> displaced;  // previous controller to send Reject Component Control to
    std::string_view why;
  };

  explicit ControlArbiter(std::uint8_t own_authority = 0) : own_authority_(own_authority) {}

  RequestOutcome request(const Address& from, std::uint8_t authority) {
    if (!controller_) {
      if (authority < own_authority_) return {false, std::nullopt, "authority below the component's own"};
      controller_ = Controller{from, authority};
      return {true, std::nullopt, "granted"};
    }
    if (controller_->address == from) {
      controller_->authority = authority;
      return {true, std::nullopt, "authority updated by the controller"};
    }
    if (authority > controller_->authority) {
      const Controller previous = *controller_;
      controller_ = Controller{from, authority};
      return {true, previous, "higher authority took control"};
    }
    return {false, std::nullopt, "not higher than the current controller's authority"};
  }

  // True when `from` was the controller and control is now released.
  bool release(const Address& from) {
    if (!controller_ || controller_->address != from) return false;
    controller_.reset();
    return true;
  }

  // Drops control regardless of who holds it (liveness timeout, reset, shutdown).
  std::optional<Controller> drop() {
    auto previous = controller_;
    controller_.reset();
    return previous;
  }

  bool is_controller(const Address& who) const { return controller_ && controller_->address == who; }
  const std::optional<Controller>& controller() const { return controller_; }
  std::uint8_t own_authority() const { return own_authority_; }
  void set_own_authority(std::uint8_t authority) { own_authority_ = authority; }

 private:
  std::uint8_t own_authority_;
  std::optional<Controller> controller_;
};

}  // namespace jaus::rt
