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

}  // namespace upgrain::dem::shapes
