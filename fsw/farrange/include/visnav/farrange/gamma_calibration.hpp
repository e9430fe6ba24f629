// Calibration of gamma in eq. 16 (d = gamma / sqrt(n)): each frame at a known distance d with target cluster
// size n gives gamma = d * sqrt(n) (the paper's example: 25 m at 1/30 scale = 750 m, 16 px -> 3000). Several
// frames are combined robustly: median, then the mean of the values within 3 scaled MADs of it.
// Ground/init-time code (visnav-calibrate-gamma): allocates.
#pragma once

#include <vector>

namespace visnav::far {

struct GammaSample {
  double distance_m = 0.0;
  double cluster_pixels = 0.0;  ///< n of eq. 16 as the estimator reports it (cluster_pixels)
};

struct GammaEstimate {
  bool ok = false;
  double gamma = 0.0;   ///< [m px^0.5]
  double median = 0.0;  ///< median of the per-frame values
  double spread = 0.0;  ///< 1.4826 * MAD / median (relative robust spread)
  int samples = 0;      ///< valid samples (d > 0, n > 0)
  int inliers = 0;      ///< samples averaged
};

/// gamma of one frame; 0 when d or n is not positive.
double gammaOf(const GammaSample& sample);
GammaEstimate calibrateGamma(const std::vector<GammaSample>& samples);

}  // namespace visnav::far
