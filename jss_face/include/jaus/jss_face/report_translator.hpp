// A JSS service whose query and report are the RA component's own (part of
// the translator kit, translator_kit.hpp; docs/jss.md, "The translator
// kit"): one description read in each dialect, so the JSS query goes to the
// RA component as it came (the same presence vector) and the RA report goes
// back to the JSS client as it is; every scaled field is a double, so
// encoding in JSS rescales it, and the JSS encoder clamps to JSS's range
// (every RA report range lies within JSS's). Commands of the service, if
// any, are the derived class's.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "jaus/jss_face/translator_kit.hpp"

namespace jaus::jss_face::kit {

template <class Query, class Report>
class ReportTranslator : public ServiceTranslator {
 public:
  ReportTranslator(std::string name, std::uint8_t ra_component_id, std::vector<ServiceUri> services)
      : name_(std::move(name)), ra_component_id_(ra_component_id), services_(std::move(services)) {}

  std::string_view name() const override { return name_; }
  std::vector<ServiceUri> services(std::uint8_t ra_component_id) const override {
    return ra_component_id == ra_component_id_ ? services_ : std::vector<ServiceUri>{};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_component_id) const override {
    return ra_component_id == ra_component_id_ && (message_id == Query::code || handles_command(message_id));
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (m.ra_component.component != ra_component_id_) return false;
    if (m.message_id != Query::code) return command(m, port);
    auto query = decode_jss_body<Query>(m.body);
    if (!query) {
      log_malformed(port, m, Query::name, query.error());
      return true;
    }
    send_ra(port, m, *query, log_);
    return true;
  }

  bool from_ra(const RaOutbound& m, FacePort& port) override {
    if (m.header.command_code != Report::code || m.header.source.component != ra_component_id_) return false;
    auto report = decode_ra<Report>(m.payload);
    if (!report) {
      // Our own component's message: a bug, not remote input.
      log_.repeated(port, "RA reports not decoded", rt::LogLevel::error, [&] {
        return std::string(Report::name) + " from " + m.header.source.to_string() +
               " not decoded: " + report.error().message();
      });
      return true;
    }
    reply_jss(port, m.to, m.our_component, *report);
    return true;
  }

 protected:
  // The service's commands (none by default).
  virtual bool handles_command(std::uint16_t) const { return false; }
  virtual bool command(const JssInbound&, FacePort&) { return false; }
  TranslatorLog& log() { return log_; }
  std::uint8_t ra_component_id() const { return ra_component_id_; }

 private:
  std::string name_;
  std::uint8_t ra_component_id_;
  std::vector<ServiceUri> services_;
  TranslatorLog log_;
};

}  // namespace jaus::jss_face::kit
