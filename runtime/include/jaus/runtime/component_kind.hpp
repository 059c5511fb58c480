// A component kind describes itself: its name as a configuration writes it,
// its RA 3.x component ID, the options it accepts and how it checks them, the
// hardware it needs (by interface), what an operator unit shows for it and
// how to make one. Each
// components/<name>/ exports its kind (jaus/components/<name>_kind.hpp); the
// node host walks the list of kinds and never names one
// (jaus/host/component_kinds.hpp). Header only: every component can use it.
#pragma once

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/base/quoted.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/node_directory.hpp"

namespace jaus::rt {

// A component's options as a configuration wrote them (key -> text), the
// kind they are for (error messages name it), and the authority the
// configuration gives the component (a kind may bound it by an option).
struct KindOptions {
  std::string_view kind;
  const std::map<std::string, std::string>& values;
  std::uint8_t authority = 0;
};

// What a host offers the components it makes, by interface name: the
// hardware (a drive, a pose source, cameras, an arm, ...) and anything else a
// kind may look up. An interface type I names itself with
// `static constexpr std::string_view kInterface` and says what it is with
// `kDescription` ("a vehicle drive"), for the error when it is missing.
class Backends {
 public:
  template <class I>
  void offer(I* backend) {
    offer<I>(I::kInterface, backend);
  }
  // Under another name (the same interface offered twice for two purposes).
  template <class I>
  void offer(std::string_view name, I* backend) {
    // As the interface's own pointer, so find<I>() gets the same subobject back.
    set(name, const_cast<void*>(static_cast<const void*>(backend)));
  }
  template <class I>
  I* find(std::string_view name = I::kInterface) const {
    return static_cast<I*>(get(name));
  }
  bool has(std::string_view name) const { return get(name) != nullptr; }

 private:
  void set(std::string_view name, void* backend) {
    for (auto& [n, b] : offered_)
      if (n == name) {
        b = backend;
        return;
      }
    offered_.emplace_back(std::string(name), backend);
  }
  void* get(std::string_view name) const {
    for (const auto& [n, b] : offered_)
      if (n == name) return b;
    return nullptr;
  }
  std::vector<std::pair<std::string, void*>> offered_;
};

// What a kind's factory is given to make one component.
struct KindContext {
  ComponentConfig config;         // name, address, authority and what every component of the node shares
  Environment env;                // the node's clock, scheduler and outbox
  const NodeDirectory& directory;  // the node
  KindOptions options;
  const Backends& backends;

  // The backend of interface I, or the error a host reports when it has none
  // ("primitive_driver needs a vehicle drive and the host has none").
  template <class I>
  Expected<I*> need() const {
    if (I* backend = backends.find<I>()) return backend;
    return unexpected(make_error(ErrorCode::invalid_argument, std::string(options.kind) + " needs " +
                                                                  std::string(I::kDescription) +
                                                                  " and the host has none"));
  }
};

// What an operator unit (jaus-console) shows for a component: the views a
// kind lists (ComponentKind::operator_views). The console follows a
// component, and the page picks its default targets, by the views of the
// component's ID, never by the ID itself.
namespace operator_view {
inline constexpr std::string_view kDrive = "drive";          // hold-to-drive (Set Wrench Effort); control's default
inline constexpr std::string_view kEmergency = "emergency";  // the emergency button's default target
inline constexpr std::string_view kLocalPose = "local_pose";  // Report Local Pose: the map
inline constexpr std::string_view kGlobalPose = "global_pose";  // Report Global Pose: its node's latitude/longitude
inline constexpr std::string_view kVelocity = "velocity";    // Report Velocity State
inline constexpr std::string_view kCamera = "camera";        // Report Image, Set Camera Pose
inline constexpr std::string_view kArm = "arm";              // joints: specifications, positions, Set Joint Positions
inline constexpr std::string_view kWaypoints = "waypoints";  // Set Local Waypoint, Set Travel Speed
}  // namespace operator_view

struct ComponentKind {
  std::string_view name;        // as written in a configuration ("primitive_driver")
  std::uint8_t default_id = 0;  // its RA 3.x component ID
  std::vector<std::string_view> options;  // the option keys it accepts
  // The hardware interfaces (Backends names) it drives or reads; a kind with
  // any is "a component with hardware": it follows an emergency latch the
  // host keeps (and persists).
  std::vector<std::string_view> needs;
  // It moves hardware (a drive, an arm, camera mounts): with emergency scope
  // `vehicle` one Set Emergency holds every such component.
  bool moves_hardware = false;
  // Every node has exactly one, at default_id and instance 1, and no other
  // component has that ID (the node manager).
  bool one_per_node = false;
  // jausd's default node (a configuration without `components:`) has one, at
  // default_id, instance 1, named as the kind, with this authority; nullopt:
  // the default node has none.
  std::optional<std::uint8_t> default_node_authority = std::nullopt;
  // What an operator unit shows for a component at default_id (operator_view
  // names); empty: it is listed, nothing of it is followed.
  std::vector<std::string_view> operator_views = {};
  // The first problem with the options, or with the authority they bound
  // (Error::field names the key, or "authority"), or nothing; nothing is
  // built. Empty: the kind has no options to check.
  std::function<Expected<void>(const KindOptions&)> check;
  std::function<Expected<std::unique_ptr<Component>>(const KindContext&)> make;
};

// ---- reading options: the errors name the kind, the key, what it must be and what it was

inline Error option_error(const KindOptions& options, std::string_view key, std::string_view what) {
  const auto it = options.values.find(std::string(key));
  Error error = make_error(ErrorCode::invalid_argument,
                           std::string(options.kind) + " option '" + std::string(key) + "' must be " +
                               std::string(what) + ", got " +
                               jaus::quoted(it != options.values.end() ? it->second : std::string()));
  error.field = std::string(key);
  return error;
}

inline std::string option_number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// The option `key` as a number in [min, max] ((min, max] when min_exclusive),
// or `fallback` when absent.
inline Expected<double> number_option(const KindOptions& options, std::string_view key, double min, double max,
                                      double fallback, bool min_exclusive = false) {
  const auto it = options.values.find(std::string(key));
  if (it == options.values.end()) return fallback;
  const std::string& text = it->second;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  const std::string range = (min_exclusive ? "a number > " : "a number ") + option_number_text(min) +
                            (min_exclusive ? " and <= " : "..") + option_number_text(max);
  if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value) || value < min ||
      (min_exclusive && value == min) || value > max)
    return unexpected(option_error(options, key, range));
  return value;
}

// The option `key` as seconds in [min_s, max_s], or `fallback` when absent.
inline Expected<Duration> seconds_option(const KindOptions& options, std::string_view key, double min_s, double max_s,
                                         Duration fallback, bool min_exclusive = false) {
  const auto s = number_option(options, key, min_s, max_s, std::chrono::duration<double>(fallback).count(),
                               min_exclusive);
  if (!s) return unexpected(s.error());
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(*s));
}

inline Expected<bool> bool_option(const KindOptions& options, std::string_view key, bool fallback) {
  const auto it = options.values.find(std::string(key));
  if (it == options.values.end()) return fallback;
  const std::string& text = it->second;
  if (text == "true" || text == "True" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "False" || text == "no" || text == "off") return false;
  return unexpected(option_error(options, key, "true or false"));
}

// check() of a kind whose options are read by `read` into its options struct.
template <class Read>
std::function<Expected<void>(const KindOptions&)> check_by(Read read) {
  return [read](const KindOptions& options) -> Expected<void> {
    auto o = read(options);
    if (!o) return unexpected(o.error());
    return {};
  };
}

}  // namespace jaus::rt
