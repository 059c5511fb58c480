#include "jaus/conform/reports.hpp"

#include <map>

#include "jaus/jss/catalogue.hpp"
#include "jaus/messages/catalogue.hpp"
#include "jaus/ocu/names.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::conform {

namespace {

std::string seconds(rt::Duration d) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", std::chrono::duration<double>(d).count());
  return text;
}

std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no control characters but tab, newline and return.
        if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' && ch != '\r')
          out += '?';
        else
          out += ch;
    }
  }
  return out;
}

// A Markdown table cell: no line breaks, no column separators.
std::string cell(std::string_view text) {
  std::string out;
  for (const char ch : text) out += ch == '|' ? std::string("\\|") : ch == '\n' ? std::string(" ") : std::string(1, ch);
  return out;
}

std::string message_name(std::uint16_t code) {
  const auto* info = msg::find_message(wire::Dialect::ra, code);
  return info ? std::string(info->name) : "unknown message";
}

std::string jss_message_name(std::uint16_t id) {
  const auto* info = msg::find_message(wire::Dialect::jss, id);
  return info ? std::string(info->name) : "unknown JSS message";
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789ABCDEF";
  std::string out;
  for (const auto b : bytes) {
    out += digits[b >> 4];
    out += digits[b & 0x0F];
  }
  return out.empty() ? "(empty)" : out;
}

// A JSS message (--profile jss): its ID, name and peer's JSS ID.
std::string jss_exchange_line(const Exchanged& e) {
  char id[8];
  std::snprintf(id, sizeof(id), "%04X", e.header.command_code);
  return "    " + seconds(e.at) + " s " + (e.sent ? "-> " : "<- ") + id + "h " + jss_message_name(e.header.command_code) +
         (e.sent ? " to " : " from ") + e.jss_peer->to_string() +
         (e.second ? std::string(e.sent ? " by the second client" : " to the second client") : std::string()) +
         ": " + hex(e.payload) + "\n";
}

std::string exchange_text(const std::vector<Exchanged>& exchange) {
  std::string out;
  for (const auto& e : exchange) {
    if (e.jss_peer) {
      out += jss_exchange_line(e);
      continue;
    }
    out += "    " + seconds(e.at) + " s " + (e.sent ? "-> " : "<- ") + ocu::code_text(e.header.command_code) + " " +
           message_name(e.header.command_code) + (e.sent ? " to " : " from ") +
           (e.sent ? e.header.destination : e.header.source).to_string() +
           (e.header.service_connection ? " (SC, sequence " + std::to_string(e.header.sequence) + ")" : "") +
           (e.second ? std::string(e.sent ? " by the second OCU" : " to the second OCU") : std::string()) + ": " +
           hex(e.payload) + "\n";
  }
  return out;
}

}  // namespace

std::string case_line(const CaseResult& r) {
  return std::string(to_string(r.outcome.verdict)) + "  " + r.component_text() + " " +
         std::string(r.test_case->id) + ": " + r.outcome.detail;
}

std::string summary_line(const RunReport& report) {
  return std::to_string(report.results.size()) + " cases: " + std::to_string(report.count(Verdict::pass)) +
         " passed, " + std::to_string(report.count(Verdict::fail)) + " failed, " +
         std::to_string(report.count(Verdict::skip)) + " skipped";
}

std::string junit_xml(const RunReport& report) {
  // One test suite per component, one test case per case.
  // Keyed by both IDs: RA results by their address, JSS results by their JSS ID.
  std::map<std::pair<Address, jss::JssId>, std::vector<const CaseResult*>> by_component;
  for (const auto& r : report.results)
    by_component[{r.component, r.jss_component.value_or(jss::JssId{})}].push_back(&r);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"jaus-conform " + xml_escaped(report.node) + "\" tests=\"" +
         std::to_string(report.results.size()) + "\" failures=\"" + std::to_string(report.count(Verdict::fail)) +
         "\" skipped=\"" + std::to_string(report.count(Verdict::skip)) + "\">\n";
  for (const auto& [key, results] : by_component) {
    const std::string component = results.front()->component_text();
    std::size_t failures = 0, skipped = 0;
    rt::Duration took{};
    for (const auto* r : results) {
      failures += r->outcome.verdict == Verdict::fail;
      skipped += r->outcome.verdict == Verdict::skip;
      took += r->took;
    }
    const std::string name =
        component +
        (results.front()->component_name.empty() ? std::string() : " " + results.front()->component_name);
    out += "  <testsuite name=\"" + xml_escaped(name) + "\" tests=\"" + std::to_string(results.size()) +
           "\" failures=\"" + std::to_string(failures) + "\" skipped=\"" + std::to_string(skipped) + "\" time=\"" +
           seconds(took) + "\">\n";
    for (const auto* r : results) {
      out += "    <testcase classname=\"" + xml_escaped(component) + "\" name=\"" +
             xml_escaped(r->test_case->id) + "\" time=\"" + seconds(r->took) + "\">\n";
      if (r->outcome.verdict == Verdict::fail)
        out += "      <failure message=\"" + xml_escaped(r->outcome.detail) + "\">" +
               xml_escaped(std::string(r->test_case->reference) + "\n" + exchange_text(r->exchange)) + "</failure>\n";
      else if (r->outcome.verdict == Verdict::skip)
        out += "      <skipped message=\"" + xml_escaped(r->outcome.detail) + "\"/>\n";
      else
        out += "      <system-out>" + xml_escaped(r->outcome.detail) + "</system-out>\n";
      out += "    </testcase>\n";
    }
    out += "  </testsuite>\n";
  }
  out += "</testsuites>\n";
  return out;
}

std::string markdown_report(const RunReport& report) {
  std::string out = "# JAUS conformance: " + report.node + "\n\n";
  out += "Profile `" + std::string(to_string(report.profile)) + "`. " + summary_line(report) + ".\n\n";
  out += "| verdict | component | case | what was seen | reference |\n|---|---|---|---|---|\n";
  for (const auto& r : report.results)
    out += "| " + std::string(to_string(r.outcome.verdict)) + " | " + r.component_text() +
           (r.component_name.empty() ? "" : " " + cell(r.component_name)) + " | `" + std::string(r.test_case->id) +
           "` " + cell(r.test_case->title) + " | " + cell(r.outcome.detail) + " | " + cell(r.test_case->reference) +
           " |\n";
  bool any_failure = false;
  for (const auto& r : report.results) {
    if (r.outcome.verdict != Verdict::fail) continue;
    if (!any_failure) out += "\n## Failures\n";
    any_failure = true;
    out += "\n### " + r.component_text() + " `" + std::string(r.test_case->id) + "`\n\n";
    out += std::string(r.test_case->title) + " (" + std::string(r.test_case->reference) + ").\n\n";
    out += "Seen: " + r.outcome.detail + "\n\nMessages exchanged (time since the case began, payload in hex):\n\n```\n";
    out += r.exchange.empty() ? "    (none)\n" : exchange_text(r.exchange);
    out += "```\n";
  }
  return out;
}

}  // namespace jaus::conform
