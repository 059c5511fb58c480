// Loss on the OCU's link, both ways, with nftables in the OCU's namespace
// (this kernel has no netem): every UDP datagram leaving or entering eth0
// (all of them JAUS here; lo is never touched) is dropped with a probability,
// or all of them while partitioned.
#pragma once

#include <string>
#include <vector>

#include "network_lab.hpp"

namespace jaus::test::network {

class LinkLoss {
 public:
  LinkLoss(const NetworkLab& lab, const LabHost& host) : exec_(lab.exec_in(host)) {}

  // percent 0..100 of UDP datagrams dropped each way.
  jaus::Expected<void> set_loss(int percent) {
    loss_percent_ = percent;
    return apply();
  }
  // Everything on eth0 dropped (true) or the configured loss again (false).
  jaus::Expected<void> partition(bool on) {
    partitioned_ = on;
    return apply();
  }

 private:
  static constexpr const char* kNft = "/usr/sbin/nft";
  jaus::Expected<void> nft(std::vector<std::string> args) {
    std::vector<std::string> argv = exec_;
    argv.push_back(kNft);
    argv.insert(argv.end(), args.begin(), args.end());
    auto r = run_command(argv);
    if (!r) return jaus::unexpected(r.error());
    return {};
  }
  jaus::Expected<void> apply() {
    if (!made_) {
      if (auto r = nft({"add", "table", "inet", "jaus_loss"}); !r) return r;
      if (auto r = nft({"add", "chain", "inet", "jaus_loss", "out", "{ type filter hook output priority 0 ; }"}); !r)
        return r;
      if (auto r = nft({"add", "chain", "inet", "jaus_loss", "in", "{ type filter hook input priority 0 ; }"}); !r)
        return r;
      made_ = true;
    }
    if (auto r = nft({"flush", "table", "inet", "jaus_loss"}); !r) return r;
    if (partitioned_) {
      if (auto r = nft({"add", "rule", "inet", "jaus_loss", "out", "oifname", "eth0", "drop"}); !r) return r;
      return nft({"add", "rule", "inet", "jaus_loss", "in", "iifname", "eth0", "drop"});
    }
    if (loss_percent_ <= 0) return {};
    const std::string percent = std::to_string(loss_percent_);
    if (auto r = nft({"add", "rule", "inet", "jaus_loss", "out", "oifname", "eth0", "meta", "l4proto", "udp", "numgen",
                      "random", "mod", "100", "lt", percent, "drop"});
        !r)
      return r;
    return nft({"add", "rule", "inet", "jaus_loss", "in", "iifname", "eth0", "meta", "l4proto", "udp", "numgen",
                "random", "mod", "100", "lt", percent, "drop"});
  }

  std::vector<std::string> exec_;
  int loss_percent_ = 0;
  bool partitioned_ = false;
  bool made_ = false;
};

}  // namespace jaus::test::network
