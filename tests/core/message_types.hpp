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

// Calls f.template operator()<M>() for every message type of every subgroup.
template <class F, class... Ms>
void for_each_in(msg::TypeList<Ms...>, F&& f) {
  (f.template operator()<Ms>(), ...);
}
template <class F>
void for_each_message_type(F&& f) {
  for_each_in(msg::CoreMessages{}, f);
  for_each_in(msg::CommunicationsMessages{}, f);
  for_each_in(msg::PlatformMessages{}, f);
  for_each_in(msg::ManipulatorMessages{}, f);
  for_each_in(msg::EnvironmentMessages{}, f);
  for_each_in(msg::DiscoveryMessages{}, f);
  for_each_in(msg::EventMessages{}, f);
}

}  // namespace jaus::test
