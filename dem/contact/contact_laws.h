#pragma once
// The contact laws a scene can choose (Contact/law): one row per law. A law is a
// ContactLaw<...> of parts (law/contact_law.h) in a file of its own; adding one means that
// file and a row here (docs/architecture.md, "How to add a contact law").
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "dem/contact/law/hertz.h"
#include "dem/contact/law/hooke.h"
#include "dem/core/error.h"

namespace upgrain::dem {

template <class... Laws>
struct LawList {};

// The table. The first row is the default.
using ContactLaws = LawList<HertzMindlin, Hooke>;

// What the rest of the program needs of a law outside the force loop: its name and
// parameters (the scene file's schema), its constants from a scene's values of them
// (SceneConfig::law_parameters), its time-step rule.
struct LawInfo {
  const char* name;
  const char* description;  // one sentence, for the scene file's documentation
  std::span<const LawParameter> parameters;
  void (*constants)(std::span<const NamedValue>, ContactMaterial&);
  LawTimeLimit (*time_limit)(const SceneTimeScales&, double rayleigh_fraction, double duration_fraction);
};

namespace law_detail {
template <class... L>
constexpr std::array<LawInfo, sizeof...(L)> rows(LawList<L...>) {
  return {LawInfo{L::name, L::Normal::description, L::Normal::parameters, &L::Normal::constants,
                  &L::Normal::time_limit}...};
}

template <class First, class... Rest, class Make>
auto dispatch(LawList<First, Rest...>, std::string_view name, Make& make) {
  if constexpr (sizeof...(Rest) == 0) {
    if (name != First::name)
      throw Error("Contact/law = '" + std::string(name) + "' is not a known contact law");
    return make.template operator()<First>();
  } else {
    if (name == First::name) return make.template operator()<First>();
    return dispatch(LawList<Rest...>{}, name, make);
  }
}
}  // namespace law_detail

inline std::span<const LawInfo> contact_law_table() {
  static constexpr auto table = law_detail::rows(ContactLaws{});
  return table;
}

// The row of the law named `name`; throws upgrain::Error for an unknown name.
inline const LawInfo& find_contact_law(std::string_view name) {
  for (const LawInfo& l : contact_law_table())
    if (name == l.name) return l;
  throw Error("Contact/law = '" + std::string(name) + "' is not a known contact law");
}

// Calls make.template operator()<Law>() for the law named `name` and returns its result:
// the one point where a run-time law choice becomes a type (the force loops).
template <class Make>
auto with_contact_law(std::string_view name, Make make) {
  return law_detail::dispatch(ContactLaws{}, name, make);
}

}  // namespace upgrain::dem
