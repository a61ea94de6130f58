// Private to librecover: drapes candidate sizings and materials of one garment of an outfit
// on the fitted body, for the searches; and the outfit's first and final drapes.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/recover/recover.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::recover {

/// A candidate drape of garment `index`, with the other garments as they lie around it.
struct DrapedCandidate {
    garment::GarmentMesh mesh;
    Eigen::MatrixX3d positions;                      ///< #V x 3, world metres
    std::vector<garment::GarmentMesh> other_meshes;  ///< the other garments (occluders)
    std::vector<Eigen::MatrixX3d> other_positions;
    std::vector<int> other_index;                    ///< their indices in the outfit
};

class CandidateDraper {
  public:
    CandidateDraper(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                    const RecoverOptions& options);

    /// The first drape of the outfit at the search resolution (the initial registration).
    garment::DressOutfitSummary dress(const std::vector<garment::GarmentRequest>& requests);
    const garment::DressedOutfit& outfit() const { return outfit_; }

    /// Garment `index` made with `sizing` and `material`, the others as they are. Called
    /// concurrently with distinct `worker`s (0 .. options.threads - 1).
    /// \throw drape::InvalidInput if the template refuses the sizing.
    DrapedCandidate drape(int index, const garment::GarmentSizing& sizing, const cloth::Material& material,
                          int worker) const;

    /// Keeps a garment's new sizing / material for the following candidates.
    void set_sizing(int index, const garment::GarmentSizing& sizing);
    void set_material(int index, const cloth::Material& material);

    /// The output drape: the outfit at the output resolution, arms cleared if needed.
    garment::DressOutfitSummary final_drape(const std::vector<garment::GarmentRequest>& requests,
                                            garment::DressedOutfit& out) const;

  private:
    garment::DressOutfitOptions options_at(double edge_cm, bool clear_arms) const;

    const body::BodyModel& model_;
    const body::ShapedBody& shaped_;
    body::Pose pose_;
    RecoverOptions options_;
    std::vector<garment::GarmentRequest> requests_;
    garment::DressedOutfit outfit_;
};

}  // namespace drape::recover
