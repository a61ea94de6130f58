#include <drape/garment/parameter_spec.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <sstream>

namespace drape::garment {

void check_parameter(const std::string& garment, const char* name, double value, double min,
                     double max, const char* unit, const char* meaning) {
    if (std::isfinite(value) && value >= min && value <= max) return;
    std::ostringstream os;
    os << garment << ": parameter " << name << " = " << value << " " << unit
       << " is outside [" << min << ", " << max << "] " << unit << " (" << meaning << ")";
    throw InvalidInput(os.str());
}

}  // namespace drape::garment
