// The OCU's own JAUS component. Being an rt::Component, it answers the core
// queries by itself — above all the Query Component Status a controlled
// component sends its controller as a liveness check — and it hosts the
// service connections the OCU subscribes to. Every other message addressed to
// it (reports, confirmations, Reject Component Control) goes to its inbox.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "jaus/runtime/component.hpp"

namespace jaus::ocu {

class OcuComponent final : public jaus::rt::Component {
 public:
  using Inbox = std::function<void(const jaus::Header&, std::span<const std::uint8_t>)>;

  OcuComponent(jaus::rt::ComponentConfig config, jaus::rt::Environment env, Inbox inbox)
      : Component(std::move(config), std::move(env)), inbox_(std::move(inbox)), consumed_(input_codes()) {}

  // Component::send is for a component's own protocol; an OCU sends whatever
  // its operator asks for.
  template <class M>
  void send_message(const jaus::Address& to, const M& message,
                    std::uint8_t priority = jaus::priority::kDefault) {
    send(to, message, priority);
  }

  // True when the runtime consumes this code itself (core queries, control,
  // service connection messages), so the inbox never sees it.
  bool consumes(std::uint16_t code) const;

 protected:
  bool unhandled(const jaus::Header& header, std::span<const std::uint8_t> payload) override {
    if (inbox_) inbox_(header, payload);
    return true;
  }

 private:
  Inbox inbox_;
  std::vector<std::uint16_t> consumed_;  // input_codes(), sorted; the handler table is fixed after construction
};

}  // namespace jaus::ocu
