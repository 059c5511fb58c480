// The Pose panel's reports: Report Local Pose of every local pose sensor
// (the map), with the latitude and longitude its node's global pose sensor
// last reported, to every page as `pose`.
#pragma once

#include <map>
#include <utility>

#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class PosePanel final : public Panel {
 public:
  using Panel::Panel;

  std::vector<std::string_view> views() const override {
    return {jaus::rt::operator_view::kLocalPose, jaus::rt::operator_view::kGlobalPose};
  }
  void follow(const jaus::Address& component, std::string_view view) override;

 private:
  std::map<jaus::Address, std::pair<double, double>> latitude_longitude_;  // by node
};

}  // namespace jaus::console
