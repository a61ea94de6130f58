#include "outfit_fixture.hpp"

namespace drape::test {

recover::OutfitGarment rectangle(double x0, double x1, double y0, double y1, double z, int class_id) {
    recover::OutfitGarment g;
    g.V.resize(4, 3);
    g.V << x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z;
    g.F.resize(2, 3);
    g.F << 0, 1, 2, 0, 2, 3;
    g.UV = g.V.leftCols(2);
    g.class_id = class_id;
    return g;
}

body::Camera rectangle_camera() {
    body::Camera c;
    c.model = body::CameraModel::weak_perspective;
    c.scale_px_per_m = 100.0;
    c.offset_px = {150.0, 150.0};
    return c;
}

recover::OutfitMeshes rectangle_outfit() {
    recover::OutfitMeshes o;
    const recover::OutfitGarment body = rectangle(-1, 1, -1, 1, 0.0, recover::kSkinClassId);
    o.body_V = body.V;
    o.body_F = body.F;
    o.garments.push_back(rectangle(-0.5, 0.5, -1.2, 0.0, 0.1, 42));
    o.garments.back().name = "skirt";
    o.garments.push_back(rectangle(-0.8, 0.8, 0.2, 0.9, -0.1, 51));
    o.garments.back().name = "tshirt";
    return o;
}

}  // namespace drape::test
