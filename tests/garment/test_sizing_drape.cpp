// SizingDrape: the fast re-drape of one garment for new sizings and materials on a fixed
// posed body (garment recovery's inner loop), against the drape it was built from.
#include <drape/body/pose.hpp>
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/local_curvature.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/sizing_drape.hpp>

#include <catch2/catch.hpp>

#include "mean_female.hpp"

#include <thread>

using namespace drape::garment;
namespace body = drape::body;
namespace cloth = drape::cloth;

namespace {

struct SkirtDrape {
    drape::test::MeanFemale b;
    DressedOutfit outfit;
    cloth::Material fabric = cloth::builtin_material("gray-interlock");
    SkirtDrape() {
        DressOutfitOptions o;
        o.mesh.target_edge_cm = 6.0;
        GarmentRequest r;
        r.type = GarmentType::skirt;
        r.material = fabric;
        const DressOutfitSummary s =
            dress_outfit(b.model, b.shaped, body::named_pose(body::NamedPose::a_pose), {r}, o, outfit);
        INFO(s.brief_report());
        REQUIRE(s.usable());
    }
};

const SkirtDrape& skirt_drape() {
    static const SkirtDrape d;
    return d;
}

double hem_min_y(const Eigen::MatrixX3d& x) { return x.col(1).minCoeff(); }

double mean_curvature(const cloth::ClothMesh& mesh, const Eigen::MatrixX3d& x) {
    cloth::ClothMesh m = mesh;
    m.positions = x;
    return cloth::vertex_local_curvature(m, cloth::build_hinges(m), x).mean();
}

}  // namespace

// One test case, one base drape (a dress_outfit of a few seconds), shared by the sections
// (ctest runs each test case in its own process).
TEST_CASE("sizing drape: re-drapes of a skirt for new sizings and materials", "[garment][drape][sizing_drape]") {
    SECTION("the drape's own sizing gives the drape back") {
        const SkirtDrape& d = skirt_drape();
        SizingDrape fast(d.outfit, 0, d.b.model.faces, d.fabric);
        const SizingDrapeResult r = fast.evaluate(d.outfit.sizings[0]);
        INFO(r.message << "; " << r.steps << " steps, " << r.newton_iterations << " Newton iterations, " << r.seconds
                       << " s");
        CHECK(r.converged);
        CHECK(r.usable(fast.options().drape));
        CHECK(r.seam_gap_max_m == 0);  // welded
        const double max_mm = 1e3 * (r.positions - d.outfit.positions[0]).rowwise().norm().maxCoeff();
        INFO("G0: max " << max_mm << " mm, " << r.steps << " steps, " << r.newton_iterations << " its, " << r.seconds << " s");
        CHECK(max_mm < 2.0);
    }
    SECTION("a skirt 5 cm longer hangs 4-6 cm lower") {
        const SkirtDrape& d = skirt_drape();
        SizingDrape fast(d.outfit, 0, d.b.model.faces, d.fabric);
        GarmentSizing longer = d.outfit.sizings[0];
        longer.skirt.r2 += 5;  // the side-seam length = the skirt's length
        const SizingDrapeResult r = fast.evaluate(longer);
        INFO(r.message);
        CHECK(r.converged);
        CHECK(r.usable(fast.options().drape));
        const double drop_cm = 100 * (hem_min_y(d.outfit.positions[0]) - hem_min_y(r.positions));
        INFO("longer: hem drop " << drop_cm << " cm, " << r.steps << " steps, " << r.newton_iterations << " its, " << r.seconds << " s");
        CHECK(drop_cm > 4.0);
        CHECK(drop_cm < 6.0);
        CHECK(fast.sizing().skirt.r2 == longer.skirt.r2);
        // Back to the base sizing: the base drape again (the longer one did not stick).
        const SizingDrapeResult back = fast.evaluate(d.outfit.sizings[0]);
        CHECK(1e3 * (back.positions - d.outfit.positions[0]).rowwise().norm().maxCoeff() < 2.0);
    }
    SECTION("a stiffer fabric folds less") {
        const SkirtDrape& d = skirt_drape();
        SizingDrapeOptions options;
        options.max_steps = 150;  // the stiff skirt unfolds from the soft one's drape
        SizingDrape fast(d.outfit, 0, d.b.model.faces, d.fabric, options);
        const GarmentMesh mesh = fast.mesh();
        const SizingDrapeResult soft = fast.evaluate();
        cloth::Material stiff = d.fabric;
        stiff.bending_scale = 100;
        fast.set_material(stiff);
        const SizingDrapeResult hard = fast.evaluate();
        INFO(soft.message << " / " << hard.message);
        CHECK(soft.converged);
        CHECK(hard.converged);
        const double k_soft = mean_curvature(mesh.cloth, soft.positions), k_hard = mean_curvature(mesh.cloth, hard.positions);
        INFO("curvature soft " << k_soft << " hard " << k_hard << " 1/m; " << hard.steps << " steps " << hard.seconds << " s");
        CHECK(k_hard < 0.9 * k_soft);
    }
    SECTION("copies evaluate on two threads as one object does") {
        const SkirtDrape& d = skirt_drape();
        const SizingDrape base(d.outfit, 0, d.b.model.faces, d.fabric);
        GarmentSizing a = d.outfit.sizings[0], b = a;
        a.skirt.r2 += 3;
        b.skirt.l1 *= 1.05;
        SizingDrape first = base, second = base;
        SizingDrapeResult ra, rb;
        std::thread t1([&] { ra = first.evaluate(a); });
        std::thread t2([&] { rb = second.evaluate(b); });
        t1.join();
        t2.join();
        // The same drapes, bit for bit, as one object evaluating them in turn. (Until
        // 2026-11-27 they were not: CHOLMOD's unserialised calls into Debian's serial OpenBLAS
        // corrupted each other's factors, up to 22 mm apart; docs/cloth.md "Solver".)
        SizingDrape serial = base;
        const SizingDrapeResult sa = serial.evaluate(a), sb = serial.evaluate(b);
        const Eigen::VectorXd da = 1e3 * (sa.positions - ra.positions).rowwise().norm();
        const Eigen::VectorXd db = 1e3 * (sb.positions - rb.positions).rowwise().norm();
        INFO("threads vs serial: mean " << da.mean() << " / " << db.mean() << " mm, max " << da.maxCoeff() << " / "
                                        << db.maxCoeff() << " mm");
        CHECK(ra.converged);
        CHECK(rb.converged);
        CHECK(ra.steps == sa.steps);
        CHECK(rb.steps == sb.steps);
        CHECK(da.maxCoeff() == 0.0);
        CHECK(db.maxCoeff() == 0.0);
    }
    SECTION("a moved body carries the garment with it (the joint material-pose search)") {
        const SkirtDrape& d = skirt_drape();
        SizingDrape fast(d.outfit, 0, d.b.model.faces, d.fabric);
        const SizingDrapeResult here = fast.evaluate();
        REQUIRE(here.converged);
        // The body 2 cm forward: the skirt follows it by contact (it hangs on the hips).
        const Eigen::MatrixX3d moved = d.outfit.body_vertices.rowwise() + Eigen::RowVector3d(0, 0, 0.02);
        fast.set_body(moved);
        const SizingDrapeResult there = fast.evaluate();
        INFO(there.message);
        CHECK(there.converged);
        CHECK(there.penetration_max_m < 0.003);
        const double shift = (there.positions - here.positions).col(2).mean();
        CHECK(shift > 0.015);
        CHECK(shift < 0.025);
        // Back to the base body: the drape of before.
        fast.set_body(Eigen::MatrixX3d());
        const SizingDrapeResult back = fast.evaluate();
        CHECK(std::abs((back.positions - here.positions).col(2).mean()) < 0.002);
        // A body of another shape is refused.
        CHECK_THROWS_AS(fast.set_body(Eigen::MatrixX3d::Zero(5, 3)), drape::InvalidInput);
    }
    SECTION("bad sizings and materials are refused and leave it unchanged") {
        const SkirtDrape& d = skirt_drape();
        SizingDrape fast(d.outfit, 0, d.b.model.faces, d.fabric);
        GarmentSizing pants;
        pants.type = GarmentType::pants;
        using Catch::Matchers::Contains;
        CHECK_THROWS_WITH(fast.evaluate(pants), Contains("pants") && Contains("skirt"));
        GarmentSizing bad = d.outfit.sizings[0];
        bad.skirt.r2 = -3;
        CHECK_THROWS_WITH(fast.evaluate(bad), Contains("r2"));
        cloth::Material m = d.fabric;
        m.density_kg_per_m2 = 0;
        CHECK_THROWS_AS(fast.set_material(m), drape::InvalidInput);
        CHECK(fast.sizing().skirt.r2 == d.outfit.sizings[0].skirt.r2);
        CHECK_THROWS_WITH(SizingDrape(d.outfit, 3, d.b.model.faces, d.fabric), Contains("garment 3"));
    }
}
