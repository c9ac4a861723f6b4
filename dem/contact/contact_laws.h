#pragma once
// The contact laws a scene can choose (Contact/law): one row per law. A law is a
// ContactLaw<...> of parts (law/contact_law.h) in a file of its own, with its constants in its
// normal part's `Constants`; adding one means that file and a row here (docs/architecture.md,
// "How to add a contact law").
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "dem/contact/law/hertz.h"
#include "dem/contact/law/hooke.h"
#include "dem/core/error.h"
#include "dem/core/material.h"

namespace upgrain::dem {

template <class... Laws>
struct LawList {};

// The table. The first row is the default.
using ContactLaws = LawList<HertzMindlin, Hooke>;

namespace law_detail {
template <class Law, class... L>
constexpr std::size_t index_in(LawList<L...>) {
  std::size_t k = 0, found = sizeof...(L);
  ((std::is_same_v<Law, L> ? (found = k, ++k) : ++k), ...);
  return found;
}
template <class... L>
std::variant<PairAndWall<typename L::Normal::Constants>...> constants_variant(LawList<L...>);
}  // namespace law_detail

// A law's row in the table.
template <class Law>
inline constexpr std::size_t kLawIndex = law_detail::index_in<Law>(ContactLaws{});

// The constants of a scene's law, whichever it is: its normal part's `Constants` between two
// grains and at a wall, as alternative kLawIndex<Law> (two laws may share a Constants type).
using LawConstants = decltype(law_detail::constants_variant(ContactLaws{}));

// The constants of `Law` from those of a scene whose law it is: what the force loop reads,
// once per evaluation.
template <class Law>
const PairAndWall<typename Law::Normal::Constants>& constants_of(const LawConstants& c) {
  return std::get<kLawIndex<Law>>(c);
}

// What the rest of the program needs of a law outside the force loop: its name and
// parameters (the scene file's schema), its constants from the grains' material and a scene's
// values of its parameters (SceneConfig::law_parameters), its time-step rule, and the duration
// of an undamped collision (the accuracy study's reference).
struct LawInfo {
  const char* name;
  const char* description;  // one sentence, for the scene file's documentation
  std::span<const LawParameter> parameters;
  LawConstants (*constants)(const Material&, std::span<const NamedValue>);
  LawTimeLimit (*time_limit)(const LawConstants&, const SceneTimeScales&, double rayleigh_fraction,
                             double duration_fraction);
  // A head-on collision of effective radius r*, effective mass m* and approach speed v, without
  // damping or friction: how long the grains touch (s).
  double (*collision_duration)(const LawConstants&, double r_star, double m_star, double speed);
};

namespace law_detail {
template <class L>
LawConstants constants(const Material& m, std::span<const NamedValue> values) {
  return LawConstants(std::in_place_index<kLawIndex<L>>, L::Normal::constants(m, values));
}
template <class L>
LawTimeLimit time_limit(const LawConstants& c, const SceneTimeScales& s, double rayleigh_fraction,
                        double duration_fraction) {
  return L::Normal::time_limit(constants_of<L>(c), s, rayleigh_fraction, duration_fraction);
}
template <class L>
double collision_duration(const LawConstants& c, double r_star, double m_star, double speed) {
  return L::Normal::collision_duration(constants_of<L>(c).pair, r_star, m_star, speed);
}
template <class... L>
constexpr std::array<LawInfo, sizeof...(L)> rows(LawList<L...>) {
  return {LawInfo{L::name, L::Normal::description, L::Normal::parameters, &constants<L>, &time_limit<L>,
                  &collision_duration<L>}...};
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
