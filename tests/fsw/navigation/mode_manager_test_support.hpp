// Inputs and hand-over parameters the mode manager's tests share (test_mode_manager*.cpp).
#pragma once

#include "visnav/navigation/mode_manager.hpp"

namespace visnav::nav::test_support {

/// A far-range fix at distance d.
inline ModeInputs farAt(double d) {
  ModeInputs in;
  in.far_valid = true;
  in.far_distance_m = d;
  return in;
}

/// A hand-over derived for a 1.5 m target seen at f = 1000 px at a 50 px radius: acquire below 30 m, fall
/// back above 40 m (round distances for the transitions the tests walk through). `beside`: the acquisition
/// beside far range (the default since stop 85) or in its own mode.
inline NavigationParams plateHandover(bool beside) {
  NavigationParams p;
  p.handover_radius_px = 50.0;
  p.near_range_min_radius_px = 37.5;
  p.acquire_beside_far_range = beside;
  return p.withDerivedHandover(1.5, 1000.0);
}

}  // namespace visnav::nav::test_support
