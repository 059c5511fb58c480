// The node: hosts components and moves messages between them and the network.
//
// From the network (receive): the packet is checked (header, length, source),
// remembered in the liveness table, ACK/NAK replies are matched, large data
// sets are reassembled, and the message is queued by priority (12-15 before
// everything queued) for every local component its destination matches (255
// is broadcast at each level), with the sender's standing: what the
// transport said, made `unrecorded` when the liveness table could not record
// the sender's node (full: a flood of new sources), since nothing would then
// end the state its requests leave (issue 28; component.hpp says who may do
// what). An ACK request is answered with ACK when some
// local component took the message (from that component, so that the sender
// of a broadcast can match it) and NAK when none could (a broadcast nobody
// here took is not answered: another node may take it). A retransmitted
// copy of an ACK-requested message already delivered is ACKed again but not
// delivered again, stops excepted (duplicate_filter.hpp).
// From a local component (send): the node stamps the sequence number (per
// source and destination; service connection reports keep their own), splits
// payloads over 4080 bytes into a large data set, delivers locally what is
// addressed here and transmits what is addressed elsewhere, and retransmits
// its own ACK-requested messages a bounded number of times: per the node's
// AckTracker::Options, or per message (send_acknowledged: commands that must
// arrive over a lossy link), on a timer armed at the tracker's next deadline.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "jaus/core/large_data_sets.hpp"
#include "jaus/node/ack_tracker.hpp"
#include "jaus/node/duplicate_filter.hpp"
#include "jaus/node/liveness_table.hpp"
#include "jaus/node/peer_counters.hpp"
#include "jaus/node/priority_queue.hpp"
#include "jaus/node/sequence_counters.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/node_directory.hpp"
#include "jaus/runtime/sender_standing.hpp"

namespace jaus::node {

// Where the node's packets leave for other nodes (UDP in production).
class Link {
 public:
  virtual ~Link() = default;
  // One JAUS message: its header as a value (to route it by, never decoded
  // again) and the packet's bytes, 16-byte header and payload (at most 4080
  // bytes). The bytes are valid only during the call: copy what is kept.
  virtual void transmit(const Header& header, std::span<const std::uint8_t> packet) = 0;
  // The rate the link holds what it is given to, bits a second; 0: none.
  virtual std::uint64_t bits_per_second() const { return 0; }
};

struct NodeConfig {
  std::uint8_t subsystem = 1;
  std::uint8_t node = 1;
  wire::Dialect dialect = wire::Dialect::ra;  // how payloads from peers are read
  std::size_t inbound_queue_capacity = 1024;
  AssemblyLimits large_data_sets = RaLargeDataSets::kDefaultLimits;
  // The most payload in one packet this node sends (1..4080): a payload over
  // it goes as a large data set of pieces this size (one that requests an ACK
  // keeps 4080). Below 4080 only on a slow radio, where one full packet holds
  // the air (and a stop behind it) for long.
  std::size_t large_data_set_piece = kMaxPayloadSize;
  AckTracker::Options acks;
  DuplicateFilter::Options duplicates;
  LivenessTable::Options liveness;
  SequenceCounters::Options sequences;
};

struct NodeCounters {
  std::uint64_t packets_received = 0;
  std::uint64_t malformed = 0;           // header or length wrong
  std::uint64_t invalid_source = 0;      // source address with 0 or 255
  std::uint64_t from_self = 0;           // source is this node (looped-back broadcast)
  std::uint64_t not_for_this_node = 0;
  std::uint64_t delivered = 0;           // messages handed to a local component
  std::uint64_t undeliverable = 0;       // addressed here, no such component
  // Packets from senders the liveness table could not record (delivered as
  // unrecorded: components refuse what would outlive them).
  std::uint64_t unrecorded_senders = 0;
  std::uint64_t queue_dropped = 0;
  std::uint64_t packets_sent = 0;
  std::uint64_t acks_sent = 0;
  std::uint64_t naks_sent = 0;
  std::uint64_t send_failures = 0;       // a local message the node could not send
  // Retransmitted copies of ACK-requested messages already delivered: ACKed
  // again, not delivered again (DuplicateFilter; stops are always delivered).
  std::uint64_t duplicates_filtered = 0;
};


class Node final : public rt::Outbox, public rt::NodeDirectory {
 public:
  // How a message sent with send_acknowledged ended (AckResolution::outcome,
  // transmissions = how often it crossed the network, 0 when it never did).
  using AckCallback = std::function<void(const AckResolution&)>;

  Node(NodeConfig config, rt::Clock& clock, rt::Scheduler& scheduler, Link& link, rt::LogFn log = {});
  ~Node() override;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  // What a component hosted here is constructed with.
  rt::Environment environment();
  // Hosts and starts a component; the node's configuration observer (its node
  // manager, if any) hears of the change. A component that is itself a
  // ConfigurationObserver becomes the node's observer.
  rt::Component& add(std::unique_ptr<rt::Component> component);
  template <class C>
  C& add_as(std::unique_ptr<C> component) {
    return static_cast<C&>(add(std::move(component)));
  }
  void remove(const Address& address);
  // Orderly stop: every component shuts down (platform stopped, control
  // dropped, service connections ended, with their messages sent), then leaves.
  void shutdown(std::string_view why);
  rt::Component* find(const Address& address) const;
  // One packet from the network, its header already decoded and checked
  // (version, data flag, sizes) by the transport, which also says what it
  // knows of the sender (recorded, allowed to command).
  void receive(const PacketView& packet, rt::SenderStanding standing = rt::SenderStanding::trusted);
  // The same from raw bytes (16-byte header + payload), for sources that have
  // not decoded the header: it is decoded and checked here once.
  void receive_bytes(std::span<const std::uint8_t> bytes);
  // Whether some local component keeps state for a component of JAUS node
  // `node` of `subsystem` (controller, emergency holder, service connection
  // requester, event subscriber: Component::keeps_state_for). The transport
  // asks before it lets another address claim that node's route.
  bool holds_state_for(std::uint8_t subsystem, std::uint8_t node) const;

  // rt::Outbox: a message from a local component.
  void send(const Header& header, std::span<const std::uint8_t> payload) override;
  std::uint64_t link_bits_per_second() const override { return link_.bits_per_second(); }
  // Sends a message from a local component with an ACK request (the
  // header's ack_nak is set here), retransmitted per `policy` until answered.
  // `on_resolved` (may be empty) is called exactly once, never during this
  // call and never after the node is destroyed; it may send again:
  // - acknowledged / refused: the destination answered ACK / NAK. A
  //   broadcast destination is settled by the first node that answers;
  // - exhausted: every transmission went unanswered (called when the
  //   policy gives up: one wait after the last transmission, or its deadline);
  // - posted at once, transmissions 0, when nothing crosses a network:
  //   acknowledged when the destination is on this node and some component
  //   here matches it (local delivery is immediate and cannot be lost),
  //   refused when none does; exhausted, nothing sent, when the message
  //   cannot be tracked: more than 4080 bytes (a large data set; an ACK
  //   answers one packet) or max_pending messages already awaiting an
  //   answer (both counted as send_failures).
  // A destination both here and elsewhere (a broadcast) is delivered here
  // and settled by the network's first answer. Returns the message's key
  // (forget_acknowledged).
  AckKey send_acknowledged(const Header& header, std::span<const std::uint8_t> payload, AckPolicy policy,
                           AckCallback on_resolved);
  // Stops retransmitting a message sent with send_acknowledged (its sender
  // gave up waiting, e.g. interrupted): nothing more of it goes out and its
  // callback is never called. How many times it went out; none when it was
  // no longer pending.
  std::optional<std::uint32_t> forget_acknowledged(const AckKey& key);

  // rt::NodeDirectory.
  std::vector<const rt::Component*> local_components() const override;
  std::vector<Address> known_subsystems() const override;
  bool hosts_component(std::uint8_t component_id) const override;

  const NodeConfig& config() const { return config_; }
  const NodeCounters& counters() const { return counters_; }
  const LivenessTable& liveness() const { return liveness_; }
  const RaLargeMessageAssembler& assembler() const { return assembler_; }
  const AckTracker& acks() const { return acks_; }
  // Per peer node: packets each way, ACK outcomes, copies filtered (peer_counters.hpp).
  const PeerCounters& peer_counters() const { return peers_; }
  const DuplicateFilter& duplicates() const { return duplicates_; }

 private:
  struct Inbound {
    Header header;
    std::vector<std::uint8_t> payload;
    Address exclude;  // the local sender of a broadcast does not get it back
    rt::SenderStanding standing = rt::SenderStanding::trusted;  // local senders are trusted
  };

  bool is_local(const Address& destination) const;
  bool reaches_elsewhere(const Address& destination) const;
  std::size_t local_matches(const Address& destination, const Address& exclude) const;
  std::optional<Address> first_local_match(const Address& destination) const;
  void enqueue(Inbound message);
  void drain();
  // Payload buffers of dispatched messages are used again for the next ones:
  // copying an inbound payload allocates nothing in steady state.
  std::vector<std::uint8_t> copy_payload(std::span<const std::uint8_t> payload);
  void recycle_payload(std::vector<std::uint8_t> payload);
  void transmit(const Header& header, std::span<const std::uint8_t> payload);
  // ACK from `receiver`, the first local component that took the message;
  // NAK when none did (not for a broadcast: another node may take it).
  void answer_ack_request(const Header& header, std::optional<Address> receiver);
  // Retransmissions and give-ups are timed by the tracker's next deadline,
  // not by the housekeeping period: a 50 ms policy retransmits 50 ms later.
  void arm_ack_timer();
  void service_acks();
  void resolve(const AckResolution& resolution);
  void resolve_soon(AckCallback on_resolved, const AckResolution& resolution);
  void subsystems_changed();
  void schedule_housekeeping();
  void housekeeping();
  void log(rt::LogLevel level, const std::string& text) const;

  NodeConfig config_;
  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  Link& link_;
  rt::LogFn log_;
  std::vector<std::unique_ptr<rt::Component>> components_;
  rt::Component* configuration_holder_ = nullptr;  // the component that is the observer
  rt::ConfigurationObserver* configuration_observer_ = nullptr;
  PriorityQueue<Inbound> inbound_;
  static constexpr std::size_t kSparePayloads = 32;
  std::vector<std::vector<std::uint8_t>> spare_payloads_ = [] {
    std::vector<std::vector<std::uint8_t>> spares;
    spares.reserve(kSparePayloads);
    return spares;
  }();
  bool drain_posted_ = false;
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);  // expires with the node
  rt::TimerId housekeeping_timer_ = rt::kNoTimer;
  // A whole set is as trusted as its least trusted packet: each packet goes
  // in with its standing as its doubt (rt::doubt_of).
  RaLargeMessageAssembler assembler_;
  AckTracker acks_;
  PeerCounters peers_;
  DuplicateFilter duplicates_;
  std::map<AckKey, AckCallback> ack_callbacks_;  // of send_acknowledged messages still pending
  rt::TimerId ack_timer_ = rt::kNoTimer;
  rt::TimePoint ack_timer_due_{};
  LivenessTable liveness_;
  SequenceCounters sequences_;
  NodeCounters counters_;
  // Lines a flood repeats (malformed packets, lost peers, ...): per reason.
  rt::RepeatedLines lines_;
  // One packet at a time is built here: the link copies or sends before
  // transmit() returns, so no packet allocates.
  std::vector<std::uint8_t> tx_buffer_ = std::vector<std::uint8_t>(kHeaderSize + kMaxPayloadSize);
};

}  // namespace jaus::node
