#include "candidate_draper.hpp"

#include <drape/body/pose.hpp>

#include <drape/core/errors.hpp>

namespace drape::recover {

CandidateDraper::CandidateDraper(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                 const RecoverOptions& options)
    : model_(model), shaped_(shaped), pose_(pose), options_(options) {
    // The garments are draped with the body standing where the dressing puts it (no root
    // translation): a fitted root translation is a rigid offset of the whole scene, and
    // moving the body by it during the drape would leave the cloth behind. The offset is
    // added back to everything handed out.
    offset_ = pose_.translation;
    pose_.translation.setZero();
}

CandidateDraper::~CandidateDraper() = default;

garment::DressOutfitOptions CandidateDraper::options_at(double edge_cm, bool clear_arms) const {
    garment::DressOutfitOptions o;
    o.mesh.target_edge_cm = edge_cm;
    o.drape.max_steps = options_.max_drape_steps;
    o.drape.min_steps = std::min(o.drape.min_steps, o.drape.max_steps);
    o.drape.max_untangle_steps = std::min(o.drape.max_untangle_steps, options_.max_drape_steps / 3);
    o.clear_arms = clear_arms;
    // The photo's camera is on +Z: arms are cleared of the trunk by the turn that changes
    // their image least (an arm in front of the trunk moves further in front, not out).
    o.arm_clearance.view_direction = Eigen::Vector3d::UnitZ();
    return o;
}

garment::DressOutfitSummary CandidateDraper::dress(const std::vector<garment::GarmentRequest>& requests) {
    requests_ = requests;
    const garment::DressOutfitOptions o = options_at(options_.search_edge_cm, true);
    const auto s = garment::dress_outfit(model_, shaped_, pose_, requests_, o, outfit_);
    pose_ = outfit_.pose;  // candidates are draped in the pose the arms were cleared to
    shifted_ = outfit_;
    shift(shifted_);
    current_meshes_ = shifted_.meshes;
    current_positions_ = shifted_.positions;
    if (s.termination != garment::DressOutfitTermination::draped) return s;
    // One fast re-drape per garment (morphed rest shape, warm start from this drape), copied
    // once per worker: each worker owns its simulators.
    garment::SizingDrapeOptions so;
    so.drape = o.drape;
    drapers_.assign(static_cast<size_t>(options_.threads), {});
    for (size_t g = 0; g < requests_.size(); ++g)
        drapers_[0].emplace_back(outfit_, static_cast<int>(g), model_.faces, requests_[g].material, so);
    for (size_t w = 1; w < drapers_.size(); ++w) drapers_[w] = drapers_[0];
    return s;
}

DrapedCandidate CandidateDraper::drape(int index, const garment::GarmentSizing& sizing,
                                       const cloth::Material& material, int worker, const Eigen::MatrixX3d* body) const {
    if (drapers_.empty()) throw InvalidInput("recover: candidates before the outfit was dressed");
    garment::SizingDrape& d = drapers_.at(static_cast<size_t>(worker)).at(static_cast<size_t>(index));
    const cloth::Material& now = d.material();
    if (now.bending_scale != material.bending_scale || now.stretching_scale != material.stretching_scale ||
        now.bending_n_m != material.bending_n_m || now.stretching_n_per_m != material.stretching_n_per_m ||
        now.density_kg_per_m2 != material.density_kg_per_m2)
        d.set_material(material);
    d.set_body(body ? *body : body_);
    const garment::SizingDrapeResult r = d.evaluate(sizing);  // InvalidInput: the template or the morph refuses it
    DrapedCandidate c;
    c.index = index;
    c.mesh = d.mesh();
    c.positions = r.positions.rowwise() + offset_.transpose();
    c.usable = r.usable(d.options().drape);
    c.converged = r.converged;
    c.penetration_max_m = r.penetration_max_m;
    c.seam_gap_max_m = r.seam_gap_max_m;
    c.self_intersections = r.self_intersections;
    for (size_t i = 0; i < outfit_.meshes.size(); ++i) {
        if (static_cast<int>(i) == index) continue;
        c.other_meshes.push_back(current_meshes_[i]);
        c.other_positions.push_back(current_positions_[i]);
        c.other_index.push_back(static_cast<int>(i));
    }
    return c;
}

Eigen::MatrixX3d CandidateDraper::posed_body(const body::Pose& pose) const {
    return body::pose_body(model_, shaped_, pose).vertices;
}

body::Pose CandidateDraper::photo_pose() const {
    body::Pose p = pose_;
    p.translation += offset_;
    return p;
}

Eigen::MatrixX3d CandidateDraper::photo_body() const {
    const Eigen::MatrixX3d b = body_.rows() > 0 ? body_ : outfit_.body_vertices;
    return b.rowwise() + offset_.transpose();
}

void CandidateDraper::set_pose(const body::Pose& pose) {
    pose_ = pose;
    pose_.translation.setZero();
    body_ = posed_body(pose_);
}

void CandidateDraper::set_sizing(int index, const garment::GarmentSizing& sizing) {
    requests_.at(static_cast<size_t>(index)).sizing = sizing;
    if (drapers_.empty()) return;
    garment::SizingDrape& d = drapers_[0].at(static_cast<size_t>(index));
    try {
        d.set_body(body_);
        const garment::SizingDrapeResult r = d.evaluate(sizing);
        current_meshes_[static_cast<size_t>(index)] = d.mesh();
        current_positions_[static_cast<size_t>(index)] = r.positions.rowwise() + offset_.transpose();
    } catch (const InvalidInput&) {
        // A sizing the search accepted was evaluated before; keep the last drape if not.
    }
}

void CandidateDraper::set_material(int index, const cloth::Material& material) {
    requests_.at(static_cast<size_t>(index)).material = material;
}

garment::DressOutfitSummary CandidateDraper::final_drape(const std::vector<garment::GarmentRequest>& requests,
                                                         garment::DressedOutfit& out) const {
    garment::DressOutfitOptions o = options_at(options_.final_edge_cm, false);
    o.drape.max_steps = std::max(600, options_.max_drape_steps);
    const auto s = garment::dress_outfit(model_, shaped_, pose_, requests, o, out);
    shift(out);
    return s;
}

void CandidateDraper::shift(garment::DressedOutfit& outfit) const {
    for (auto& p : outfit.positions) p = p.rowwise() + offset_.transpose();
    outfit.body_vertices = outfit.body_vertices.rowwise() + offset_.transpose();
    outfit.pose.translation += offset_;
}

}  // namespace drape::recover
