// The 80 cases of the thesis's Table 5-2 grid (4 speeds × 4 depths × 5 friction values), each the
// default configuration otherwise, for the benchmarks.
#pragma once

#include "rotbeam/config.hpp"

#include <vector>

inline std::vector<rotbeam::Config> table_5_2_cases() {
  std::vector<rotbeam::Config> cases;
  for (double rpm : {550.0, 1000.0, 2000.0, 3000.0})
    for (double depth : {0.02, 0.04, 0.06, 0.08})
      for (double mu : {0.1, 0.3, 0.4, 0.5, 0.7}) {
        rotbeam::Config c = rotbeam::load_config_string("", {});
        c.beam.speed_rpm = rpm;
        c.surface.depth_fraction = depth;
        c.contact.friction.mu = mu;
        cases.push_back(c);
      }
  return cases;
}
