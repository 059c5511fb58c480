// The JAUS link in the top bar: the nodes heard and how long ago the last
// one was, every link_period and to a page that opens.
#pragma once

#include <map>

#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class LinkPanel final : public Panel {
 public:
  explicit LinkPanel(PanelContext& context) : Panel(context), link_timer_(context.clock, context.scheduler) {}

  void start();
  void page_opened(PageId page) override;
  void heard(const jaus::Header& header) override;
  void shutdown() override;

 private:
  LinkFrame link() const;

  std::map<jaus::Address, jaus::rt::TimePoint> heard_;  // by node
  Periodic link_timer_;
};

}  // namespace jaus::console
