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

    /// The built-in prior (ANSUR II figures embedded as constants).
    static ShapePrior ansur2();

    /// Completes a partial request: unspecified parameters take the conditional mean of the
    /// gender's Gaussian given the specified ones. An unspecified gender is chosen as the
    /// one under which the specified values are more likely (female when nothing is given).
    /// \throw drape::InvalidInput if a given value is not finite, or lies outside
    ///        [0.5 * min, 1.5 * max] of the gender's range (naming the key and value).
    SemanticShape complete(const SemanticRequest& request) const;

    /// Squared Mahalanobis distance of `shape` under its gender's Gaussian.
    double mahalanobis2(const SemanticShape& shape) const;
};

}  // namespace drape::body
