#pragma once
// The unbalanced-force ratio of an assembly without gravity: the mean magnitude of the grains'
// resultant forces over the mean magnitude of the contact forces, Yade's unbalancedForce
// (Smilauer et al. 2015, Yade documentation, utils.unbalancedForce). An assembly in static
// equilibrium has 0; Yade's quasi-static runs stop below 1e-2 to 1e-4. FIRE's residual
// (relaxation.h) is normalised by the weight, which a periodic cell without gravity lacks.
// A plain function over one rank's data, and the same terms summed over a whole run.
#include <span>

#include "dem/contact/contact_sample.h"
#include "dem/core/types.h"

namespace upgrain::dem {
class Simulation;
}

namespace upgrain::dem {

// `forces`: the owned grains' resultant forces; `contacts`: one evaluation's recorded contacts,
// of which the pairs whose first grain is owned (index below forces.size(), each pair once) and
// no wall contact count. 0 when no contact carries a force.
[[nodiscard]] double unbalanced_force_ratio(std::span<const Vec3> forces,
                                            std::span<const ContactSample> contacts);

// Collective: the ratio of the run's last evaluation over every rank, with its gravity in the
// resultants (|F + m g|); the sums follow the run's summation (particle_sums.h), each contact's
// term kept with its first grain, in the order of that grain's contacts. Needs the contacts
// recorded at the last step (Simulation::request_contacts).
[[nodiscard]] double unbalanced_force_ratio(const Simulation& sim);

}  // namespace upgrain::dem
