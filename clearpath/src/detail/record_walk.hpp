// Helpers shared by the visitors: counting a record's fields and visiting
// only its k-th field, for lists laid out column by column.
#pragma once

#include <cstddef>

namespace jaus::clearpath::detail {

struct FieldCounter {
  std::size_t count = 0;
  template <class F>
  void operator()(const F&) { ++count; }
};

template <class Record>
std::size_t field_count() {
  Record r{};
  FieldCounter counter;
  Record::describe(r, counter);
  return counter.count;
}

// Forwards only the field at position `target` to the inner visitor.
template <class Inner>
struct ColumnVisitor {
  Inner& inner;
  std::size_t target;
  std::size_t index = 0;
  template <class F>
  void operator()(const F& field) {
    if (index++ == target) inner(field);
  }
};

}  // namespace jaus::clearpath::detail
