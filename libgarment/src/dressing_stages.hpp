// The stages of dress_garment (not installed): dressing.cpp runs them in order
// (dress_with_passes), dressing_push_out.cpp holds the push-out out of the body.
#pragma once

#include "dressing_internal.hpp"

#include <drape/body/body_model.hpp>
#include <drape/body/skeleton.hpp>
#include <drape/core/point_in_mesh.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::garment::detail {

/// Nearest row of V (#B x 3) to p (brute force, exact).
int nearest_vertex(const Eigen::MatrixXd& V, const Eigen::Vector3d& p);

/// Whether joint j is a shoulder, elbow or wrist.
bool arm_joint(int j);

/// Moves the vertices from X (#V x 3) towards `to` one at a time, keeping a move only if it
/// does not increase the number of intersecting triangle pairs at the moved vertex; see
/// dressing.cpp. Returns the number of vertices not fully moved.
int guarded_moves(const GarmentMesh& mesh, const Eigen::MatrixX3d& to, Eigen::MatrixX3d& X);

/// Throws drape::InvalidInput unless the options, pose, shaped body and mesh fit together.
void check_dressing_inputs(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                           const body::ShapedBody& shaped, const body::Pose& pose,
                           const DressingOptions& options);

/// Stage 1: the garment wrapped around the rest body.
struct WrappedGarment {
    Eigen::MatrixX3d positions;     ///< #V x 3, rest body frame (metres)
    Eigen::VectorXd pelvis_weight;  ///< #V, see wrap_panels
    double alignment_rms_m = 0;     ///< DressingSummary::alignment_rms_m
    double skirt_waist_drop_m = 0;  ///< DressingSummary::skirt_waist_drop_m
};

/// Stage 1: wraps the panels in the garment frame on ellipses matching the rest body's torso
/// sections and aligns the garment skeleton rigidly with the body's rest joints.
/// \param dominant per body vertex, the joint of its largest skin weight.
WrappedGarment wrap_on_rest_body(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                                 const body::ShapedBody& shaped, const std::vector<int>& dominant);

/// Stage 2: linear blend skinning of X (#V x 3, rest frame) into the pose of `skel`, each
/// panel with the weights of its nearest rest body vertex among its own joints.
void skin_to_pose(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                  const body::ShapedBody& shaped, const body::PosedSkeleton& skel,
                  const std::vector<int>& dominant, const Eigen::VectorXd& pelvis_weight, Eigen::MatrixX3d& X);

/// Stage 3: radial placement outside the posed body (body_v, #B x 3), then the sleeves on
/// the posed arms around the placed torso; `placement_passes` guarded passes. Returns
/// DressingSummary::sleeve_cap_offset_m.
double place_on_posed_body(const Pattern& pattern, const GarmentMesh& mesh, const body::PosedSkeleton& skel,
                         const Eigen::MatrixXd& body_v, const std::vector<int>& dominant,
                         const Eigen::VectorXd& pelvis_weight, double clearance_m, int placement_passes,
                         Eigen::MatrixX3d& X);

/// The garment vertices inside the posed body or closer to it than half the clearance,
/// each with its target outside (stages 4 and 5).
class BodyOffenders {
public:
    BodyOffenders(const Pattern& pattern, const GarmentMesh& mesh, const Eigen::MatrixXd& body_v,
                  const Eigen::MatrixXi& body_faces, const std::vector<int>& dominant, double clearance_m);
    /// Per row of `P` (#P x 3): inside the posed body.
    std::vector<bool> inside_rows(const Eigen::MatrixX3d& P) const;
    /// The offending vertices of X (#V x 3) and their targets (#ids x 3); records for each
    /// whether its target may march further out (march()).
    void find(const Eigen::MatrixX3d& X, std::vector<int>* ids, Eigen::MatrixX3d* targets);
    /// Per garment vertex: whether the last find() gave it a target that may march along
    /// the normal (false: a fold of the body, the target is on the nearest surface).
    const std::vector<bool>& march() const { return march_; }
    const core::ClosedMeshInside& inside_test() const { return inside_test_; }

private:
    const Pattern& pattern_;
    const GarmentMesh& mesh_;
    const Eigen::MatrixXd& body_v_;
    Eigen::MatrixXd body_n_;
    const std::vector<int>& dominant_;
    double clearance_m_;
    core::ClosedMeshInside inside_test_;
    std::vector<bool> march_;
};

/// Stage 4 result.
struct PushOutResult {
    int iterations = 0;             ///< DressingSummary::iterations
    int vertices_pushed = 0;        ///< DressingSummary::vertices_pushed
    double wrapped_seam_gap_m = 0;  ///< DressingSummary::wrapped_seam_gap_m
};

/// Stage 4: interpenetration removal. Offending vertices are pushed out along the body
/// normal and an as-rigid-as-possible deformation carries their neighbours; what is still
/// inside is then projected onto its target.
PushOutResult push_out_of_body(const Pattern& pattern, const GarmentMesh& mesh, const DressingOptions& options,
                               BodyOffenders& offenders, Eigen::MatrixX3d& X);

/// Stage 5: separates the crossings left, pushes out what they held inside the body and
/// untangles once more if it had to. Returns the summary of the untangling.
UntangleSummary untangle_and_push_out(const GarmentMesh& mesh, const Eigen::MatrixXd& body_v,
                                      const Eigen::MatrixXi& body_faces, const DressingOptions& options,
                                      BodyOffenders& offenders, Eigen::MatrixX3d& X);

/// The measurements of the dressed state X (#V x 3) into `summary` (inside count, seam
/// gap, crossings, penetration, layer distance, termination).
void measure_dressed(const GarmentMesh& mesh, const Eigen::MatrixX3d& X, const Eigen::MatrixXd& body_v,
                     const Eigen::MatrixXi& body_faces, const BodyOffenders& offenders, DressingSummary& summary);

}  // namespace drape::garment::detail
