// The described message types as GoogleTest type lists and a runtime loop.
#pragma once

#include <gtest/gtest.h>

#include "jaus/messages/all.hpp"

namespace jaus::test {

template <class List>
struct AsGtestTypes;
template <class... Ms>
struct AsGtestTypes<msg::TypeList<Ms...>> {
  using type = ::testing::Types<Ms...>;
};

// Every subgroup's list of message types.
using MessageGroups = msg::TypeList<msg::CoreMessages, msg::CommunicationsMessages, msg::PlatformMessages,
                                    msg::ManipulatorMessages, msg::EnvironmentMessages, msg::DiscoveryMessages,
                                    msg::EventMessages>;

// Calls f.template operator()<M>() for every message type of every subgroup.
template <class F, class... Ms>
void for_each_in(msg::TypeList<Ms...>, F&& f) {
  (f.template operator()<Ms>(), ...);
}
template <class F>
void for_each_message_type(F&& f) {
  [&]<class... Groups>(msg::TypeList<Groups...>) { (for_each_in(Groups{}, f), ...); }(MessageGroups{});
}

}  // namespace jaus::test
