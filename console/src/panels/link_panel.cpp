#include "jaus/console/panels/link_panel.hpp"

namespace jaus::console {

void LinkPanel::start() {
  link_timer_.start(options().link_period, [this] { pages().to_all(link()); });
}

void LinkPanel::shutdown() {
  link_timer_.stop();
  Panel::shutdown();
}

void LinkPanel::page_opened(PageId page) { pages().to_page(page, link()); }

void LinkPanel::heard(const jaus::Header& header) { heard_[node_of(header.source)] = context_.clock.now(); }

LinkFrame LinkPanel::link() const {
  std::optional<std::int64_t> last;
  for (const auto& [node, when] : heard_) {
    const auto ms = static_cast<std::int64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(context_.clock.now() - when).count());
    last = last ? std::min(*last, ms) : ms;
  }
  return LinkFrame{heard_.size(), last};
}

}  // namespace jaus::console
