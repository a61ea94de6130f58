#include "candidate_draper.hpp"

#include <drape/core/errors.hpp>

namespace drape::recover {

CandidateDraper::CandidateDraper(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                 const RecoverOptions& options)
    : model_(model), shaped_(shaped), pose_(pose), options_(options) {}

garment::DressOutfitOptions CandidateDraper::options_at(double edge_cm, bool clear_arms) const {
    garment::DressOutfitOptions o;
    o.mesh.target_edge_cm = edge_cm;
    o.drape.max_steps = options_.max_drape_steps;
    o.drape.min_steps = std::min(o.drape.min_steps, o.drape.max_steps);
    o.drape.max_untangle_steps = std::min(o.drape.max_untangle_steps, options_.max_drape_steps / 3);
    o.clear_arms = clear_arms;
    return o;
}

garment::DressOutfitSummary CandidateDraper::dress(const std::vector<garment::GarmentRequest>& requests) {
    requests_ = requests;
    const auto s = garment::dress_outfit(model_, shaped_, pose_, requests_, options_at(options_.search_edge_cm, true),
                                         outfit_);
    pose_ = outfit_.pose;  // candidates are draped in the pose the arms were cleared to
    return s;
}

DrapedCandidate CandidateDraper::drape(int index, const garment::GarmentSizing& sizing,
                                       const cloth::Material& material, int /*worker*/) const {
    std::vector<garment::GarmentRequest> requests = requests_;
    requests.at(static_cast<size_t>(index)).sizing = sizing;
    requests.at(static_cast<size_t>(index)).material = material;
    garment::DressedOutfit made;
    garment::dress_outfit(model_, shaped_, pose_, requests, options_at(options_.search_edge_cm, false), made);
    DrapedCandidate c;
    for (size_t i = 0; i < made.meshes.size(); ++i) {
        if (static_cast<int>(i) == index) {
            c.mesh = made.meshes[i];
            c.positions = made.positions[i];
        } else {
            c.other_meshes.push_back(made.meshes[i]);
            c.other_positions.push_back(made.positions[i]);
            c.other_index.push_back(static_cast<int>(i));
        }
    }
    if (c.positions.rows() == 0) throw InvalidInput("the candidate could not be draped");
    return c;
}

void CandidateDraper::set_sizing(int index, const garment::GarmentSizing& sizing) {
    requests_.at(static_cast<size_t>(index)).sizing = sizing;
}

void CandidateDraper::set_material(int index, const cloth::Material& material) {
    requests_.at(static_cast<size_t>(index)).material = material;
}

garment::DressOutfitSummary CandidateDraper::final_drape(const std::vector<garment::GarmentRequest>& requests,
                                                         garment::DressedOutfit& out) const {
    garment::DressOutfitOptions o = options_at(options_.final_edge_cm, false);
    o.drape.max_steps = std::max(600, options_.max_drape_steps);
    return garment::dress_outfit(model_, shaped_, pose_, requests, o, out);
}

}  // namespace drape::recover
