// The pose graph's residual Jacobians against numeric ones: Ceres' own GradientChecker on every
// residual block of a problem, at its current parameters. Shared by the pose-graph tests.
#pragma once

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace msislab {

/// Expects `blocks` residual blocks in the problem and each one's analytic Jacobians within 1e-6
/// (relative, Ceres' measure) of central differences with a relative step of 1e-7.
inline void expect_residual_jacobians_match(const ceres::Problem& problem, std::size_t blocks) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocks(&ids);
  ASSERT_EQ(ids.size(), blocks);
  ceres::NumericDiffOptions numeric;
  numeric.relative_step_size = 1e-7;
  for (const ceres::ResidualBlockId id : ids) {
    const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
    std::vector<double*> parameters;
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
    ceres::GradientChecker checker(cost, no_manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters.data(), 1e-6, &results)) << results.error_log;
  }
}

}  // namespace msislab
