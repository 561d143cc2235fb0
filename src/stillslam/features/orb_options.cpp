#include "stillslam/features/orb_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void OrbOptions::check() const {
  using namespace option_check;
  at_least("OrbOptions.n_features", n_features, 1);
  at_least("OrbOptions.n_levels", n_levels, 1);
  if (n_levels > 1) above("OrbOptions.scale_factor", scale_factor, 1);  // one level needs no factor
  in_range("OrbOptions.ini_th_fast", ini_th_fast, 1, 254);
  in_range("OrbOptions.min_th_fast", min_th_fast, 1, ini_th_fast);
  at_least("OrbOptions.fast_cell_size", fast_cell_size, 8);
}

}  // namespace stillslam
