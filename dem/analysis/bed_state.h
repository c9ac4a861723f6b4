#pragma once
// Measures of a deposited bed: surface height and solid fraction of its core.
#include "dem/core/particle_store.h"
#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct BedState {
  double surface_height = 0.0;  // mean of the column tops (m)
  double solid_fraction = 0.0;  // in the core region below
  double core_lo[3] = {0, 0, 0};
  double core_hi[3] = {0, 0, 0};
  long particles_outside = 0;  // centroids outside the container's walls or below the floor
};

// The surface is the mean over horizontal columns (two largest diameters wide) of the
// highest particle top in each column. The solid fraction is measured by sampling a
// regular lattice of points in a core box that stays two largest diameters clear of the
// side walls, the floor and the surface (wall layers are looser; Mueller 1992), and
// counting the points that lie inside a grain (a sphere, or an ellipsoid in its own frame;
// an ellipsoid's top is its support height along z).
BedState measure_bed(const ParticleStore& p, const BoxContainer& box, int samples_per_axis = 60);

}  // namespace upgrain::dem
