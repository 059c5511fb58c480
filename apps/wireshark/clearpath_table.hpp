// A Clearpath message's description as a Lua table for the dissector
// (wireshark_plugin.hpp): a visitor over describe(), one overload per field
// kind of jaus/clearpath/fields.hpp. A kind it does not know fails to compile
// (the catch-all below), so a new kind gets its case here and in
// lua/clearpath.lua before it builds.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

#include "jaus/clearpath/fields.hpp"
#include "lua_text.hpp"

// Declared here too, so this header compiles with a fields.hpp before the
// packed date-time kind existed (the declaration matches its definition).
namespace jaus::clearpath::fields {
template <class T>
struct PackedDateTime;
}  // namespace jaus::clearpath::fields

namespace jaus::wireshark::clearpath_table {

namespace fields = clearpath::fields;

template <class T>
inline constexpr bool kAlwaysFalse = false;

class LuaFieldWriter {
 public:
  std::string out = "{";

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    out += "{k=\"num\",n=" + lua_string(f.name) + number_params<W, std::remove_cvref_t<T>>(f.scale, f.unit);
    if constexpr (requires { f.names; }) {
      if (!f.names.empty()) {
        out += ",vs={";
        for (const auto& v : f.names) out += "[" + std::to_string(v.value) + "]=" + lua_string(v.name) + ",";
        out += "}";
      }
    }
    out += "},";
  }
  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    out += "{k=\"datetime\",n=" + lua_string(f.name) + ",s=" + std::to_string(sizeof(T)) + "},";
  }
  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    out += "{k=\"text\",n=" + lua_string(f.name) + ",max=" + std::to_string(f.max_length) +
           (f.nul_terminated != nullptr ? ",nul=true" : "") + "},";
  }
  template <class B>
  void operator()(const fields::Flag<B>& f) {
    out += "{k=\"flag\",n=" + lua_string(f.name) + ",v=" + (f.value ? "true" : "false") + "},";
  }
  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    using T = typename std::remove_cvref_t<V>::value_type;
    out += "{k=\"list\",n=" + lua_string(f.name) + number_params<W, T>(f.scale, f.unit) + "},";
  }
  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    using Record = typename std::remove_cvref_t<V>::value_type;
    out += "{k=\"records\",n=" + lua_string(f.name) + (f.count == fields::Count::implied ? ",implied=true" : "") +
           (f.layout == fields::Layout::columns ? ",columns=true" : "") + ",body=" + body_of<Record>() + "},";
  }
  template <class R>
  void operator()(const fields::Group<R>& f) {
    out += "{k=\"group\",n=" + lua_string(f.name) + ",body=" + body_of<std::remove_cvref_t<R>>() + "},";
  }
  template <class F>
  void operator()(const F&) {
    static_assert(kAlwaysFalse<F>,
                  "clearpath_table.hpp: a field kind the dissector does not know; add its overload here and "
                  "its reader in lua/clearpath.lua");
  }

  template <class Record>
  static std::string body_of() {
    Record record{};
    LuaFieldWriter nested;
    Record::describe(record, nested);
    return nested.out + "}";
  }

 private:
  // Engineering values (double in memory) are raw / scale on the wire; integers are the raw value.
  template <class W, class T>
  static std::string number_params(double scale, std::string_view unit) {
    std::string p = ",s=" + std::to_string(sizeof(W)) + (std::is_signed_v<W> ? ",signed=true" : "");
    if constexpr (std::is_floating_point_v<T>) p += ",scale=" + lua_number(scale);
    if (!unit.empty()) p += ",unit=" + lua_string(unit);
    return p;
  }
};

}  // namespace jaus::wireshark::clearpath_table
