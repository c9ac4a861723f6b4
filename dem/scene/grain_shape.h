#pragma once
// The shapes of a granular mix: each a row of the shape table (dem/shape/grain_shapes.h) with
// its dimensions as ratios to the grain's size a, and a number fraction. The grain's size
// (Particles/radius or the gradation) is its largest dimension a: an ellipsoid's major semi-axis,
// as Yan and Regueiro's radii 1.0-2.5 mm (docs/ellipsoids.md, docs/stress.md). What the ratios
// are, which are valid, how the grain is made and how thin, flat and heavy it is for its size
// is the shape's own (its `ratios`, `rule`, `valid`, `add`, `scales`): this file goes through the
// table and names no shape.
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <functional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "dem/core/particle_store.h"
#include "dem/core/shape_kind.h"
#include "dem/core/types.h"
#include "dem/shape/shape_description.h"

namespace upgrain::dem {

using shapes::ShapeScales;

// The most ratios a shape of the table has.
inline constexpr std::size_t kMaxShapeRatios = 6;

struct GrainShape {
  ShapeKind kind = ShapeKind::sphere;
  std::array<double, kMaxShapeRatios> ratios{};  // the shape's own, the first ratio_count(kind)
  double number_fraction = 1.0;                  // relative weight among the mix's shapes (> 0)

  [[nodiscard]] bool is_sphere() const { return kind == ShapeKind::sphere; }
  [[nodiscard]] std::span<const double> dimensions() const;
};

// How many ratios describe a shape of kind k, and their names ("b/a", "c/a").
std::size_t ratio_count(ShapeKind k);

// The shape of kind k with these ratios (as many as the shape has) and fraction. A shape whose
// every ratio is 1 is the sphere: the sphere is the shape of equal dimensions.
GrainShape grain_shape(ShapeKind k, std::span<const double> ratios, double number_fraction = 1.0);
// A three-axis ellipsoid 1 : b/a : c/a (a sphere for 1:1:1): the scenes' usual grain.
GrainShape ellipsoid_grain(double b_over_a, double c_over_a, double number_fraction = 1.0);

// Reads one shape of Particles/shapes: "[name] d1:d2:...[@fraction]", the dimensions in any unit
// (the first is the size a) and the name a row of the shape table; without a name the ellipsoid
// "a:b:c". Throws upgrain::Error with what it could not read.
GrainShape read_grain_shape(const std::string& item);
// The shape as read_grain_shape reads it, without its fraction: "1:0.8:0.6" for an ellipsoid,
// "1:1:1" for a sphere, "<name> 1:..." for another shape; each ratio written by `number`.
std::string format_grain_shape(const GrainShape& s, const std::function<std::string(double)>& number);

// Throws upgrain::Error naming the offending shape (1-based) when its ratios break its shape's
// rule or a fraction is not positive.
void validate_shapes(const std::vector<GrainShape>& shapes);

// True when some shape of the mix is not a sphere: the store then carries shapes.
bool has_shapes(const std::vector<GrainShape>& shapes);
// The mix's shapes other than the sphere, as a plural noun: "ellipsoids"; empty for spheres.
std::string shape_nouns(const std::vector<GrainShape>& shapes);

// How thin, flat and light the shape is for its size (shape_description.h).
ShapeScales scales(const GrainShape& s);

// Adds a grain of this shape and size a (m), uniform density, to the store; `orientation` is
// not used by a sphere.
void add_grain(ParticleStore& p, const GrainShape& s, GlobalId id, double a, double density,
               const Eigen::Quaterniond& orientation, const GrainMotion& motion);
// The shape of grain i of a store, its fraction 1.
GrainShape grain_shape_of(const ParticleStore& p, std::size_t i);

// Shape index of each of n grains: the counts follow the number fractions (largest remainder),
// and the order is a seeded shuffle, so the mix does not depend on the radii.
std::vector<int> assign_shapes(const std::vector<GrainShape>& shapes, long n, std::mt19937_64& rng);

// An orientation uniformly distributed over SO(3) (Shoemake, Graphics Gems III, 1992),
// from the given generator (Eigen's UnitRandom draws from std::rand).
Eigen::Quaterniond random_orientation(std::mt19937_64& rng);

}  // namespace upgrain::dem
