#pragma once
// What describes a grain of a shape beyond the sphere's radius, as the serialisers write it: a
// shape declares the columns of the store that hold its description (its `description`), and
// the checkpoints' engine state and the snapshots write each column of the shape table once
// (grain_shapes.h, description_columns()), for every grain of a store that has shapes, a
// sphere's rows as the shape of equal axes it is there (ParticleStore::ensure_shapes).
#include <vector>

#include "dem/core/particle_store.h"

namespace upgrain::dem::shapes {

struct DescriptionColumn {
  const char* name;                          // dataset name in the files
  std::vector<Vec3> ParticleStore::*values;  // one vector per grain
  const char* doc;                           // what the three numbers are, with their unit
};

// How thin, flat and light a shape is for its size a (its largest dimension), from its ratios in
// a scene's mix (dem/scene/grain_shape.h): what the time step's limits take of it
// (dem/time_step.cc, docs/ellipsoids.md). A sphere is 1, 1, 1.
struct ShapeScales {
  double thinnest = 1.0;  // the smallest half-thickness over a (an ellipsoid's c/a)
  double flattest = 1.0;  // the largest radius of curvature over a (an ellipsoid's b/c, at its c pole)
  double volume = 1.0;    // the volume over a sphere's of radius a (an ellipsoid's b c / a^2)
};

}  // namespace upgrain::dem::shapes
