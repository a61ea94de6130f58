#include <drape/garment/dress_outfit.hpp>

#include <drape/body/measurements.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <chrono>
#include <sstream>

namespace drape::garment {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* termination_name(DressOutfitTermination t) {
    switch (t) {
        case DressOutfitTermination::draped: return "draped";
        case DressOutfitTermination::meshing_failed: return "meshing failed";
        case DressOutfitTermination::cancelled: return "cancelled";
    }
    return "?";
}

}  // namespace

bool DressOutfitOptions::is_valid(std::string* why) const {
    std::string reason;
    const auto fail = [&](const std::string& what) {
        if (why) *why = what;
        return false;
    };
    if (!mesh.is_valid(&reason)) return fail("mesh: " + reason);
    if (!dressing.is_valid(&reason)) return fail("dressing: " + reason);
    if (!drape.is_valid(&reason)) return fail("drape: " + reason);
    if (clear_arms && !arm_clearance.is_valid(&reason)) return fail("arm clearance: " + reason);
    return true;
}

bool DressOutfitSummary::checks_pass(const DressedOutfit& outfit) const {
    if (termination != DressOutfitTermination::draped || outfit.checks.size() != size_t(garments)) return false;
    for (const GarmentStateCheck& c : outfit.checks)
        if (c.max_penetration_m > drape.penetration_tolerance_m || c.self_intersections != 0 ||
            !(c.max_seam_gap_m < drape.seam_gap_tolerance_m))
            return false;
    return true;
}

std::string DressOutfitSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "outfit draped" : "outfit NOT usable") << " (" << termination_name(termination) << "): "
       << garments << " garment" << (garments == 1 ? "" : "s") << ", " << vertices << " vertices, " << faces
       << " faces; meshing " << seconds_mesh << " s, dressing " << seconds_dress << " s, draping " << seconds_drape
       << " s, total " << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

DressOutfitSummary dress_outfit(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                const std::vector<GarmentRequest>& garments, const DressOutfitOptions& options,
                                DressedOutfit& out) {
    const auto start = std::chrono::steady_clock::now();
    std::string why;
    require(!garments.empty(), "dress_outfit: no garments");
    require(options.is_valid(&why), "dress_outfit: ", why);
    require(pose.is_valid(&why), "dress_outfit: pose: ", why);
    for (size_t g = 0; g < garments.size(); ++g) {
        const GarmentRequest& r = garments[g];
        require(!r.sizing || r.sizing->type == r.type, "dress_outfit: garment ", g, " (", garment_type_name(r.type),
                "): its sizing is of a ", r.sizing ? garment_type_name(r.sizing->type) : "", "");
        require(r.material.is_valid(&why), "dress_outfit: material of garment ", g, " (", garment_type_name(r.type),
                "): ", why);
    }
    out = DressedOutfit{};
    DressOutfitSummary summary;
    summary.garments = int(garments.size());

    // Sizing and patterns; the body is measured only if a sizing is to be proposed.
    std::optional<body::BodyMeasurements> measured;
    for (const GarmentRequest& r : garments) {
        if (!r.sizing && !measured) measured = body::measure_body(model, shaped.vertices);
        out.sizings.push_back(r.sizing ? *r.sizing : proposed_sizing(r.type, model, shaped, *measured));
        out.patterns.push_back(make_pattern(out.sizings.back()));
    }
    if (options.clear_arms)
        out.pose = clear_arms_from_trunk(model, shaped, pose, options.arm_clearance, &out.arms);
    else
        out.pose = pose;
    out.body_vertices = body::pose_body(model, shaped, out.pose).vertices;

    const auto t_mesh = std::chrono::steady_clock::now();
    out.meshes.resize(garments.size());
    for (size_t g = 0; g < garments.size(); ++g) {
        out.meshing.push_back(mesh_pattern(out.patterns[g], options.mesh, out.meshes[g]));
        summary.vertices += out.meshes[g].cloth.vertex_count();
        summary.faces += out.meshes[g].cloth.face_count();
        if (!out.meshing[g].usable()) {
            summary.termination = DressOutfitTermination::meshing_failed;
            summary.message = "meshing " + garment_type_name(garments[g].type) + " failed: " +
                              out.meshing[g].brief_report();
            summary.seconds_mesh = seconds_since(t_mesh);
            summary.seconds = seconds_since(start);
            return summary;
        }
    }
    summary.seconds_mesh = seconds_since(t_mesh);

    // Dressed in the rest A-pose, sewn, then moved to the pose.
    if (garments.size() == 1) {
        out.positions.resize(1);
        out.dressing.resize(1);
        summary.drape = dress_and_drape(out.patterns[0], out.meshes[0], model, shaped, out.pose, garments[0].material,
                                        options.dressing, options.drape, out.positions[0], &out.dressing[0]);
    } else {
        std::vector<cloth::Material> materials;
        for (const GarmentRequest& r : garments) materials.push_back(r.material);
        summary.drape = dress_and_drape_outfit(out.patterns, out.meshes, model, shaped, out.pose, materials,
                                               options.dressing, options.drape, out.positions, &out.dressing);
    }
    for (const DressingSummary& d : out.dressing) summary.seconds_dress += d.seconds;
    summary.seconds_drape = summary.drape.seconds;
    if (summary.drape.termination == DrapeTermination::cancelled) {
        summary.termination = DressOutfitTermination::cancelled;
        summary.message = "cancelled while draping";
        summary.seconds = seconds_since(start);
        return summary;
    }
    // Independent of the simulator's own report: the checks of the draped state.
    for (size_t g = 0; g < garments.size(); ++g)
        out.checks.push_back(check_garment_state(out.meshes[g], out.positions[g], out.body_vertices, model.faces));
    summary.termination = DressOutfitTermination::draped;
    summary.message = summary.drape.usable() ? "" : "the drape is not usable: see drape";
    summary.seconds = seconds_since(start);
    return summary;
}

}  // namespace drape::garment
