// Our components' JSS IDs (face.hpp): each RA component of the node is one
// JSS component, subsystem FaceConfig::subsystem (else the RA subsystem),
// node the RA node, component FaceConfig::component_ids[RA ID] (else the RA
// ID). Read from the node each time: components added later are covered.
#pragma once

#include <optional>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/node/node.hpp"

namespace jaus::jss_face {

struct OurComponent {
  jss::JssId jss;
  Address ra;
};

class IdMap {
 public:
  IdMap(const FaceConfig& config, const node::Node& node) : config_(config), node_(node) {}

  std::uint16_t subsystem() const;
  std::uint8_t node_id() const { return node_.config().node; }
  std::optional<jss::JssId> jss_id_of(const Address& ra_component) const;
  // Our components a JSS destination reaches (wildcards expanded), in RA ID order.
  std::vector<OurComponent> reached_by(const jss::JssId& destination) const;
  std::vector<OurComponent> all() const { return reached_by({jss::JssId::kAllSubsystems, jss::JssId::kAll, jss::JssId::kAll}); }
  // The node manager (RA component 1), or the first component.
  std::optional<OurComponent> node_manager() const;

 private:
  jss::JssId jss_of(const Address& ra) const;
  const FaceConfig& config_;
  const node::Node& node_;
};

}  // namespace jaus::jss_face
