// How deformation gradients are interpolated in a state transfer (seed 000 §3.2; deformation_interpolation.hpp
// does it): apart, so that the transfer's settings are known without Eigen's eigensolver behind them.
#pragma once

namespace loom {

enum class IsoMode { iso0, iso1, iso2 };

}  // namespace loom
