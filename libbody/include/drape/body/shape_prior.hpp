// Per-gender Gaussian prior over the ten continuous semantic parameters, derived from
// the ANSUR II public release (Gordon C.C. et al., 2012 Anthropometric Survey of U.S. Army
// Personnel: Methods and Summary Statistics, NATICK/TR-15/007, 2014). Public domain data.
#pragma once

#include <drape/body/semantic_shape.hpp>

#include <Eigen/Core>

namespace drape::body {

/// Mean and covariance of one gender, in Semantic order and SI units.
struct GaussianPrior {
    Eigen::Matrix<double, kSemanticCount, 1> mean;
    Eigen::Matrix<double, kSemanticCount, kSemanticCount> covariance;
    Eigen::Matrix<double, kSemanticCount, 1> min;  ///< plausible range (0.5th percentile)
    Eigen::Matrix<double, kSemanticCount, 1> max;  ///< plausible range (99.5th percentile)
    int sample_count = 0;                          ///< number of records it was derived from
};

struct ShapePrior {
    GaussianPrior female;
    GaussianPrior male;

    const GaussianPrior& of(Gender g) const { return g == Gender::female ? female : male; }

    /// The built-in prior (ANSUR II figures embedded as constants; defined in the generated
    /// src/ansur_prior_data.cpp, see docs/shape-prior.md to regenerate it).
    static ShapePrior ansur2();

    /// Completes a partial request: unspecified parameters take the conditional mean of the
    /// gender's Gaussian given the specified ones,
    ///   x_u = mean_u + S_ug S_gg^-1 (x_g - mean_g),
    /// and given values are returned unchanged. An unspecified gender is chosen as the one
    /// under which the specified values are more likely (marginal Gaussian density, equal
    /// prior odds; female when nothing is given).
    ///
    /// Predictions are not clamped to [min, max]: a request far from the survey (e.g. a
    /// 2.2 m stature) yields predictions outside the survey's range, which is the honest
    /// extrapolation. Two exceptions keep the result a valid SemanticShape: a predicted
    /// muscle is clamped to [0, 1]; and if the predicted heights break crotch < shoulder <
    /// stature, every predicted height is re-placed between its nearest given heights (the
    /// floor counting as 0) in proportion to the gender's mean heights, or scaled from the
    /// highest given height by the ratio of the means. See docs/shape-prior.md.
    /// \throw drape::InvalidInput naming the key and value if a given value is not finite,
    ///        not positive (muscle: not in [0, 1]), or lies outside [0.5 * min, 1.5 * max] of
    ///        the chosen gender's range; if given heights are not ordered crotch < shoulder
    ///        < stature; or if the prediction is not a valid shape (a predicted length not
    ///        positive: only for combinations far outside the survey).
    SemanticShape complete(const SemanticRequest& request) const;

    /// Squared Mahalanobis distance of `shape` under its gender's Gaussian
    /// (about chi-squared with 10 degrees of freedom for surveyed people: mean 10).
    /// \throw drape::InvalidInput if that covariance is not positive definite.
    double mahalanobis2(const SemanticShape& shape) const;
};

}  // namespace drape::body
