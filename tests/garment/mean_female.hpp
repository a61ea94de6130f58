// Test fixture: the mean female (the shape prior's completion of an empty request, as
// `drape dress` uses without --body) and her measurements.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>

#include <catch2/catch.hpp>

namespace drape::test {

struct MeanFemale {
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::BodyMeasurements m;
    MeanFemale() {
        REQUIRE(body::shape_body(model, model.prior.complete(body::SemanticRequest{}), body::ShapeOptions{}, shaped)
                    .usable());
        m = body::measure_body(model, shaped.vertices);
    }
};

}  // namespace drape::test
