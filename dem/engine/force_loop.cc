#include "dem/engine/force_loop.h"

#include "dem/engine/force_loop_body.h"

namespace upgrain::dem {

// Each summation's instantiations compile in a translation unit of their own
// (force_loop_fast.cc, force_loop_deterministic.cc).
namespace force_loop_detail {
extern template ForceLoops force_loops_for<Summation::fast>(const EffectSet&, bool);
extern template ForceLoops force_loops_for<Summation::deterministic>(const EffectSet&, bool);
}  // namespace force_loop_detail

ForceLoops select_force_loops(const EffectSet& effects, bool shapes, Summation summation) {
  return summation == Summation::fast
             ? force_loop_detail::force_loops_for<Summation::fast>(effects, shapes)
             : force_loop_detail::force_loops_for<Summation::deterministic>(effects, shapes);
}

}  // namespace upgrain::dem
