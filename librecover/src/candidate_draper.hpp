// Private to librecover: drapes candidate sizings and materials of one garment of an outfit
// on the fitted body, for the searches; and the outfit's first and final drapes.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/sizing_drape.hpp>
#include <drape/recover/recover.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::recover {

/// A candidate drape of garment `index`, with the other garments as they lie around it.
struct DrapedCandidate {
    int index = -1;                                  ///< the garment's index in the outfit (inner first)
    garment::GarmentMesh mesh;
    Eigen::MatrixX3d positions;                      ///< #V x 3, world metres
    std::vector<garment::GarmentMesh> other_meshes;  ///< the other garments (occluders)
    std::vector<Eigen::MatrixX3d> other_positions;
    std::vector<int> other_index;                    ///< their indices in the outfit
    bool usable = false;                             ///< the re-drape settled cleanly
    bool converged = false;                          ///< it settled within its steps
    double penetration_max_m = 0, seam_gap_max_m = 0;
    int self_intersections = 0;
};

class CandidateDraper {
  public:
    CandidateDraper(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                    const RecoverOptions& options);
    ~CandidateDraper();

    /// The first drape of the outfit at the search resolution (the initial registration).
    garment::DressOutfitSummary dress(const std::vector<garment::GarmentRequest>& requests);
    /// The first drape, in the photo's frame (the fitted root translation applied).
    const garment::DressedOutfit& outfit() const { return shifted_; }

    /// Garment `index` made with `sizing` and `material`: its fast re-drape
    /// (garment::SizingDrape: the search mesh morphed to the sizing, warm-started from the
    /// first drape, settled); the other garments as first draped. Called concurrently with
    /// distinct `worker`s (0 .. options.threads - 1), each with its own simulators.
    /// \throw drape::InvalidInput if the template refuses the sizing or the morph inverts a
    ///        triangle (the candidate is too far from the first drape's sizing).
    /// `body` (if given: #B x 3, the body at the origin as simulated, same faces) replaces the
    /// body for this candidate (SizingDrape::set_body: moved there from the first drape's
    /// body before settling); else the body of set_pose.
    DrapedCandidate drape(int index, const garment::GarmentSizing& sizing, const cloth::Material& material,
                          int worker, const Eigen::MatrixX3d* body = nullptr) const;

    /// The draping pose (arms cleared), at the origin (no root translation).
    const body::Pose& pose() const { return pose_; }
    /// The body posed in `pose` at the origin (#B x 3), as `drape` takes it.
    Eigen::MatrixX3d posed_body(const body::Pose& pose) const;
    /// A new draping pose (at the origin) for the following candidates and the final drape,
    /// e.g. refined by the joint material-pose search.
    void set_pose(const body::Pose& pose);

    /// Keeps a garment's new sizing / material for the following candidates. A new sizing
    /// is also re-draped once (fast re-drape, its current material), so that the candidates
    /// of the other garments see it as it now lies (a top's hem over the pants' waist).
    void set_sizing(int index, const garment::GarmentSizing& sizing);
    void set_material(int index, const cloth::Material& material);

    /// The draping pose and the body posed in it, in the photo's frame (the root translation
    /// added): where the candidates lie.
    body::Pose photo_pose() const;
    Eigen::MatrixX3d photo_body() const;

    /// The output drape: the outfit at the output resolution, arms cleared if needed.
    garment::DressOutfitSummary final_drape(const std::vector<garment::GarmentRequest>& requests,
                                            garment::DressedOutfit& out) const;

  private:
    garment::DressOutfitOptions options_at(double edge_cm, bool clear_arms) const;
    void shift(garment::DressedOutfit& outfit) const;  ///< adds offset_ to positions, body and pose

    const body::BodyModel& model_;
    const body::ShapedBody& shaped_;
    body::Pose pose_;
    RecoverOptions options_;
    std::vector<garment::GarmentRequest> requests_;
    garment::DressedOutfit outfit_;   ///< the first drape, at the origin (as simulated)
    garment::DressedOutfit shifted_;  ///< the same, in the photo's frame
    /// Each garment as it now lies (photo frame): the first drape, then the re-drape of its
    /// latest sizing; what the other garments' candidates see.
    std::vector<garment::GarmentMesh> current_meshes_;
    std::vector<Eigen::MatrixX3d> current_positions_;
    Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();  ///< the fitted root translation
    /// [worker][garment]: each worker's own re-drapes (SizingDrape copies).
    mutable std::vector<std::vector<garment::SizingDrape>> drapers_;
    Eigen::MatrixX3d body_;  ///< the body of set_pose (empty: the first drape's)
};

}  // namespace drape::recover
