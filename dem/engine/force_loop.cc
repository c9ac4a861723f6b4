#include "dem/engine/force_loop.h"

#include "dem/engine/force_loop_body.h"

namespace upgrain::dem {

// Each summation's instantiations compile in a translation unit of their own
// (force_loop_fast.cc, force_loop_deterministic.cc).
namespace force_loop_detail {
extern template ForceLoops force_loops_for<Summation::fast>(const EffectSet&, bool, std::string_view);
extern template ForceLoops force_loops_for<Summation::deterministic>(const EffectSet&, bool,
                                                                     std::string_view);
}  // namespace force_loop_detail

ForceLoops select_force_loops(const EffectSet& effects, bool shapes, Summation summation,
                              std::string_view law) {
  return summation == Summation::fast
             ? force_loop_detail::force_loops_for<Summation::fast>(effects, shapes, law)
             : force_loop_detail::force_loops_for<Summation::deterministic>(effects, shapes, law);
}

}  // namespace upgrain::dem
