#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>

#include <cmath>
#include <cstdio>

int main() {
    using namespace drape::body;
    const BodyModel& model = BodyModel::default_model();
    SemanticRequest request;
    request[Semantic::height_m] = 1.75;
    ShapedBody body;
    const ShapeSummary s = shape_body(model, model.prior.complete(request), ShapeOptions{}, body);
    std::printf("%s\n", s.brief_report().c_str());
    return std::abs(s.measured.height_m - 1.75) < 0.005 ? 0 : 1;
}
