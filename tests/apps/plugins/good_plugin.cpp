// A working plugin: kind `plugin_odometer` (option speed_mps 0..10, ID 150,
// one no built-in kind has) answers Query Velocity State with the configured
// speed; its JSS service (Velocity State Sensor, the translator kit's report
// translator) comes with it, so a JSS client asks it too, and it tells an
// operator unit to show its velocity (jaus-console --plugin). Kind, service
// and view in one file: what a kind owns.
#include "jaus/host/jss_plugin.hpp"
#include "jaus/jss/messages/mobility.hpp"
#include "jaus/jss_face/report_translator.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/runtime/component_plugin.hpp"

namespace {

constexpr std::uint8_t kOdometerId = 150;

class PluginOdometer final : public jaus::rt::Component {
 public:
  PluginOdometer(jaus::rt::ComponentConfig config, jaus::rt::Environment env, double speed_mps)
      : Component(std::move(config), std::move(env)) {
    handle<jaus::msg::QueryVelocityState>(Access::anyone, false,
                                          [this, speed_mps](const jaus::Header& header, const jaus::msg::QueryVelocityState&) {
                                            jaus::msg::ReportVelocityState report;
                                            report.velocity_x_mps = speed_mps;
                                            send(header.source, report);
                                          });
  }
};

jaus::Expected<double> speed(const jaus::rt::KindOptions& options) {
  return jaus::rt::number_option(options, "speed_mps", 0, 10, 1);
}

std::vector<jaus::rt::ComponentKind> kinds() {
  return {jaus::rt::ComponentKind{
      .name = "plugin_odometer",
      .default_id = kOdometerId,
      .options = {"speed_mps"},
      .needs = {},
      .moves_hardware = false,
      .one_per_node = false,
      .operator_views = {jaus::rt::operator_view::kVelocity},
      .check = jaus::rt::check_by(speed),
      .make = [](const jaus::rt::KindContext& k) -> jaus::Expected<std::unique_ptr<jaus::rt::Component>> {
        const auto s = speed(k.options);
        if (!s) return jaus::unexpected(s.error());
        return std::unique_ptr<jaus::rt::Component>(std::make_unique<PluginOdometer>(k.config, k.env, *s));
      }}};
}

jaus::jss_face::Translators odometer_translators(const jaus::jss_face::FaceConfig&) {
  using Translator =
      jaus::jss_face::kit::ReportTranslator<jaus::jss::msg::QueryVelocityState, jaus::jss::msg::ReportVelocityState>;
  jaus::jss_face::Translators translators;
  translators.push_back(std::make_unique<Translator>(
      "plugin odometer", kOdometerId,
      std::vector<jaus::jss_face::ServiceUri>{{"urn:jaus:jss:mobility:VelocityStateSensor", 1, 0}}));
  return translators;
}

std::vector<jaus::jss_face::TranslatorFactory> jss_services() { return {&odometer_translators}; }

}  // namespace

JAUS_COMPONENT_PLUGIN("test_odometer", kinds)
JAUS_JSS_PLUGIN("test_odometer", jss_services)
