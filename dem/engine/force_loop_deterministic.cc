// The force loop's instantiations for the deterministic summation (force_loop_body.h).
#include "dem/engine/force_loop_body.h"

namespace upgrain::dem::force_loop_detail {

template ForceLoops force_loops_for<Summation::deterministic>(const EffectSet&, bool, std::string_view);

}  // namespace upgrain::dem::force_loop_detail
