#pragma once
// How a Drucker–Prager cone is fitted to the Mohr–Coulomb hexagon of (phi, c) (de Souza
// Neto, Perić & Owen 2008, Computational Methods for Plasticity, sect. 6.4; docs/fem.md,
// "Cone matching"). Its own header, without Eigen, so that scene options can name it.
namespace upgrain::fem {

// - outer: through the triaxial-compression corners (the outer edges of the hexagon);
// - inner: through the triaxial-extension corners;
// - plane_strain: the same collapse load as Mohr–Coulomb in plane strain. For associated
//   flow this is de Souza Neto et al.'s plane-strain match; for psi < phi the match is
//   derived in docs/fem.md (eta_bar gives Mohr–Coulomb's dilatancy in plane strain, and eta,
//   xi its strength under that flow).
enum class ConeMatching { outer, inner, plane_strain };

}  // namespace upgrain::fem
