// Levenberg-Marquardt contract (issue 14): convergence on a known minimum, an honest kGaveUp when every
// step is rejected until the damping passes max_lambda, kNotEnoughData, the iteration bound, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "visnav/solver/levenberg_marquardt.hpp"

namespace visnav {
namespace {

/// A plain 2-vector state: boxPlus is +.
struct Vec2State {
  Vec2 x = Vec2::Zero();
  Vec2State boxPlus(const Vec2& delta) const { return {x + delta}; }
};

/// Rosenbrock as least squares: r = (1 - x, 10 (y - x^2)); minimum 0 at (1, 1).
struct Rosenbrock {
  int linearize(const Vec2State& s, Mat2& jtj, Vec2& jtr, double& cost) const {
    const double x = s.x[0];
    const double y = s.x[1];
    const Vec2 r(1.0 - x, 10.0 * (y - x * x));
    Mat2 j;
    j << -1.0, 0.0, -20.0 * x, 10.0;
    jtj = j.transpose() * j;
    jtr = j.transpose() * r;
    cost = r.squaredNorm();
    ++linearize_calls;
    return 2;
  }
  bool evaluate(const Vec2State& s, double& cost) const {
    const double x = s.x[0];
    const double y = s.x[1];
    cost = (1.0 - x) * (1.0 - x) + 100.0 * (y - x * x) * (y - x * x);
    return true;
  }
  mutable int linearize_calls = 0;
};

/// Linearises like a quadratic bowl but every candidate is worse than the current point (a broken model,
/// or a cost that cannot be evaluated away from the start): no step can ever be accepted.
struct NeverImproves {
  int linearize(const Vec2State& s, Mat2& jtj, Vec2& jtr, double& cost) const {
    jtj = Mat2::Identity();
    jtr = s.x - Vec2(3.0, -2.0);
    cost = jtr.squaredNorm();
    return 4;
  }
  bool evaluate(const Vec2State& s, double& cost) const {
    if (refuse) return false;
    cost = 1e9 + s.x.squaredNorm();
    return true;
  }
  bool refuse = false;
};

/// Only one scalar residual for two parameters.
struct Underdetermined {
  int linearize(const Vec2State&, Mat2& jtj, Vec2& jtr, double& cost) const {
    jtj.setIdentity();
    jtr.setOnes();
    cost = 1.0;
    return 1;
  }
  bool evaluate(const Vec2State&, double& cost) const {
    cost = 1.0;
    return true;
  }
};

TEST(LevenbergMarquardt, RosenbrockConvergesToTheKnownMinimum) {
  Rosenbrock problem;
  Vec2State state{Vec2(-1.2, 1.0)};  // the classic start
  LmOptions options;
  options.max_iterations = 200;
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, options);
  EXPECT_EQ(summary.status, Status::kOk);
  EXPECT_TRUE(summary.converged);
  EXPECT_NEAR(state.x[0], 1.0, 1e-6);
  EXPECT_NEAR(state.x[1], 1.0, 1e-6);
  EXPECT_NEAR(summary.initial_cost, 24.2, 1e-12);  // (2.2)^2 + 100 (1 - 1.44)^2
  EXPECT_LT(summary.final_cost, 1e-12);
  EXPECT_EQ(summary.residual_count, 2);
  EXPECT_GT(summary.iterations, 1);
  EXPECT_LE(summary.iterations, options.max_iterations);
  // The information is J^T J at the solution (1, 1): J = [-1 0; -20 10].
  Mat2 expected;
  expected << 401.0, -200.0, -200.0, 100.0;
  EXPECT_LT((summary.information - expected).norm(), 1e-4);
}

TEST(LevenbergMarquardt, StartingAtTheMinimumIsConvergedWithoutIterating) {
  Rosenbrock problem;
  Vec2State state{Vec2(1.0, 1.0)};
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, LmOptions{});
  EXPECT_EQ(summary.status, Status::kOk);
  EXPECT_TRUE(summary.converged);
  EXPECT_EQ(summary.iterations, 0);
  EXPECT_EQ(state.x, Vec2(1.0, 1.0));
}

TEST(LevenbergMarquardt, EveryStepRejectedIsGaveUpNotConverged) {
  NeverImproves problem;
  // Far from the bowl's centre (3, -2): even at max_lambda the damped step (|J^T r| / max_lambda ~ 1.4e-7)
  // is above step_tolerance, so this is no "converged at this precision" case.
  const Vec2State start{Vec2(-7.0, 8.0)};
  Vec2State state = start;
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, LmOptions{});
  EXPECT_EQ(summary.status, Status::kGaveUp);
  EXPECT_FALSE(summary.converged);
  EXPECT_EQ(summary.iterations, 1);  // the damping loop of the first iteration ran past max_lambda
  EXPECT_EQ(state.x, start.x);       // nothing was accepted
  EXPECT_EQ(summary.final_cost, summary.initial_cost);
  EXPECT_STREQ(toString(summary.status), "gave up");
}

TEST(LevenbergMarquardt, CandidatesThatCannotBeEvaluatedAreGaveUp) {
  NeverImproves problem;
  problem.refuse = true;
  Vec2State state{Vec2(-7.0, 8.0)};
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, LmOptions{});
  EXPECT_EQ(summary.status, Status::kGaveUp);
  EXPECT_FALSE(summary.converged);
}

TEST(LevenbergMarquardt, RejectedStepBelowTheStepToleranceIsConverged) {
  // The same problem next to its (linearised) minimum: the undamped step is below step_tolerance, so the
  // rejection means "no further progress at this precision", not a give-up.
  NeverImproves problem;
  Vec2State state{Vec2(3.0 + 1e-10, -2.0)};
  LmOptions options;
  options.gradient_tolerance = 0.0;  // force the damping loop
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, options);
  EXPECT_EQ(summary.status, Status::kOk);
  EXPECT_TRUE(summary.converged);
}

TEST(LevenbergMarquardt, FewerResidualsThanParametersIsNotEnoughData) {
  Underdetermined problem;
  Vec2State state{Vec2(0.1, 0.2)};
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, LmOptions{});
  EXPECT_EQ(summary.status, Status::kNotEnoughData);
  EXPECT_FALSE(summary.converged);
  EXPECT_EQ(summary.iterations, 0);
  EXPECT_EQ(state.x, Vec2(0.1, 0.2));
}

TEST(LevenbergMarquardt, IterationBoundIsRespectedAndReportedAsNotConverged) {
  Rosenbrock problem;
  Vec2State state{Vec2(-1.2, 1.0)};
  LmOptions options;
  options.max_iterations = 3;
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, options);
  EXPECT_EQ(summary.status, Status::kNotConverged);
  EXPECT_FALSE(summary.converged);
  EXPECT_EQ(summary.iterations, 3);
  EXPECT_EQ(problem.linearize_calls, 1 + 3);  // the start plus one per iteration
  EXPECT_LT(summary.final_cost, summary.initial_cost);
}

TEST(LevenbergMarquardt, ZeroIterationsLeavesTheStateAlone) {
  Rosenbrock problem;
  Vec2State state{Vec2(-1.2, 1.0)};
  LmOptions options;
  options.max_iterations = 0;
  const LmSummary<2> summary = solveLevenbergMarquardt<2>(problem, state, options);
  EXPECT_EQ(summary.status, Status::kNotConverged);
  EXPECT_EQ(summary.iterations, 0);
  EXPECT_EQ(state.x, Vec2(-1.2, 1.0));
}

TEST(LevenbergMarquardt, IsDeterministic) {
  LmOptions options;
  options.max_iterations = 200;
  Vec2State a{Vec2(-1.2, 1.0)};
  Vec2State b = a;
  Rosenbrock pa;
  Rosenbrock pb;
  const LmSummary<2> sa = solveLevenbergMarquardt<2>(pa, a, options);
  const LmSummary<2> sb = solveLevenbergMarquardt<2>(pb, b, options);
  // Bit for bit: same state, cost, iterations and information.
  EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), sizeof(double) * 2), 0);
  EXPECT_EQ(std::memcmp(&sa.final_cost, &sb.final_cost, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(sa.information.data(), sb.information.data(), sizeof(double) * 4), 0);
  EXPECT_EQ(sa.iterations, sb.iterations);
  EXPECT_EQ(sa.status, sb.status);
}

}  // namespace
}  // namespace visnav
