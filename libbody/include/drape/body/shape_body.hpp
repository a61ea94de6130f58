// From semantic parameters z to a shaped body: the model's linear SemanticMap gives the
// initial shape coefficients, then (optionally) a Gauss-Newton refinement on the measured
// mesh makes every requested girth and height come out as asked.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>

#include <string>

namespace drape::body {

enum class ShapeTermination { converged, max_iterations, linear_only, failed };

struct ShapeOptions {
    /// Refine the coefficients until the mesh measures as requested (else: linear map only).
    bool match_measurements = true;
    int max_iterations = 10;
    /// On every matched girth and height: 0.1 % is 1 mm on a 1 m girth, a tape's resolution;
    /// the convex-hull girth is only piecewise smooth, so much tighter is not reachable.
    double relative_tolerance = 1e-3;
    bool is_valid(std::string* why = nullptr) const;
};

struct ShapeSummary {
    ShapeTermination termination = ShapeTermination::failed;
    std::string message;
    int iterations = 0;
    double max_relative_error = 0;  ///< over the matched measurements, after refinement
    BodyMeasurements measured;      ///< measured on the result

    bool usable() const { return termination != ShapeTermination::failed; }
    std::string brief_report() const;
};

/// Shapes the model for `shape`. Weight and muscle act through the linear map (they are
/// not matched exactly: weight is reported in `summary.measured.weight_kg`).
/// \throw drape::InvalidInput if `shape` or `options` is invalid.
ShapeSummary shape_body(const BodyModel& model, const SemanticShape& shape,
                        const ShapeOptions& options, ShapedBody& out);

}  // namespace drape::body
