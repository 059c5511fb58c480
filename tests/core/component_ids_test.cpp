// The RA 3.x component ID table (jaus/core/component_ids.hpp;
// docs/wire-format.md, "Component IDs").
#include <gtest/gtest.h>

#include <set>

#include "jaus/core/component_ids.hpp"

namespace jaus::component_id {
namespace {

TEST(ComponentIds, EachIdHasTheRasNameAndNoIdIsListedTwice) {
  EXPECT_EQ(ra_name(kNodeManager), "node manager");
  EXPECT_EQ(ra_name(kPrimitiveDriver), "primitive driver");
  EXPECT_EQ(ra_name(kVelocityStateSensor), "velocity state sensor");
  EXPECT_EQ(ra_name(kPrimitiveManipulator), "primitive manipulator");
  EXPECT_EQ(ra_name(kWorldModelVectorKnowledgeStore), "world model vector knowledge store");
  std::set<std::uint8_t> ids;
  for (const Named& named : kNames) {
    EXPECT_TRUE(ids.insert(named.id).second) << int(named.id) << " listed twice";
    EXPECT_FALSE(named.name.empty());
  }
}

TEST(ComponentIds, TheManipulatorRangeIsNamedAndAnUnassignedIdIsNot) {
  EXPECT_EQ(ra_name(kFirstManipulatorSensorOrDriver), "manipulator sensor/driver");
  EXPECT_EQ(ra_name(kLastManipulatorSensorOrDriver), "manipulator sensor/driver");
  EXPECT_EQ(ra_name(0), "");
  EXPECT_EQ(ra_name(2), "");
  EXPECT_EQ(ra_name(60), "");
  EXPECT_EQ(ra_name(255), "");
}

}  // namespace
}  // namespace jaus::component_id
