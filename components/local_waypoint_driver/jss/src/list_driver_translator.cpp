// List Manager 1.0 and Local Waypoint List Driver 1.0 on the RA local
// waypoint driver, docs/jss.md "List Manager and Local Waypoint List Driver"; the element store:
// list_manager_elements.hpp, loading the RA driver: waypoint_driver_state.hpp.
//   Set / Delete Element (controller, any state): Confirm Element Request,
//     or Reject Element Request with the code of the first broken rule (the
//     list unchanged); element data other than format 0 with a whole Set
//     Local Waypoint is code 4. From a client that does not control the
//     component: nothing (JSS has no reply for it), logged.
//   Query Element / Element List / Element Count: anyone; Query Element is
//     answered only for an existing UID.
//   Execute List (controller, Ready): with an existing start UID, the list
//     from there (to the tail, or once round a circular list) becomes RA
//     waypoints 0..n-1 at the given speed, started by Standby + Resume;
//     without a start UID only the speed changes.
//   Query Active Element: the element the RA driver drives to, 0 when none.
#include <memory>
#include <vector>

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/translator_kit.hpp"
#include "kit_names.hpp"
#include "list_manager_elements.hpp"
#include "waypoint_driver_state.hpp"
#include "waypoint_translator.hpp"

namespace jaus::components_jss {
namespace {

class ListDriverTranslator final : public ServiceTranslator {
 public:
  explicit ListDriverTranslator(std::shared_ptr<WaypointDrivers> drivers) : drivers_(std::move(drivers)) {}

  std::string_view name() const override { return "local waypoint list driver"; }
  std::vector<ServiceUri> services(std::uint8_t ra_component_id) const override {
    if (ra_component_id != component_id::kLocalWaypointDriver) return {};
    return {ServiceUri{"urn:jaus:jss:mobility:ListManager", 1, 0},
            ServiceUri{"urn:jaus:jss:mobility:LocalWaypointListDriver", 1, 0}};
  }
  bool handles(std::uint16_t id, std::uint8_t ra_component_id) const override {
    return ra_component_id == component_id::kLocalWaypointDriver &&
           is_one_of<jss::msg::SetElement, jss::msg::DeleteElement, jss::msg::QueryElement, jss::msg::QueryElementList,
                     jss::msg::QueryElementCount, jss::msg::ExecuteList, jss::msg::QueryActiveElement>(id);
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (m.ra_component.component != component_id::kLocalWaypointDriver || !handles(m.message_id, m.ra_component.component))
      return false;
    answer(m, port);
    // Execute List reaches the RA driver itself; the rest only the face.
    if (m.message_id != jss::msg::ExecuteList::code) WaypointDrivers::heard(port, m, log_);
    return true;
  }
  bool from_ra(const RaOutbound&, FacePort&) override { return false; }

 private:
  void answer(const JssInbound& m, FacePort& port) {
    auto& elements = drivers_->state(m.ra_component).elements;
    switch (m.message_id) {
      case jss::msg::SetElement::code:
        set_elements(m, port);
        return;
      case jss::msg::DeleteElement::code:
        delete_elements(m, port);
        return;
      case jss::msg::QueryElement::code: {
        auto query = kit::decode_jss_body<jss::msg::QueryElement>(m.body);
        if (!query) {
          kit::log_malformed(port, m, jss::msg::QueryElement::name, query.error());
          return;
        }
        const ListElement* e = elements.find(query->element_uid);
        if (e == nullptr) return;  // answered only for an existing element
        jss::msg::ReportElement report{};
        report.element_uid = e->uid;
        report.previous_uid = e->previous_uid;
        report.next_uid = e->next_uid;
        report.format = e->format;
        report.element_data = e->data;
        kit::reply_jss(port, m.origin, m.our_component, report);
        return;
      }
      case jss::msg::QueryElementList::code: {
        jss::msg::ReportElementList report{};
        report.element_uids = elements.in_order();
        kit::reply_jss(port, m.origin, m.our_component, report);
        return;
      }
      case jss::msg::QueryElementCount::code: {
        jss::msg::ReportElementCount report{};
        report.element_count = static_cast<std::uint16_t>(elements.size());
        kit::reply_jss(port, m.origin, m.our_component, report);
        return;
      }
      case jss::msg::ExecuteList::code:
        execute(m, port);
        return;
      case jss::msg::QueryActiveElement::code: {
        jss::msg::ReportActiveElement report{};
        report.element_uid = drivers_->active_element(port, m.ra_component);
        kit::reply_jss(port, m.origin, m.our_component, report);
        return;
      }
      default:
        return;
    }
  }

  void set_elements(const JssInbound& m, FacePort& port) {
    auto set = kit::decode_jss_body<jss::msg::SetElement>(m.body);
    if (!set) return kit::log_malformed(port, m, jss::msg::SetElement::name, set.error());
    if (!kit::client_controls(port, m)) return ignored(m, port, "Set Element", "it does not control it");
    std::vector<ListElement> elements;
    elements.reserve(set->elements.size());
    for (const auto& record : set->elements) {
      // The list driver executes Set Local Waypoint elements only.
      const bool supported = record.format == jss::msg::element_format::kJausMessage &&
                             jss::decode_contents<jss::msg::SetLocalWaypoint>(record.element_data).has_value();
      if (!supported)
        return reject(m, port, set->request_id,
                      ElementRejection{ElementReject::unsupported_type,
                                       "element " + std::to_string(record.element_uid) +
                                           " is not a Set Local Waypoint (format 0)"});
      elements.push_back(ListElement{record.element_uid, record.previous_uid, record.next_uid, record.format,
                                     record.element_data});
    }
    auto applied = drivers_->state(m.ra_component).elements.set(elements);
    if (!applied) return reject(m, port, set->request_id, applied.error());
    kit::reply_jss(port, m.origin, m.our_component, jss::msg::ConfirmElementRequest{{set->request_id}});
  }

  void delete_elements(const JssInbound& m, FacePort& port) {
    auto del = kit::decode_jss_body<jss::msg::DeleteElement>(m.body);
    if (!del) return kit::log_malformed(port, m, jss::msg::DeleteElement::name, del.error());
    if (!kit::client_controls(port, m)) return ignored(m, port, "Delete Element", "it does not control it");
    auto removed = drivers_->state(m.ra_component).elements.remove(del->element_uids);
    if (!removed) return reject(m, port, del->request_id, removed.error());
    kit::reply_jss(port, m.origin, m.our_component, jss::msg::ConfirmElementRequest{{del->request_id}});
  }

  void execute(const JssInbound& m, FacePort& port) {
    auto run = kit::decode_jss_body<jss::msg::ExecuteList>(m.body);
    if (!run) return kit::log_malformed(port, m, jss::msg::ExecuteList::name, run.error());
    if (!kit::client_controls(port, m)) return ignored(m, port, "Execute List", "it does not control it");
    if (!WaypointDrivers::ready(port, m.ra_component))
      return ignored(m, port, "Execute List", "the driver is not Ready");
    if (!run->element_uid) return drivers_->set_speed(port, m, run->speed_mps, log_);
    auto& s = drivers_->state(m.ra_component);
    const auto route = s.elements.from(*run->element_uid);
    if (route.empty()) return ignored(m, port, "Execute List", "its start element does not exist");
    std::vector<jss::msg::SetLocalWaypoint> waypoints;
    std::vector<std::uint16_t> uids;
    for (const ListElement* e : route) {
      auto waypoint = jss::decode_contents<jss::msg::SetLocalWaypoint>(e->data);
      if (!waypoint) return ignored(m, port, "Execute List", "an element is not a waypoint");  // checked on Set
      waypoints.push_back(*waypoint);
      uids.push_back(e->uid);
    }
    s.loaded = WaypointDriverState::Loaded::element_list;
    s.route_uids = std::move(uids);
    drivers_->load(port, m, waypoints, run->speed_mps, true, log_);
  }

  void reject(const JssInbound& m, FacePort& port, std::uint8_t request_id, const ElementRejection& why) {
    log_.repeated(port, "element requests rejected", rt::LogLevel::info, [&] {
      return "element request " + std::to_string(request_id) + " from " + kit::who(m) + " rejected (code " +
             std::to_string(static_cast<int>(why.code)) + "): " + why.why;
    });
    jss::msg::RejectElementRequest reply{};
    reply.request_id = request_id;
    reply.response_code = static_cast<std::uint8_t>(why.code);
    kit::reply_jss(port, m.origin, m.our_component, reply);
  }

  void ignored(const JssInbound& m, FacePort& port, std::string_view what, std::string_view why) {
    log_.repeated(port, "list commands not executed", rt::LogLevel::info, [&] {
      return std::string(what) + " from " + kit::who(m, port) + " not executed: " + std::string(why);
    });
  }

  std::shared_ptr<WaypointDrivers> drivers_;
  kit::TranslatorLog log_;
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_list_driver_translator(std::shared_ptr<WaypointDrivers> drivers) {
  return std::make_unique<ListDriverTranslator>(std::move(drivers));
}

}  // namespace jaus::components_jss
