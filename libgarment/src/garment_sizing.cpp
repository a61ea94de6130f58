#include <drape/garment/garment_sizing.hpp>

#include <drape/core/errors.hpp>

namespace drape::garment {

Pattern make_pattern(const GarmentSizing& g) {
    switch (g.type) {
        case GarmentType::skirt: return make_circle_skirt(g.skirt);
        case GarmentType::pants: return make_pants(g.pants);
        case GarmentType::tshirt: return make_tshirt(g.tshirt);
        case GarmentType::dress: return make_dress(g.dress);
    }
    throw InvalidInput("unknown garment type");
}

}  // namespace drape::garment
