#pragma once
// The contact-geometry table: one row per pair of grain shapes (in either order) and one per
// shape against a plane wall, each naming the geometry that computes it. The force loop
// (dem/engine/force_loop_body.h) classifies each pair slot once per evaluation by the two
// grains' kinds (ParticleStore::shape) through this table: sphere pairs in closed form in the
// force pass, the others collected in one batch per geometry and solved before it.
//
// Contacts outside the force loop (the force network, the packing checks) go by the same rows,
// one at a time: pair_contact() and wall_depth().
//
// Adding a shape (docs/architecture.md, "How to add a shape"): a row per new pair and one
// for its wall contacts, with a geometry file per new kind of geometry.
#include <array>
#include <tuple>
#include <type_traits>

#include "dem/contact/geometry/ellipsoid_plane.h"
#include "dem/contact/geometry/sphere_pair.h"
#include "dem/contact/geometry/sphere_plane.h"
#include "dem/contact/geometry/support_function_pair.h"
#include "dem/shape/grain_shapes.h"

namespace upgrain::dem {

template <class A, class B, class Geometry>
struct PairRow {
  using First = A;
  using Second = B;
  using Type = Geometry;
};
template <class S, class Geometry>
struct WallRow {
  using Shape = S;
  using Type = Geometry;
};

// clang-format off
using PairGeometries = std::tuple<
    PairRow<shapes::Sphere,    shapes::Sphere,    SpherePair>,
    PairRow<shapes::Sphere,    shapes::Ellipsoid, SupportFunctionPair>,
    PairRow<shapes::Ellipsoid, shapes::Ellipsoid, SupportFunctionPair>>;
using WallGeometries = std::tuple<
    WallRow<shapes::Sphere,    SpherePlane>,
    WallRow<shapes::Ellipsoid, EllipsoidPlane>>;
// clang-format on

// The geometries that are solved in batches (all but the closed-form sphere pair), each once,
// in the order of their first row: a pair slot's class is 0 (apart), kSpherePairClass, or
// kFirstBatchClass + its geometry's index here.
namespace geometry_detail {
template <class List, class G>
struct Append;
template <class... T, class G>
struct Append<std::tuple<T...>, G> {
  using type = std::conditional_t<(std::is_same_v<T, G> || ...) || G::closed_form, std::tuple<T...>,
                                  std::tuple<T..., G>>;
};
template <class Rows, class Acc = std::tuple<>>
struct Batched;
template <class Acc>
struct Batched<std::tuple<>, Acc> {
  using type = Acc;
};
template <class Row, class... Rest, class Acc>
struct Batched<std::tuple<Row, Rest...>, Acc> {
  using type = typename Batched<std::tuple<Rest...>, typename Append<Acc, typename Row::Type>::type>::type;
};
template <class G, class List>
struct IndexOf;
template <class G, class... T>
struct IndexOf<G, std::tuple<T...>> {
  static constexpr int value = [] {
    int k = 0, found = -1;
    ((std::is_same_v<G, T> ? (found = k, ++k) : ++k), ...);
    return found;
  }();
};
}  // namespace geometry_detail

using BatchedPairGeometries = typename geometry_detail::Batched<PairGeometries>::type;
inline constexpr int kBatchedPairGeometries = std::tuple_size_v<BatchedPairGeometries>;

inline constexpr unsigned char kApartClass = 0;
inline constexpr unsigned char kSpherePairClass = 1;
inline constexpr unsigned char kFirstBatchClass = 2;

// The class of a slot whose grains have kinds a and b (bounding spheres overlapping).
inline constexpr auto kPairClass = [] {
  std::array<std::array<unsigned char, kShapeKinds>, kShapeKinds> t{};
  auto add = [&]<class Row>() {
    using G = typename Row::Type;
    const auto c = static_cast<unsigned char>(
        G::closed_form ? kSpherePairClass
                       : kFirstBatchClass + geometry_detail::IndexOf<G, BatchedPairGeometries>::value);
    const int a = static_cast<int>(Row::First::kind), b = static_cast<int>(Row::Second::kind);
    t[a][b] = c;
    t[b][a] = c;
  };
  [&]<class... R>(std::tuple<R...>*) {
    (add.template operator()<R>(), ...);
  }(static_cast<PairGeometries*>(nullptr));
  return t;
}();

namespace geometry_detail {
constexpr bool every_pair_has_a_row() {
  int rows = 0;
  [&]<class... R>(std::tuple<R...>*) { rows = sizeof...(R); }(static_cast<PairGeometries*>(nullptr));
  for (int a = 0; a < kShapeKinds; ++a)
    for (int b = 0; b < kShapeKinds; ++b)
      if (kPairClass[a][b] == kApartClass) return false;
  return rows == kShapeKinds * (kShapeKinds + 1) / 2;
}
}  // namespace geometry_detail
static_assert(geometry_detail::every_pair_has_a_row(), "one row per unordered pair of shapes");
static_assert(std::is_same_v<std::tuple_element_t<0, PairGeometries>::Type, SpherePair>,
              "sphere pairs are the closed-form class");
static_assert(std::tuple_size_v<WallGeometries> == kShapeKinds, "one wall row per shape");

// Whether a grain of kind k meets a wall in closed form (evaluated in the wall loop itself).
inline constexpr auto kWallClosedForm = [] {
  std::array<bool, kShapeKinds> t{};
  [&]<class... R>(std::tuple<R...>*) {
    ((t[static_cast<int>(R::Shape::kind)] = R::Type::closed_form), ...);
  }(static_cast<WallGeometries*>(nullptr));
  return t;
}();

// Calls f.template operator()<Geometry>() with the wall geometry of a grain of kind k.
template <class F>
decltype(auto) with_wall_geometry(ShapeKind k, F&& f) {
  return [&]<class... R>(std::tuple<R...>*) -> decltype(auto) {
    using Ret = decltype(f.template operator()<SpherePlane>());
    if constexpr (std::is_void_v<Ret>) {
      (void)((R::Shape::kind == k ? (f.template operator()<typename R::Type>(), true) : false) || ...);
    } else {
      Ret r{};
      (void)((R::Shape::kind == k ? (r = f.template operator()<typename R::Type>(), true) : false) || ...);
      return r;
    }
  }(static_cast<WallGeometries*>(nullptr));
}

// Calls f.template operator()<Geometry>() with the pair geometry of grains of kinds a and b.
template <class F>
decltype(auto) with_pair_geometry(ShapeKind a, ShapeKind b, F&& f) {
  return [&]<class... R>(std::tuple<R...>*) -> decltype(auto) {
    using Ret = decltype(f.template operator()<SpherePair>());
    const auto is = [&]<class Row>() {
      return (Row::First::kind == a && Row::Second::kind == b) ||
             (Row::First::kind == b && Row::Second::kind == a);
    };
    if constexpr (std::is_void_v<Ret>) {
      (void)((is.template operator()<R>() ? (f.template operator()<typename R::Type>(), true) : false) ||
             ...);
    } else {
      Ret r{};
      (void)((is.template operator()<R>() ? (r = f.template operator()<typename R::Type>(), true) : false) ||
             ...);
      return r;
    }
  }(static_cast<PairGeometries*>(nullptr));
}

// Contacts outside the force loop (the force network, the packing checks), by the same table:
// one pair at a time, cold (no warm start, no radius held from first touch).
// The geometry of grains i and j of `p`: body 1 is i, the normal from i to j. `shift_j` moves j
// by a lattice vector of a periodic cell, to its image next to i (the force network's pairs
// across a face: docs/periodic.md); zero leaves the position's bits as they are.
inline ContactGeometry pair_contact(const ParticleStore& p, std::size_t i, std::size_t j,
                                    ContactSolverStats& stats, const Vec3& shift_j = Vec3::Zero()) {
  return with_pair_geometry(p.kind(i), p.kind(j),
                            [&]<class G>() { return G::contact(p, i, j, shift_j, stats); });
}
// How far grain i of `p` reaches behind `wall` (> 0: overlap).
inline double wall_depth(const ParticleStore& p, std::size_t i, const PlaneWall& wall) {
  return with_wall_geometry(p.kind(i), [&]<class G>() { return G::depth(p, i, wall); });
}

}  // namespace upgrain::dem
