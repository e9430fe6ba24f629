// Levenberg-Marquardt (More 1978, the paper's ref. [7]) on a fixed-size parameter block. The problem
// accumulates the Gauss-Newton normal equations itself, so the number of residuals can vary per frame
// without any dynamic matrix: nothing here allocates.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>

#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"

namespace visnav {

struct LmOptions {
  int max_iterations = 50;       ///< bounded loop
  double initial_lambda = 1e-4;  ///< damping relative to diag(H)
  /// Give up beyond this damping: when no step is accepted before lambda passes it, the result is kGaveUp.
  double max_lambda = 1e8;
  /// Converged when |delta| < this. Parameters are radians and metres: 1e-8 is far below anything a camera
  /// can resolve, and still reachable in double precision on the ill-conditioned far end (25 m) of the range.
  double step_tolerance = 1e-8;
  double cost_tolerance = 1e-10;      ///< converged when the relative cost decrease is below this
  double gradient_tolerance = 1e-12;  ///< converged when max |J^T r| is below this (already at the minimum)
};

template <int N>
struct LmSummary {
  /// kOk: converged (step, cost decrease or gradient below its tolerance, or a rejected step already below
  /// step_tolerance). kNotConverged: max_iterations reached. kGaveUp: the damping passed max_lambda without
  /// an accepted step while the step was still above step_tolerance (no descent found: the iterate is not a
  /// minimum). kNotEnoughData: fewer residuals than parameters, or the problem could not be linearised.
  Status status = Status::kNotConverged;
  int iterations = 0;
  int residual_count = 0;  ///< scalar residuals in the final linearisation
  double initial_cost = 0.0;
  double final_cost = 0.0;  ///< sum of squared residuals at the solution
  bool converged = false;
  Eigen::Matrix<double, N, N> information = Eigen::Matrix<double, N, N>::Zero();  ///< J^T J at the solution
};

/// Problem concept:
///   int linearize(const State&, Eigen::Matrix<double,N,N>& JtJ, Eigen::Matrix<double,N,1>& Jtr, double&
///   cost)
///       returns the number of scalar residuals (0 = cannot evaluate);
///   bool evaluate(const State&, double& cost);
/// State concept: State boxPlus(const Eigen::Matrix<double,N,1>&) const.
template <int N, typename State, typename Problem>
LmSummary<N> solveLevenbergMarquardt(Problem& problem, State& state, const LmOptions& options) {
  using MatN = Eigen::Matrix<double, N, N>;
  using VecN = Eigen::Matrix<double, N, 1>;
  LmSummary<N> summary;
  MatN jtj;
  VecN jtr;
  double cost = 0.0;
  int residuals = problem.linearize(state, jtj, jtr, cost);
  if (residuals < N) {
    summary.status = Status::kNotEnoughData;
    return summary;
  }
  summary.initial_cost = cost;
  double lambda = options.initial_lambda;
  bool gave_up = false;
  if (jtr.template lpNorm<Eigen::Infinity>() < options.gradient_tolerance) summary.converged = true;
  for (int iteration = 0; iteration < options.max_iterations && !summary.converged; ++iteration) {
    summary.iterations = iteration + 1;
    bool accepted = false;
    // Inner damping loop, bounded by max_lambda (at most ~log10(max/initial) + 1 rounds).
    for (int attempt = 0; attempt < 32 && lambda <= options.max_lambda; ++attempt) {
      MatN damped = jtj;
      damped.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      const Eigen::LDLT<MatN> ldlt(damped);
      if (ldlt.info() != Eigen::Success) {
        lambda *= 10.0;
        continue;
      }
      const VecN delta = -ldlt.solve(jtr);
      if (!delta.allFinite()) {
        lambda *= 10.0;
        continue;
      }
      const State candidate = state.boxPlus(delta);
      double candidate_cost = 0.0;
      if (problem.evaluate(candidate, candidate_cost) && candidate_cost < cost) {
        const double decrease = (cost - candidate_cost) / std::fmax(cost, 1e-300);
        state = candidate;
        lambda = std::fmax(lambda * 0.1, 1e-12);
        accepted = true;
        if (delta.norm() < options.step_tolerance || decrease < options.cost_tolerance) {
          summary.converged = true;
        }
        break;
      }
      if (delta.norm() < options.step_tolerance) {
        summary.converged = true;  // no further progress is possible at this precision
        break;
      }
      lambda *= 10.0;
    }
    residuals = problem.linearize(state, jtj, jtr, cost);
    if (residuals < N) {
      summary.status = Status::kNotEnoughData;
      return summary;
    }
    if (jtr.template lpNorm<Eigen::Infinity>() < options.gradient_tolerance) summary.converged = true;
    if (summary.converged) break;
    if (!accepted) {
      // Every damped step was rejected while still above step_tolerance: no descent direction was found.
      gave_up = lambda > options.max_lambda;
      break;
    }
  }
  summary.final_cost = cost;
  summary.residual_count = residuals;
  summary.information = jtj;
  if (summary.converged) {
    summary.status = Status::kOk;
  } else {
    summary.status = gave_up ? Status::kGaveUp : Status::kNotConverged;
  }
  return summary;
}

}  // namespace visnav
