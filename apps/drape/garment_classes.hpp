// From what libvision sees in a photo to what libgarment can make: the mapping of
// drape::vision::GarmentType (image classes) onto drape::garment::GarmentType (pattern
// templates). It lives in the app layer because libgarment must not depend on libvision.
//
//   vision class       template   how the class is made with it
//   t_shirt            tshirt     as proposed (short sleeves)
//   tank_top           tshirt     sleeve length l1 = 0 (no sleeve panels, open armholes)
//   long_sleeve_top    tshirt     long sleeves: l1 up to 80 cm (the template's range)
//   dress              dress      as proposed
//   skirt              skirt      as proposed
//   pants              pants      as proposed
//   shorts             pants      a short inseam (h1 - h3 < 40 cm: the knee line falls below
//                                 the hem and w3 is unused, see pants.hpp)
//
// The variant column is a hint for whoever sizes the garment (recovery starts from it);
// the mapping itself is one template per class, so every image class can be recovered.
#pragma once

#include <drape/garment/garment_type.hpp>
#include <drape/vision/garment_type.hpp>

namespace drape::app {

/// The template that makes garments of image class `c` (table above).
inline garment::GarmentType template_of(vision::GarmentType c) {
    switch (c) {
        case vision::GarmentType::t_shirt:
        case vision::GarmentType::tank_top:
        case vision::GarmentType::long_sleeve_top: return garment::GarmentType::tshirt;
        case vision::GarmentType::dress: return garment::GarmentType::dress;
        case vision::GarmentType::skirt: return garment::GarmentType::skirt;
        case vision::GarmentType::pants:
        case vision::GarmentType::shorts: return garment::GarmentType::pants;
    }
    return garment::GarmentType::tshirt;
}

}  // namespace drape::app
