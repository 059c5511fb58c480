// What carries the vehicle, as a configuration names it: a platform kind
// (platform_kinds.hpp) by name, its options as text (jausd's
// `platform: {serial: /dev/ttyUSB0, baud: 115200}`), and typed sections a
// kind reads beyond its options (a Clearpath platform's mapping,
// host::ClearpathSettings). The host never names a kind: make_platform
// (platform_kinds.hpp) finds it and the kind reads its own settings.
#pragma once

#include <any>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace jaus::host {

// Settings of any type a platform kind looks up by the type's name
// (`static constexpr std::string_view kSection`), held by value: a copied
// HostConfig copies them.
class PlatformSections {
 public:
  // Sets (or replaces) the section of type T; returns it for filling in.
  template <class T>
  T& set(T section) {
    std::any& held = sections_[std::string(T::kSection)];
    held = std::move(section);
    return *std::any_cast<T>(&held);
  }
  // The section of type T, or nullptr when none was set.
  template <class T>
  const T* find() const {
    const auto it = sections_.find(T::kSection);
    return it == sections_.end() ? nullptr : std::any_cast<T>(&it->second);
  }
  template <class T>
  T* find() {
    const auto it = sections_.find(T::kSection);
    return it == sections_.end() ? nullptr : std::any_cast<T>(&it->second);
  }

 private:
  std::map<std::string, std::any, std::less<>> sections_;
};

struct PlatformSettings {
  std::string kind = "model";  // a registered platform kind (platform_kinds.hpp)
  // The kind's own options (key -> text), checked by the kind.
  std::map<std::string, std::string> options;
  PlatformSections sections;
};

}  // namespace jaus::host
