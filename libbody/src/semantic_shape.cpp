#include <drape/body/semantic_shape.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <string>

namespace drape::body {

std::string_view to_string(Gender g) {
    return g == Gender::female ? "female" : "male";
}

Gender parse_gender(std::string_view s) {
    if (s == "female") return Gender::female;
    if (s == "male") return Gender::male;
    throw drape::InvalidInput("gender = \"" + std::string(s) +
                              "\" is not a gender (expected \"female\" or \"male\")");
}

bool SemanticShape::is_valid(std::string* why) const {
    const auto fail = [why](const std::string& message) {
        if (why) *why = message;
        return false;
    };
    const auto key = [](Semantic s) {
        return std::string(kSemanticKeys[static_cast<std::size_t>(s)]);
    };
    for (int k = 0; k < kSemanticCount; ++k) {
        const auto s = static_cast<Semantic>(k);
        const double v = values[k];
        if (!std::isfinite(v)) return fail(detail::concat(key(s), " = ", v, " is not finite"));
        if (s == Semantic::muscle) {
            if (v < 0.0 || v > 1.0)
                return fail(detail::concat(key(s), " = ", v, " is outside [0, 1]"));
        } else if (v <= 0.0) {
            return fail(detail::concat(key(s), " = ", v, " is not positive"));
        }
    }
    const double crotch = (*this)[Semantic::crotch_height_m];
    const double shoulder = (*this)[Semantic::shoulder_height_m];
    const double height = (*this)[Semantic::height_m];
    if (!(crotch < shoulder))
        return fail(detail::concat("crotch_height_m = ", crotch,
                                   " is not below shoulder_height_m = ", shoulder));
    if (!(shoulder < height))
        return fail(detail::concat("shoulder_height_m = ", shoulder,
                                   " is not below height_m = ", height));
    if (why) why->clear();
    return true;
}

}  // namespace drape::body
