#pragma once
// One entry of a scene file's section (docs/input.md): its name, kind, allowed values, unit and
// meaning, and where its value lives in the scene's input. Its default is the value a
// default-constructed SceneInput holds there: the member's initialiser, written once.
//
// The builders below bind an entry to a member, given as a path of member pointers from
// SceneInput (`at(&SceneInput::scene, &dem::SceneConfig::time_step)`) or as a function that
// returns a reference to it. The text of a value is converted by the parameter-file layer
// (input/parameter_file.cc, deal.II's patterns) into an EntryValue before an entry reads it.
#include <algorithm>
#include <array>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "dem/core/error.h"

namespace upgrain::coupling {
struct SceneInput;
}

namespace upgrain::coupling::input {

enum class Kind { real, integer, boolean, selection, multiple_selection, text, vector3, integer3 };

// A value as its kind converts it: real, integer, boolean, text (selection, multiple selection
// and text), three reals, three integers.
using EntryValue = std::variant<double, long, bool, std::string, std::array<double, 3>, std::array<int, 3>>;

struct Entry {
  std::string name;
  Kind kind = Kind::text;
  double min = 0.0;  // inclusive bounds of real, integer, vector3 and integer3 entries
  double max = 0.0;
  std::string choices;  // "a|b" for selection and multiple selection
  std::string unit = "-";
  std::string doc;
  // Stores a converted value; `path` ("Section/entry") names the entry in an error.
  std::function<void(SceneInput&, const EntryValue&, const std::string& path)> read;
  // The value as a scene file writes it.
  std::function<std::string(SceneInput&)> write;
};

// Shortest text that reads back as the same double, exponents without '+' or leading zeros
// ("1e-6", "5e9", "0.045").
std::string format_real(double v);
// Items joined by ", ".
std::string join(const std::vector<std::string>& items, const char* separator = ", ");
// The items of a list separated by `separator`, trimmed, empty items left out.
std::vector<std::string> split_list(const std::string& text, char separator = ',');
// The numbers of a list; throws upgrain::Error naming `path` and the item that is not a finite
// number.
std::vector<double> numbers_of(const std::string& text, const std::string& path, char separator = ',');

namespace detail {
template <class Object>
Object& follow(Object& object) {
  return object;
}
template <class Object, class Class, class Member, class... Rest>
auto& follow(Object& object, Member Class::*member, Rest... rest) {
  return follow(object.*member, rest...);
}
}  // namespace detail

// A member of SceneInput by its path of member pointers.
template <class... Members>
auto at(Members... members) {
  return [=](SceneInput & in) -> auto& { return detail::follow(in, members...); };
}

template <class Get>
using value_of = std::remove_reference_t<std::invoke_result_t<Get, SceneInput&>>;

template <class Get>
Entry real(std::string name, Get get, double min, double max, std::string unit, std::string doc) {
  return {std::move(name),
          Kind::real,
          min,
          max,
          "",
          std::move(unit),
          std::move(doc),
          [get](SceneInput& in, const EntryValue& v, const std::string&) { get(in) = std::get<double>(v); },
          [get](SceneInput& in) { return format_real(get(in)); }};
}

template <class Get>
Entry integer(std::string name, Get get, double min, double max, std::string unit, std::string doc) {
  return {std::move(name),
          Kind::integer,
          min,
          max,
          "",
          std::move(unit),
          std::move(doc),
          [get](SceneInput& in, const EntryValue& v, const std::string&) {
            get(in) = static_cast<value_of<Get>>(std::get<long>(v));
          },
          [get](SceneInput& in) { return std::to_string(get(in)); }};
}

template <class Get>
Entry boolean(std::string name, Get get, std::string doc) {
  return {std::move(name),
          Kind::boolean,
          0,
          0,
          "",
          "-",
          std::move(doc),
          [get](SceneInput& in, const EntryValue& v, const std::string&) { get(in) = std::get<bool>(v); },
          [get](SceneInput& in) { return std::string(get(in) ? "true" : "false"); }};
}

template <class Get>
Entry text(std::string name, Get get, std::string unit, std::string doc) {
  return {
      std::move(name),
      Kind::text,
      0,
      0,
      "",
      std::move(unit),
      std::move(doc),
      [get](SceneInput& in, const EntryValue& v, const std::string&) { get(in) = std::get<std::string>(v); },
      [get](SceneInput& in) { return std::string(get(in)); }};
}

// "a|b|c" of named values.
template <class Options>
std::string choices_of(const Options& options) {
  std::vector<std::string> names;
  for (const auto& o : options) names.push_back(o.first);
  return join(names, "|");
}

// One of named values: an enum, a bool or a string.
template <class Get>
Entry choice(std::string name, Get get, std::vector<std::pair<std::string, value_of<Get>>> options,
             std::string doc) {
  return {std::move(name),
          Kind::selection,
          0,
          0,
          choices_of(options),
          "-",
          std::move(doc),
          [get, options](SceneInput& in, const EntryValue& v, const std::string& path) {
            for (const auto& [n, value] : options)
              if (n == std::get<std::string>(v)) {
                get(in) = value;
                return;
              }
            throw Error(path + " = '" + std::get<std::string>(v) + "': not one of its choices");
          },
          [get, options](SceneInput& in) {
            for (const auto& [n, value] : options)
              if (value == get(in)) return n;
            throw Error("a value of no choice in a scene entry");
          }};
}

// A comma-separated subset of named values, kept in the order the file gives, without repeats.
template <class Get>
Entry subset(std::string name, Get get,
             std::vector<std::pair<std::string, typename value_of<Get>::value_type>> options,
             std::string doc) {
  return {std::move(name),
          Kind::multiple_selection,
          0,
          0,
          choices_of(options),
          "-",
          std::move(doc),
          [get, options](SceneInput& in, const EntryValue& v, const std::string&) {
            auto& values = get(in);
            values.clear();
            for (const std::string& item : split_list(std::get<std::string>(v)))
              for (const auto& [n, value] : options)
                if (n == item && std::find(values.begin(), values.end(), value) == values.end())
                  values.push_back(value);
          },
          [get, options](SceneInput& in) {
            std::vector<std::string> out;
            for (const auto& value : get(in))
              for (const auto& [n, v] : options)
                if (v == value) out.push_back(n);
            return join(out);
          }};
}

// A comma-separated subset of named flags, each a bool member.
using Flag = std::function<bool&(SceneInput&)>;
inline Entry flags(std::string name, std::vector<std::pair<std::string, Flag>> options, std::string doc) {
  return {std::move(name),
          Kind::multiple_selection,
          0,
          0,
          choices_of(options),
          "-",
          std::move(doc),
          [options](SceneInput& in, const EntryValue& v, const std::string&) {
            const std::vector<std::string> items = split_list(std::get<std::string>(v));
            for (const auto& [n, get] : options)
              get(in) = std::find(items.begin(), items.end(), n) != items.end();
          },
          [options](SceneInput& in) {
            std::vector<std::string> out;
            for (const auto& [n, get] : options)
              if (get(in)) out.push_back(n);
            return join(out);
          }};
}

// Three reals (Kind::vector3: an Eigen vector or an array) or three integers (Kind::integer3: an
// array or a C array), written as "x, y, z".
template <Kind kind, class Get>
Entry triple(std::string name, Get get, double min, double max, std::string unit, std::string doc) {
  static_assert(kind == Kind::vector3 || kind == Kind::integer3);
  using Value = std::conditional_t<kind == Kind::vector3, std::array<double, 3>, std::array<int, 3>>;
  return {std::move(name),
          kind,
          min,
          max,
          "",
          std::move(unit),
          std::move(doc),
          [get](SceneInput& in, const EntryValue& v, const std::string&) {
            const auto& a = std::get<Value>(v);
            for (int d = 0; d < 3; ++d) get(in)[d] = a[d];
          },
          [get](SceneInput& in) {
            auto& x = get(in);
            std::vector<std::string> items;
            for (int d = 0; d < 3; ++d)
              items.push_back(kind == Kind::vector3 ? format_real(x[d]) : std::to_string(x[d]));
            return join(items);
          }};
}

template <class Get>
Entry vector3(std::string name, Get get, double min, double max, std::string unit, std::string doc) {
  return triple<Kind::vector3>(std::move(name), get, min, max, std::move(unit), std::move(doc));
}

template <class Get>
Entry integer3(std::string name, Get get, double min, double max, std::string unit, std::string doc) {
  return triple<Kind::integer3>(std::move(name), get, min, max, std::move(unit), std::move(doc));
}

// A comma-separated list of reals, converted to the member's element type.
template <class Get>
Entry numbers(std::string name, Get get, std::string unit, std::string doc) {
  return {std::move(name),
          Kind::text,
          0,
          0,
          "",
          std::move(unit),
          std::move(doc),
          [get](SceneInput& in, const EntryValue& v, const std::string& path) {
            auto& values = get(in);
            values.clear();
            for (double x : numbers_of(std::get<std::string>(v), path))
              values.push_back(static_cast<typename value_of<Get>::value_type>(x));
          },
          [get](SceneInput& in) {
            std::vector<std::string> out;
            for (const auto x : get(in)) out.push_back(format_real(static_cast<double>(x)));
            return join(out);
          }};
}

}  // namespace upgrain::coupling::input
