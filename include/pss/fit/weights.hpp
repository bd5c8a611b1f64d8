// Weight functions of the paper. θ3 is the Gaussian of §3/§4; the volume features θ1, θ2
// live with the volume code because they read voxel values.
#pragma once

#include "pss/core/platform.hpp"

namespace pss {

// θ3(d) = exp(-d²/h²), taking d² so callers never need the square root, and 1/h², what a
// sample of varying width stores (spatial/support_grid.hpp), so no division either.
PSS_INLINE float gaussian_weight(float distance2, float inv_h2) { return exp_nonpositive(-distance2 * inv_h2); }

}  // namespace pss
