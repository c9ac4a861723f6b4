#pragma once
// The preconditioner of both column solvers (elastic_column.cc: CG; frictional_column.cc:
// GMRES on the Newton tangent): smoothed-aggregation AMG (Trilinos ML), as in deal.II's
// step-40 and step-42. Private to upgrain::fem: it includes deal.II, so only those two
// translation units include it.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

namespace upgrain::fem {

// Sets `amg` up on `matrix`, the stiffness of a displacement field of `dim` components of
// polynomial degree `degree` on `dofs`.
template <int dim>
void initialize_column_amg(dealii::TrilinosWrappers::PreconditionAMG& amg,
                           const dealii::TrilinosWrappers::SparseMatrix& matrix,
                           const dealii::DoFHandler<dim>& dofs, const unsigned int degree) {
  dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic = true;
  data.higher_order_elements = degree > 1;
  // Aggregation threshold and smoother sweeps stay at deal.II's defaults (1e-4, 2):
  // 0.02 (step-31's value) cut CG iterations for Q2 but made the solve slower
  // (docs/fem.md, "Solver settings: what was tried").
  //
  // The near-null space of elasticity: AMG needs the modes the operator barely sees to
  // build coarse spaces that represent them. extract_constant_modes gives one
  // translation per displacement component. deal.II 9.4 has no rotation modes here;
  // adding them through ML's "null space: vectors" saved 10-20% of the iterations but
  // doubled the solve time of this compression-dominated problem (docs/fem.md).
  dealii::DoFTools::extract_constant_modes(dofs, dealii::ComponentMask(dim, true), data.constant_modes);
  amg.initialize(matrix, data);
}

}  // namespace upgrain::fem
