#include "action.hpp"

#include <sstream>

namespace jaus::model {

const char* name(Party p) {
  switch (p) {
    case Party::a: return "A";
    case Party::b: return "B";
    case Party::j: return "J";
    case Party::c: return "C";
  }
  return "?";
}

namespace {

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::request_control: return "request_control";
    case Kind::release_control: return "release_control";
    case Kind::effort: return "effort";
    case Kind::stick: return "stick";
    case Kind::set_emergency: return "set_emergency";
    case Kind::clear_emergency: return "clear_emergency";
    case Kind::standby: return "standby";
    case Kind::resume: return "resume";
    case Kind::set_authority: return "set_authority";
    case Kind::shutdown: return "shutdown";
    case Kind::reset: return "reset";
    case Kind::link: return "link";
    case Kind::estop: return "estop";
    case Kind::pause: return "pause";
    case Kind::advance: return "advance";
    case Kind::restart: return "restart";
    case Kind::local_clear: return "local_clear";
    case Kind::take_vector: return "take_vector";
    case Kind::release_vector: return "release_vector";
    case Kind::keep_vector: return "keep_vector";
    case Kind::drive_vector: return "drive_vector";
  }
  return "?";
}

const char* party_cpp(Party p) {
  switch (p) {
    case Party::a: return "Party::a";
    case Party::b: return "Party::b";
    case Party::j: return "Party::j";
    case Party::c: return "Party::c";
  }
  return "?";
}

}  // namespace

std::string describe(const Action& a) {
  std::ostringstream o;
  const char* to = a.target == Target::primitive_driver ? "the primitive driver" : "the vector driver";
  switch (a.kind) {
    case Kind::request_control: o << name(a.who) << " requests control, authority " << a.value; break;
    case Kind::release_control: o << name(a.who) << " releases control"; break;
    case Kind::effort: o << name(a.who) << " sends Set Wrench Effort " << a.value << "%"; break;
    case Kind::stick:
      if (a.value == 0) o << name(a.who) << " lets go of the stick";
      else o << name(a.who) << " streams Set Wrench Effort " << a.value << "% at 10 Hz";
      break;
    case Kind::set_emergency: o << name(a.who) << " sends Set Emergency to " << to; break;
    case Kind::clear_emergency: o << name(a.who) << " sends Clear Emergency to " << to; break;
    case Kind::standby: o << name(a.who) << " sends Standby"; break;
    case Kind::resume: o << name(a.who) << " sends Resume"; break;
    case Kind::set_authority: o << name(a.who) << " sets the component's authority to " << a.value; break;
    case Kind::shutdown: o << name(a.who) << " sends Shutdown"; break;
    case Kind::reset: o << name(a.who) << " sends Reset"; break;
    case Kind::link: o << name(a.who) << "'s link " << (a.value ? "comes back" : "is lost"); break;
    case Kind::estop:
      o << "the platform's e-stop is " << (a.value == 2 ? "pressed for 20 ms" : a.value ? "pressed" : "released");
      break;
    case Kind::pause: o << "the platform's pause is " << (a.value == 2 ? "on for 20 ms" : a.value ? "on" : "off"); break;
    case Kind::advance: o << a.value << " ms pass"; break;
    case Kind::restart: o << "jausd restarts"; break;
    case Kind::local_clear: o << "the local clear (SIGUSR1)"; break;
    case Kind::take_vector: o << name(a.who) << " requests control of the vector driver"; break;
    case Kind::release_vector: o << name(a.who) << " releases the vector driver"; break;
    case Kind::keep_vector:
      o << name(a.who) << (a.value ? " keeps talking to" : " stops talking to") << " the vector driver";
      break;
    case Kind::drive_vector: o << name(a.who) << " sends Set Local Vector, " << a.value << " cm/s"; break;
  }
  return o.str();
}

std::string to_cpp(const Sequence& s) {
  std::ostringstream o;
  for (const Action& a : s) {
    o << "    {Kind::" << kind_name(a.kind) << ", " << party_cpp(a.who) << ", " << a.value;
    if (a.target != Target::primitive_driver) o << ", Target::vector_driver";
    o << "},  // " << describe(a) << "\n";
  }
  return o.str();
}

}  // namespace jaus::model
