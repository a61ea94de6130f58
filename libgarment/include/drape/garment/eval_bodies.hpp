// The bodies of the dressing evaluation (issue 4's acceptance: `drape eval-dress`).
#pragma once

#include <drape/body/semantic_shape.hpp>

namespace drape::garment {

/// An evaluation body: a request for the shape prior by gender, stature and body mass.
struct EvalBody {
    const char* name;
    body::Gender gender;
    double height_m;
    double weight_kg;
};

/// The 5th percentile, median and 95th percentile of stature and of body mass of the ANSUR
/// II women (1,986 records) and the 5th and 95th of the men (4,082); the other measurements
/// are completed by the shape prior (body::ShapePrior::complete).
constexpr EvalBody kEvalBodies[] = {{"female_p5", body::Gender::female, 1.525, 51.3},
                                    {"female_p50", body::Gender::female, 1.626, 66.8},
                                    {"female_p95", body::Gender::female, 1.740, 87.0},
                                    {"male_p5", body::Gender::male, 1.648, 64.4},
                                    {"male_p95", body::Gender::male, 1.870, 110.6}};

}  // namespace drape::garment
