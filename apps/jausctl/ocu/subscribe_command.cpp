// `jausctl subscribe ADDR CODE --rate HZ`: a service connection for one
// report; each report is printed as a JSON line, the measured rate goes to
// stderr every few seconds and at the end, and the connection is terminated
// on the way out.
#include <algorithm>

#include "jaus/messages/catalogue.hpp"
#include "jaus/ocu/names.hpp"
#include "image_file.hpp"
#include "ocu_commands.hpp"
#include "jaus/ocu/rate_meter.hpp"

namespace jausctl::ocu {

namespace {

std::string report_label(std::uint16_t code) {
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, code);
  return (info ? std::string(info->name) + " " : std::string()) + "(" + code_text(code) + ")";
}

}  // namespace

int run_subscribe(OcuSession& session, const SubscribeOptions& o, CommandIo io) {
  auto& clock = session.clock();
  const std::string label = report_label(o.report_code) + " from " + o.target.to_string();
  RateMeter meter(clock.now());
  bool output_broken = false;
  const auto id = session.component().subscribe_code(
      o.target, o.report_code, o.rate_hz, o.presence_vector,
      [&](const jaus::Header& h, std::span<const std::uint8_t> payload) {
        meter.tick(clock.now());
        const Received report{h, {payload.begin(), payload.end()}};
        auto json = message_json(report, session.options().dialect);
        if (!json) {
          io.err << "jausctl subscribe: " << json.error().message() << "\n";
          return;
        }
        if (o.save_image) {
          auto saved = save_report_image(report, *o.save_image);
          if (!saved) {
            io.err << "jausctl subscribe: " << saved.error().message() << "\n";
            return;
          }
          *json = with_saved_image(std::move(*json), *saved, *o.save_image);
        }
        io.out << json_line(*json) << "\n" << std::flush;
        output_broken = !io.out;  // a closed pipe (| head): stop and terminate the connection
      });
  auto& component = session.component();
  const auto* status = component.subscription(id);
  session.run_until([&] { return status->confirmed || status->refused; }, o.timeout);
  if (!status->confirmed) {
    const auto refused = status->refused;
    component.unsubscribe(id);
    if (session.interrupted())
      io.err << "jausctl subscribe: interrupted\n";
    else if (refused)
      io.err << "jausctl subscribe: service connection for " << label << " refused: "
             << service_connection_response_text(*refused) << " (response " << int{*refused} << ")\n";
    else
      io.err << "jausctl subscribe: " << no_reply_error(o.target, o.timeout).message() << "\n";
    return kExitFailure;
  }
  io.err << "jausctl subscribe: " << label << " at " << hz_text(status->confirmed_rate_hz) << " Hz (service connection "
         << int{status->instance} << ")\n";

  const auto start = clock.now();
  const auto until = o.run_for ? start + *o.run_for : jaus::rt::TimePoint::max();
  auto next_rate = start + o.rate_every;
  const auto finished = [&] { return output_broken || (o.count && meter.count() >= *o.count); };
  while (!finished() && !session.interrupted()) {
    const auto now = clock.now();
    if (now >= until) break;
    if (now >= next_rate) {
      io.err << "jausctl subscribe: " << summary_text(meter.take_window(now)) << "\n";
      next_rate += o.rate_every;
      continue;
    }
    session.run_until(finished, std::min(until, next_rate) - now);
  }
  component.unsubscribe(id);  // Terminate Service Connection, sent before this returns

  io.err << "jausctl subscribe: " << label << ": " << summary_text(meter.total())
         << "; service connection terminated\n";
  if (o.count && meter.count() < *o.count && !session.interrupted() && !output_broken) {
    io.err << "jausctl subscribe: only " << meter.count() << " of " << *o.count << " reports within "
           << elapsed_text(clock.now() - start) << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace jausctl::ocu
