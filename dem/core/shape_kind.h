#pragma once
// Which shape a grain has: its row of the shape table (dem/shape/grain_shapes.h). A grain's
// kind is set when it is made (ParticleStore::add_sphere, add_ellipsoid; the scene's mix,
// dem/scene/grain_shape.h) and travels with it; it is never inferred from its dimensions.
#include <cstdint>

namespace upgrain::dem {

enum class ShapeKind : std::uint8_t { sphere = 0, ellipsoid = 1 };
inline constexpr int kShapeKinds = 2;

}  // namespace upgrain::dem
