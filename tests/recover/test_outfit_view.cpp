// A candidate's view: the other garments keep their image but are layered in depth as worn
// (docs/recovery.md, "Layers in the candidate's view").
#include "../../librecover/src/outfit_view.hpp"

#include "outfit_fixture.hpp"

#include <catch2/catch.hpp>

using namespace drape;

namespace {

long long count_on(const garment::BinaryImage& b) {
    long long n = 0;
    for (const std::uint8_t p : b.pixels) n += p != 0;
    return n;
}

garment::GarmentMesh mesh_of(const recover::OutfitGarment& g) {
    garment::GarmentMesh m;
    m.cloth.positions = g.V;
    m.cloth.faces = g.F;
    return m;
}

// Body [-1, 1]^2 at z = 0; the candidate [-0.5, 0.5] x [-0.6, 0.4] at z = 0.02, re-draped on
// the body alone; the other garment [-0.7, 0.7] x [-0.9, -0.1] at z = 0.04, as first draped:
// in front of the candidate by 2 cm where they overlap (x 100..199, y 160..209: 5 000 px).
recover::DrapedCandidate candidate(int index, int other_index) {
    const recover::OutfitGarment c = test::rectangle(-0.5, 0.5, -0.6, 0.4, 0.02, 51);
    const recover::OutfitGarment o = test::rectangle(-0.7, 0.7, -0.9, -0.1, 0.04, 31);
    recover::DrapedCandidate d;
    d.index = index;
    d.mesh = mesh_of(c);
    d.positions = c.V;
    d.other_meshes = {mesh_of(o)};
    d.other_positions = {o.V};
    d.other_index = {other_index};
    return d;
}

void check_layers(const body::Camera& camera, long long candidate_pixels, long long overlap_pixels) {
    body::BodyModel model;
    const recover::OutfitMeshes plain = test::rectangle_outfit();
    model.faces = plain.body_F;
    const recover::OutfitView view(model, plain.body_V, camera, 300, 300);

    // Worn over the other garment (a top over pants): nothing of it is hidden.
    const garment::CandidateSilhouette over = view.candidate(candidate(1, 0));
    CHECK(count_on(over.visible) == candidate_pixels);
    CHECK(count_on(over.occluded) == 0);
    // Worn under it (pants under a top): the overlap is hidden, as the top hides it.
    const garment::CandidateSilhouette under = view.candidate(candidate(0, 1));
    CHECK(count_on(under.visible) == candidate_pixels - overlap_pixels);
    CHECK(count_on(under.occluded) == overlap_pixels);
    // The other garment's image is unchanged by its move in depth.
    const recover::OutfitMeshes scene = view.candidate_scene(candidate(1, 0));
    REQUIRE(scene.garments.size() == 2);
    for (Eigen::Index i = 0; i < scene.garments[0].V.rows(); ++i) {
        const Eigen::Vector2d a = camera.project(scene.garments[0].V.row(i).transpose());
        const Eigen::Vector2d b = camera.project(candidate(1, 0).other_positions[0].row(i).transpose());
        CHECK((a - b).norm() < 1e-9);
    }
    CHECK(scene.garments[0].V(0, 2) < 0.04 - 0.5 * recover::kLayerDepthM);
}

}  // namespace

TEST_CASE("candidate view: the other garments are layered as worn, their image kept", "[recover][mask]") {
    SECTION("weak perspective") { check_layers(test::rectangle_camera(), 100 * 100, 100 * 50); }
    SECTION("pinhole") {
        // Focal 500 px at 5 m: 100 px per metre at z = 0, slightly more nearer the camera.
        body::Camera c;
        c.model = body::CameraModel::pinhole;
        c.focal_px = 500;
        c.distance_m = 5;
        c.offset_px = {150, 150};
        // The candidate at z = 0.02 spans 100.4 px per metre: x 99.8..200.2 -> pixel
        // centres 100..199 (100), y 109.8..210.2 -> 110..209 (100); the overlap, from the
        // other garment's image (y from 159.9: 160..209), 100 x 50.
        check_layers(c, 100 * 100, 100 * 50);
    }
}
