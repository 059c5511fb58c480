// The runner's other OCUs on a jaus::testing memory network under virtual
// time (conform::OcuFactory): each is attached to a link of its own, and a
// silenced one's link is unplugged while a fresh link at its node, that
// nobody answers from, hears what still reaches it.
#pragma once

#include <map>
#include <memory>

#include "jaus/conform/ocu_factory.hpp"
#include "jaus/testing/memory_link.hpp"
#include "memory_ocu.hpp"

namespace jaus::conform::test {

class MemoryOcus final : public OcuFactory {
 public:
  MemoryOcus(rt::VirtualTime& time, testing::MemoryNetwork& network) : time_(time), network_(network) {}

  Expected<std::unique_ptr<ocu::OcuSession>> open(ocu::SessionOptions options) override {
    auto& link = network_.attach(options.self.subsystem, options.self.node);
    auto session = test_support::attach_ocu(time_, link, std::move(options));
    if (session) links_[session->get()] = &link;
    return session;
  }

  Expected<std::unique_ptr<DeafEndpoint>> silence(ocu::OcuSession& session, Heard heard) override {
    const auto found = links_.find(&session);
    if (found == links_.end())
      return unexpected(make_error(ErrorCode::invalid_argument, "silence: an OCU these OCUs did not open"));
    testing::MemoryLink& own = *found->second;
    links_.erase(found);
    own.set_connected(false);  // nothing out of the session, nothing in
    auto& deaf = network_.attach(own.subsystem(), own.node());
    deaf.on_receive([heard = std::move(heard)](std::span<const std::uint8_t> bytes) {
      if (const auto packet = decode_packet(bytes)) heard(*packet);
    });
    return std::unique_ptr<DeafEndpoint>(new DeafLink(deaf));
  }

 private:
  // Unplugged when it goes: a later OCU at the same node has a link of its own.
  class DeafLink final : public DeafEndpoint {
   public:
    explicit DeafLink(testing::MemoryLink& link) : link_(link) {}
    ~DeafLink() override {
      link_.on_receive({});
      link_.set_connected(false);
    }

   private:
    testing::MemoryLink& link_;
  };

  rt::VirtualTime& time_;
  testing::MemoryNetwork& network_;
  std::map<const ocu::OcuSession*, testing::MemoryLink*> links_;  // the open, unsilenced ones
};

}  // namespace jaus::conform::test
