#pragma once
// The shape table: one row per grain shape, in the order of ShapeKind. What a shape's contacts
// are with each other shape and with a wall is the table of dem/contact/geometry/
// pair_geometries.h. Adding a shape: docs/architecture.md, "How to add a shape".
#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <span>
#include <type_traits>
#include <utility>

#include "dem/core/shape_kind.h"
#include "dem/shape/ellipsoid.h"
#include "dem/shape/sphere.h"

namespace upgrain::dem::shapes {

template <class... S>
struct ShapeList {
  static constexpr std::size_t size = sizeof...(S);
};

using GrainShapes = ShapeList<Sphere, Ellipsoid>;

namespace detail {
template <class... S>
constexpr bool rows_in_kind_order(ShapeList<S...>) {
  int k = 0;
  return ((static_cast<int>(S::kind) == k++) && ...);
}
}  // namespace detail
static_assert(detail::rows_in_kind_order(GrainShapes{}) && GrainShapes::size == kShapeKinds,
              "one row per ShapeKind, in its order");

// The columns of the shapes' descriptions (shape_description.h): each shape's in the table's
// order, a column that several shapes declare once.
namespace detail {
template <class... S>
constexpr auto description_columns(ShapeList<S...>) {
  constexpr std::size_t most = (std::size(S::description) + ... + 0);
  std::array<DescriptionColumn, most> all{};
  std::size_t n = 0;
  auto add = [&](const DescriptionColumn& c) {
    for (std::size_t k = 0; k < n; ++k)
      if (all[k].values == c.values) return;
    all[n++] = c;
  };
  (std::ranges::for_each(S::description, add), ...);
  return std::pair{all, n};
}
}  // namespace detail
inline std::span<const DescriptionColumn> description_columns() {
  static constexpr auto columns = detail::description_columns(GrainShapes{});
  return {columns.first.data(), columns.second};
}

// Calls f.template operator()<S>() for the shape S of kind k among `list`, and returns its result.
template <class F, class... S>
decltype(auto) visit_shape(ShapeKind k, F&& f, ShapeList<S...> /*list*/) {
  using R = decltype(f.template operator()<Sphere>());
  if constexpr (std::is_void_v<R>) {
    (void)((S::kind == k ? (f.template operator()<S>(), true) : false) || ...);
  } else {
    R r{};
    (void)((S::kind == k ? (r = f.template operator()<S>(), true) : false) || ...);
    return r;
  }
}

// The same over the shape table.
template <class F>
decltype(auto) visit_shape(ShapeKind k, F&& f) {
  return visit_shape(k, std::forward<F>(f), GrainShapes{});
}

// Calls f.template operator()<S>() for every shape S of the table, in its order.
template <class F, class... S>
void for_each_shape(F&& f, ShapeList<S...> /*list*/) {
  (f.template operator()<S>(), ...);
}
template <class F>
void for_each_shape(F&& f) {
  for_each_shape(std::forward<F>(f), GrainShapes{});
}

}  // namespace upgrain::dem::shapes
