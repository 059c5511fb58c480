// The node under the model, whole, under virtual time: a node host (as jausd
// makes it) with the node manager, the primitive driver and the local vector
// driver on the in-process simulated Clearpath platform (through the bridge,
// the Husky's emergency bit 0x08 shared with its e-stop), its JSS face, and
// its emergency holds in a state directory of its own. Around it: three RA
// operators (A, B, C) sending raw messages on a memory network, and a JSS
// client (J) sending AS5669A datagrams to the face. restart() is a jausd
// restart: the host stopped and made again from the same configuration (the
// holds file is what carries over; the platform's pressed inputs are pressed
// again on the new simulator, as the hardware would still hold them).
//
// What it shows (observe()): the last motion command jausd wrote to the
// platform, the primitive driver's state and controller, the vector driver's
// controller, and who holds the vehicle's emergency latch, each in the
// model's terms.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/core/address.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/testing/memory_link.hpp"
#include "reference_model.hpp"

namespace jaus::model {

inline const Address kPrimitiveDriver{1, 1, 33, 1};
inline const Address kVectorDriver{1, 1, 44, 1};
inline const jss::JssId kJssPrimitiveDriver{1, 1, 33};
inline const jss::JssId kJssClient{42, 1, 1};
Address address_of(Party p);  // A, B, C (J speaks through an alias the face gives it)

struct Observation {
  double left = 0, right = 0;  // the last Set Differential Output jausd wrote (percent; none: 0)
  PdState state = PdState::initialize;
  std::optional<Ctl> controller;     // nullopt: an address the model does not know (in `unknown`)
  bool c_controls_vector = false;
  std::optional<std::set<Party>> holders;  // nullopt: a holder the model does not know
  std::string unknown;               // what could not be named
  bool drive_zero() const { return left == 0 && right == 0; }
};

class ModelNode {
 public:
  explicit ModelNode(std::filesystem::path state_directory);
  ~ModelNode();
  ModelNode(const ModelNode&) = delete;
  ModelNode& operator=(const ModelNode&) = delete;

  // Virtual milliseconds since the node was first made.
  Ms now() const;
  void run_for(Ms ms);
  // Until the primitive driver has left Initialize (and the vector driver
  // too), at most `limit`: a (re)started node meets its platform.
  void wait_started(Ms limit = 3000);

  void set_link(Party p, bool up) { link_up_[static_cast<int>(p)] = up; }
  bool link_up(Party p) const { return link_up_[static_cast<int>(p)]; }

  // What each operator sends (lost while its link is down: false).
  bool request_control(Party p, std::uint8_t authority);
  bool release_control(Party p);
  bool effort(Party p, double percent);
  bool set_emergency(Party p, Target to);
  bool clear_emergency(Party p, Target to);
  bool standby(Party p);
  bool resume(Party p);
  bool set_authority(Party p, std::uint8_t authority);
  bool shutdown(Party p);
  bool reset(Party p);
  bool query_vector_driver(Party p);  // keeps C alive as the vector driver's controller
  bool take_vector(Party p);
  bool release_vector(Party p);
  bool drive_vector(Party p, double speed_mps);

  void press(bool estop, bool on);
  void restart();
  void local_clear();

  Observation observe();
  PdState pd_state();
  PdState vector_state();
  host::NodeHost& host() { return *host_; }
  const std::vector<std::string>& log() const { return log_; }

 private:
  void attach();
  void detach();
  template <class M>
  bool send_ra(Party p, const Address& to, const M& message);
  template <class M>
  bool send_jss(const jss::JssId& to, const M& message);
  std::optional<Party> party_of(const Address& a) const;

  std::filesystem::path state_directory_;
  rt::VirtualTime time_;
  rt::TimePoint epoch_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& host_link_;
  std::vector<testing::MemoryLink*> operator_links_;  // A, B, C
  std::unique_ptr<host::NodeHost> host_;
  bool link_up_[kParties] = {true, true, true, true};
  bool estop_ = false, pause_ = false;
  double left_ = 0, right_ = 0;
  std::uint16_t jss_sequence_ = 1;
  std::vector<std::string> log_;
};

}  // namespace jaus::model
