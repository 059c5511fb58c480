#include "model_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <sstream>

#include "model_node.hpp"

namespace jaus::model {

namespace {

constexpr Ms kSettle = 50;  // after each message, platform input, clear: a stop is due within it
constexpr Ms kTick = 100;   // streams and checks while time passes
constexpr Ms kPulse = 20;   // a platform input pressed and released at once

template <class T>
bool contains(const std::vector<T>& v, const T& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

class Runner {
 public:
  Runner(const std::filesystem::path& directory, ModelTiming timing, RunStats* stats)
      : node_(directory), model_(timing), stats_(stats) {
    node_.wait_started();
    model_.start(node_.now());
  }

  std::optional<Failure> run(const Sequence& sequence) {
    if (auto f = check()) return fail(0, *f);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      trace_.push_back("step " + std::to_string(i + 1) + " at " + std::to_string(node_.now()) +
                       " ms: " + describe(sequence[i]));
      if (auto f = apply(sequence[i])) return fail(i + 1, *f);
      if (auto f = check()) return fail(i + 1, *f);
      if (stats_) ++stats_->steps;
    }
    return std::nullopt;
  }

 private:
  Failure fail(std::size_t step, const std::string& what) {
    std::ostringstream t;
    for (const auto& line : trace_) t << "  " << line << "\n";
    t << "the model at " << node_.now() << " ms: " << model_.describe(node_.now()) << "\n";
    const auto& log = node_.log();
    t << "the node's last log lines:\n";
    for (std::size_t i = log.size() > 30 ? log.size() - 30 : 0; i < log.size(); ++i) t << "  | " << log[i] << "\n";
    return Failure{step, what, t.str()};
  }

  // Time passes in ticks: the streams go on, and the node is checked at each.
  std::optional<std::string> pass(Ms ms) {
    while (ms > 0) {
      const Ms dt = std::min(ms, kTick);
      stream();
      node_.run_for(dt);
      ms -= dt;
      if (auto f = check()) return f;
    }
    return std::nullopt;
  }

  void stream() {
    const Ms now = node_.now();
    model_.advance_to(now);
    for (const Party p : {Party::a, Party::b, Party::j}) {
      const auto& value = stick_[static_cast<int>(p)];
      if (!value) continue;
      const PdState observed = node_.pd_state();
      if (node_.effort(p, *value)) model_.effort(p, *value, now, observed);
    }
    if (keep_vector_ && node_.query_vector_driver(Party::c)) model_.c_heard_by_vector(now);
  }

  std::optional<std::string> apply(const Action& a) {
    const Ms now = node_.now();
    model_.advance_to(now);
    const PdState observed = node_.pd_state();
    const auto message = [&](bool sent, auto&& to_model) -> std::optional<std::string> {
      if (sent) to_model();
      return pass_settle();
    };
    switch (a.kind) {
      case Kind::request_control: {
        const auto authority = static_cast<std::uint8_t>(a.value);
        return message(node_.request_control(a.who, authority),
                       [&] { model_.request_control(a.who, authority, now); });
      }
      case Kind::release_control:
        return message(node_.release_control(a.who), [&] { model_.release_control(a.who, now); });
      case Kind::effort:
        return message(node_.effort(a.who, a.value), [&] { model_.effort(a.who, a.value, now, observed); });
      case Kind::stick:
        stick_[static_cast<int>(a.who)] = a.value == 0 ? std::nullopt : std::optional<double>(a.value);
        return std::nullopt;
      case Kind::set_emergency:
        return message(node_.set_emergency(a.who, a.target), [&] { model_.set_emergency(a.who, a.target, now); });
      case Kind::clear_emergency:
        return message(node_.clear_emergency(a.who, a.target),
                       [&] { model_.clear_emergency(a.who, a.target, now); });
      case Kind::standby: return message(node_.standby(a.who), [&] { model_.standby(a.who, now, observed); });
      case Kind::resume: return message(node_.resume(a.who), [&] { model_.resume(a.who, now, observed); });
      case Kind::set_authority: {
        const auto authority = static_cast<std::uint8_t>(a.value);
        return message(node_.set_authority(a.who, authority), [&] { model_.set_authority(a.who, authority, now); });
      }
      case Kind::shutdown: return message(node_.shutdown(a.who), [&] { model_.shutdown(a.who, now); });
      case Kind::reset: return message(node_.reset(a.who), [&] { model_.reset(a.who, now); });
      case Kind::link: node_.set_link(a.who, a.value != 0); return std::nullopt;
      case Kind::estop:
      case Kind::pause: {
        const bool estop = a.kind == Kind::estop;
        node_.press(estop, a.value != 0);
        model_.platform_input(estop, a.value != 0, now);
        if (a.value == 2) {  // a pulse: one period of the platform's 50 Hz safety status
          node_.run_for(kPulse);
          node_.press(estop, false);
          model_.advance_to(node_.now());
          model_.platform_input(estop, false, node_.now());
        }
        return pass_settle();
      }
      case Kind::advance: return pass(a.value);
      case Kind::restart:
        node_.restart();
        node_.wait_started();
        model_.start(node_.now());
        return std::nullopt;
      case Kind::local_clear:
        node_.local_clear();
        model_.local_clear(now);
        return pass_settle();
      case Kind::take_vector: return message(node_.take_vector(Party::c), [&] { model_.c_takes_vector(now); });
      case Kind::release_vector:
        return message(node_.release_vector(Party::c), [&] { model_.c_releases_vector(now); });
      case Kind::keep_vector: keep_vector_ = a.value != 0; return std::nullopt;
      case Kind::drive_vector: {
        const bool ready = node_.vector_state() == PdState::ready;
        return message(node_.drive_vector(Party::c, a.value / 100.0), [&] { model_.c_drives_vector(now, ready); });
      }
    }
    return std::nullopt;
  }

  std::optional<std::string> pass_settle() {
    node_.run_for(kSettle);
    return std::nullopt;
  }

  // Every rule, against what the node shows now.
  std::optional<std::string> check() {
    const Ms now = node_.now();
    model_.advance_to(now);
    const Observation o = node_.observe();
    if (stats_) ++stats_->checks;
    if (!o.unknown.empty()) return "the node shows what no operator did: " + o.unknown;

    // C's hold on the vector driver first: losing it gives the primitive driver back.
    if (!contains(model_.allowed_vector_controlled(now), o.c_controls_vector))
      return std::string("C ") + (o.c_controls_vector ? "controls" : "does not control") +
             " the vector driver; the rules say otherwise";
    model_.sync_vector_controlled(o.c_controls_vector, now);
    const auto controllers = model_.allowed_controllers(now);
    if (!contains(controllers, *o.controller)) {
      std::string allowed;
      for (const Ctl c : controllers) allowed += std::string(allowed.empty() ? "" : " or ") + name(c);
      return std::string("the primitive driver is controlled by ") + name(*o.controller) + "; the rules say " + allowed;
    }
    model_.sync_controller(*o.controller, now);

    // Every holder's hold is kept until that holder clears it (or the local clear).
    if (!o.holders || *o.holders != model_.holders()) {
      std::string seen, want;
      if (o.holders)
        for (const Party p : *o.holders) seen += name(p);
      for (const Party p : model_.holders()) want += name(p);
      return "the vehicle's emergency is held by {" + seen + "}; the holders are {" + want + "}";
    }
    if (!model_.holders().empty() && stats_) ++stats_->held;

    const auto states = model_.expected_states(now);
    if (!contains(states, o.state)) {
      std::string allowed;
      for (const PdState s : states) allowed += std::string(allowed.empty() ? "" : " or ") + name(s);
      return std::string("the primitive driver is in ") + name(o.state) + "; the rules say " + allowed;
    }

    // The drive: zero whenever a hold, Standby, a platform stop or a loss
    // says so; otherwise only what the controller commanded since the last stop.
    const std::string zero = model_.zero_required(now);
    if (!zero.empty() && stats_) ++stats_->stopped;
    if (!o.drive_zero()) {
      if (stats_) ++stats_->moving;
      std::ostringstream drive;
      drive << "jausd commands the platform (" << o.left << " %, " << o.right << " %)";
      if (!zero.empty()) return drive.str() + " while the rules require zero: " + zero;
      if (!model_.allows_drive(o.left, now) || !model_.allows_drive(o.right, now))
        return drive.str() + ": no command of the controller in effect asks for it";
    }
    return std::nullopt;
  }

  ModelNode node_;
  ReferenceModel model_;
  RunStats* stats_;
  std::array<std::optional<double>, kParties> stick_{};
  bool keep_vector_ = false;
  std::vector<std::string> trace_;
};

// splitmix64: the same numbers everywhere (std's distributions are not).
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  template <class T>
  T pick(std::initializer_list<T> items) {
    return *(items.begin() + below(static_cast<int>(items.size())));
  }
};

}  // namespace

std::optional<Failure> run_sequence(const Sequence& sequence, const std::filesystem::path& directory,
                                    RunStats* stats, ModelTiming timing) {
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  std::optional<Failure> failure;
  {
    Runner runner(directory, timing, stats);
    failure = runner.run(sequence);
  }
  std::filesystem::remove_all(directory);
  return failure;
}

Sequence generate(std::uint64_t seed, std::size_t steps) {
  Random r{seed};
  // Weights per kind: operators act often, time passes often, the platform
  // and the process less, Shutdown (a dead end until a restart) rarely.
  struct Weighted {
    Kind kind;
    int weight;
  };
  static constexpr Weighted kWeights[] = {
      {Kind::request_control, 20}, {Kind::release_control, 5}, {Kind::effort, 12},    {Kind::stick, 20},
      {Kind::set_emergency, 4},    {Kind::clear_emergency, 8},  {Kind::standby, 4},    {Kind::resume, 6},
      {Kind::set_authority, 3},    {Kind::shutdown, 1},         {Kind::reset, 2},      {Kind::link, 5},
      {Kind::estop, 3},            {Kind::pause, 2},            {Kind::advance, 30},   {Kind::restart, 2},
      {Kind::local_clear, 1},      {Kind::take_vector, 5},      {Kind::release_vector, 2}, {Kind::keep_vector, 4},
      {Kind::drive_vector, 7},
  };
  // What the generator remembers, so that clears, releases and links coming
  // back are mostly the ones that undo something.
  std::vector<Party> holding;
  bool estop = false, pause = false;
  bool down[kParties] = {};
  Party requester = Party::a;  // the last to request control: mostly the one that commands
  int total = 0;
  for (const auto& w : kWeights) total += w.weight;
  const auto effort = [&r] {
    const int v = 5 * (1 + r.below(16));  // 5..80 %, each operator's its own sign now and then
    return r.below(4) == 0 ? -v : v;
  };
  Sequence s;
  for (std::size_t i = 0; i < steps; ++i) {
    int roll = r.below(total);
    Kind kind = Kind::advance;
    for (const auto& w : kWeights) {
      if (roll < w.weight) {
        kind = w.kind;
        break;
      }
      roll -= w.weight;
    }
    Action a;
    a.kind = kind;
    const Party op = r.pick({Party::a, Party::b, Party::j});
    const Party commander = r.below(3) == 0 ? op : requester;
    switch (kind) {
      case Kind::request_control:
        a.who = op;
        a.value = r.pick({1, 2, 5});
        requester = op;
        break;
      case Kind::standby:
      case Kind::shutdown: a.who = op; break;
      case Kind::release_control:
      case Kind::resume:
      case Kind::reset: a.who = commander; break;
      case Kind::effort: a.who = commander; a.value = effort(); break;
      case Kind::stick:
        a.who = commander;
        a.value = r.below(4) == 0 ? 0 : effort();
        break;
      case Kind::set_emergency:
      case Kind::clear_emergency:
        a.who = r.pick({Party::a, Party::b, Party::j, Party::c});
        if (kind == Kind::clear_emergency && !holding.empty() && r.below(4) != 0)
          a.who = holding[static_cast<std::size_t>(r.below(static_cast<int>(holding.size())))];
        if (a.who != Party::j && r.below(3) == 0) a.target = Target::vector_driver;
        if (kind == Kind::set_emergency) holding.push_back(a.who);
        else std::erase(holding, a.who);
        break;
      case Kind::set_authority:
        a.who = commander;
        a.value = r.pick({0, 1, 3});
        break;
      case Kind::link: {
        a.who = r.pick({Party::a, Party::b, Party::j, Party::c});
        bool& is_down = down[static_cast<int>(a.who)];
        a.value = r.below(4) == 0 ? r.below(2) : is_down;  // mostly a change
        is_down = a.value == 0;
        break;
      }
      case Kind::estop:
      case Kind::pause: {
        bool& on = kind == Kind::estop ? estop : pause;
        a.value = r.below(4) == 0 ? r.below(2) : !on;
        if (!on && r.below(5) == 0) a.value = 2;  // a pulse
        on = a.value == 1;
        break;
      }
      case Kind::advance:
        a.value = r.below(4) == 0 ? 1000 * (2 + r.below(4)) : 100 * (1 + r.below(8));
        break;
      case Kind::restart:
      case Kind::local_clear: break;
      case Kind::take_vector:
      case Kind::release_vector: a.who = Party::c; break;
      case Kind::keep_vector: a.who = Party::c; a.value = r.below(3) == 0 ? 0 : 1; break;
      case Kind::drive_vector: a.who = Party::c; a.value = 10 * (2 + r.below(6)); break;
    }
    s.push_back(a);
  }
  return s;
}

Sequence shrink(Sequence failing, const std::function<bool(const Sequence&)>& fails, std::size_t budget) {
  std::size_t chunk = std::max<std::size_t>(failing.size() / 2, 1);
  while (budget > 0) {
    bool removed = false;
    for (std::size_t start = 0; start < failing.size() && budget > 0;) {
      Sequence candidate = failing;
      const auto end = std::min(failing.size(), start + chunk);
      candidate.erase(candidate.begin() + static_cast<std::ptrdiff_t>(start),
                      candidate.begin() + static_cast<std::ptrdiff_t>(end));
      --budget;
      if (fails(candidate)) {
        failing = std::move(candidate);
        removed = true;
      } else {
        start += chunk;
      }
    }
    if (chunk == 1 && !removed) break;
    if (!removed) chunk = std::max<std::size_t>(chunk / 2, 1);
  }
  // Shorter waits read better.
  for (auto& a : failing) {
    while (a.kind == Kind::advance && a.value > 100 && budget > 0) {
      Action shorter = a;
      shorter.value = std::max(100, a.value / 2 / 100 * 100);
      Sequence candidate = failing;
      candidate[static_cast<std::size_t>(&a - failing.data())] = shorter;
      --budget;
      if (!fails(candidate)) break;
      a = shorter;
    }
  }
  return failing;
}

std::filesystem::path fresh_directory(const std::string& tag) {
  static int runs = 0;
  return std::filesystem::temp_directory_path() /
         ("jaus-model-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(runs++));
}

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const auto value = std::strtoull(text, &end, 0);
  return end && *end == '\0' ? value : fallback;
}

}  // namespace jaus::model
