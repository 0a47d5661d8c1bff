// Whole passes against their CPU mirrors with vplkit::parity: the doctest adapter, and the grid
// of a pass's output image (its coordinates, no inputs) for compare().
#pragma once

#include <vplkit/parity/doctest.hpp>

#include "frontend/image/image.hpp"

namespace vplkit::parity {

inline kernel_inputs coordinates_of(const image& pass_output) { return grid_of(pass_output.width, pass_output.height, 0); }

}  // namespace vplkit::parity
