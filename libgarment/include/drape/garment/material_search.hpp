// The search for a garment's fabric (paper section 5.3, Algorithm 1,
// "MaterialParamIdentification"): the bending scale s_b of the base fabric whose static drape
// has the target mean curvature K, by L-BFGS (Ceres GradientProblem) on
// (K(s_b) − K_target)², over x = log10 s_b in the paper's range [0, 2] (×1 … ×100). The
// drape is the caller's (a warm-started static solve): the search sees K(x) only.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace drape::garment {

/// The mean curvature K (1/m) of the drape in the base fabric with bending scale 10^x.
/// Throwing drape::InvalidInput ends the search (failed).
using CurvatureOfBending = std::function<double(double log10_bending_scale)>;

struct MaterialSearchOptions {
    double min_log10_bending = 0.0;   ///< the paper's softest: gray interlock ×1
    double max_log10_bending = 2.0;   ///< the paper's stiffest: ×100
    /// Where the search starts. The paper starts from the softest (0); recovery starts from the
    /// calibrated estimate of P (docs/recovery.md), the middle of the range when it has none.
    double start_log10_bending = 1.0;
    int max_iterations = 12;          ///< L-BFGS iterations, >= 1
    /// Drapes (K evaluations, finite differences included) at most, >= 3: the search stops
    /// with the best K found when the budget is spent.
    int max_evaluations = 16;
    /// Central finite-difference step in x for dK/dx, > 0.
    double difference_step = 0.05;
    /// Stop when |K − K_target| / K_target falls below this, >= 0.
    double relative_tolerance = 0.01;
    bool is_valid(std::string* why = nullptr) const;
};

enum class MaterialSearchTermination { converged, max_iterations, at_bound, failed };

struct MaterialSearchSummary {
    MaterialSearchTermination termination = MaterialSearchTermination::failed;
    std::string message;
    double log10_bending_scale = 0;   ///< the best found
    double mean_curvature_per_m = 0;  ///< K there
    double target_per_m = 0;
    std::vector<double> history;      ///< (K − K_target)² at each accepted iterate
    int evaluations = 0;              ///< drapes (K evaluations)
    double seconds = 0;
    double bending_scale() const;
    std::string brief_report() const;
};

/// Finds log10 s_b with K(s_b) = target (least squares) by L-BFGS over x, bounded to the
/// options' range by clamping (outside it the drape is the bound's, so the cost is flat and
/// the search stops there: at_bound).
/// \throw drape::InvalidInput on invalid options or a target that is not finite and > 0.
MaterialSearchSummary search_bending(double target_mean_curvature_per_m, const CurvatureOfBending& curvature,
                                     const MaterialSearchOptions& options);

}  // namespace drape::garment
