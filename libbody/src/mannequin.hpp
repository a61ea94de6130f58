// The procedural default body ("mannequin"): a smooth implicit human body, polygonised
// and remeshed into a closed genus-0 triangle surface, with joints, a joint regressor,
// skinning weights and tailor landmarks. Private to libbody (namespace detail); the
// public entry point is BodyModel::default_model(). See docs/body-model.md.
//
// Frame: world, metres, +Y up, the body faces +Z, the person's left is +X, feet on Y = 0,
// rest A-pose (arms 45 degrees below horizontal, legs 7.5 degrees apart).
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/skeleton.hpp>
#include <drape/core/parallel_for.hpp>
#include <drape/core/vertex_normals.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <array>
#include <string>
#include <vector>

namespace drape::body::detail {

using JointMatrix = Eigen::Matrix<double, kJointCount, 3>;

/// Knobs of the implicit body; all dimensionless. Stature is the same for every design
/// (1.70 m) so that the designs differ in shape only.
struct MannequinDesign {
    double femininity = 0.5;  ///< 0 = male build, 1 = female build (bust, shoulders, hips, waist)
    double fat = 0.0;         ///< -1..1: belly, softness, fuller thighs/arms/neck
    double muscle = 0.0;      ///< -1..1: deltoids, pectorals, biceps, calves, trapezius

    /// femininity in [0, 1], fat and muscle in [-1, 1], all finite.
    bool is_valid(std::string* why = nullptr) const;
};

/// The generated mesh and its rig.
struct MannequinMesh {
    Eigen::MatrixXd V;  ///< #V x 3, metres, rest A-pose
    Eigen::MatrixXi F;  ///< #F x 3, counter-clockwise seen from outside
    JointMatrix joints = JointMatrix::Zero();    ///< rest joint positions (skeleton.hpp order)
    Eigen::SparseMatrix<double> joint_regressor;  ///< kJointCount x #V, rows sum to 1, >= 0
    Eigen::SparseMatrix<double> skin_weights;     ///< #V x kJointCount, rows sum to 1, >= 0
    Landmarks landmarks;                          ///< all filled
    MannequinDesign design;                       ///< the design V lies on
};

/// Generates the mannequin of `design` (deterministic, independent of the thread count;
/// about 11.5k vertices, 0.6-0.8 s on two cores).
/// \throw drape::InvalidInput if `design` is not valid (or, never seen in the valid range,
/// if its surface does not polygonise to a sphere).
MannequinMesh generate_mannequin(const MannequinDesign& design = {});

/// Same topology as `base`, each vertex moved along its base vertex normal onto the
/// zero level set of `design`'s implicit body. Smooth in the design parameters, so
/// differences of two results are usable as shape-basis directions.
/// \return #V x 3 vertex positions.
/// \throw drape::InvalidInput if `design` is not valid or `base` is empty.
Eigen::MatrixXd conform_mannequin(const MannequinMesh& base, const MannequinDesign& design);

// ---- internals shared by the mannequin_*.cpp files and the tests ----------------------

/// One primitive of the implicit body: a loft (elliptic or superelliptic cross-sections
/// varying along a straight axis, ellipsoidal end caps) or an ellipsoid with a different
/// radius on each side of each axis. value() approximates the signed distance (metres,
/// negative inside) near the surface.
struct ImplicitPart {
    enum class Shape { loft, ellipsoid };
    /// Cross-section of a loft at parameter t in [0, 1] along the axis: half-axis r1 along
    /// e1, half-axes r2_pos / r2_neg along +e2 / -e2, centre offset (c1, c2).
    struct Section {
        double t = 0, r1 = 0, r2_pos = 0, r2_neg = 0, c1 = 0, c2 = 0;
    };
    Shape shape = Shape::ellipsoid;
    int bone = -1;         ///< joint that moves this part (skinning); -1: torso, by height
    double blend = 0.0;    ///< smooth-union radius with the parts before it, metres
    bool carve = false;    ///< subtracted (smooth difference) instead of added
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< loft start / ellipsoid centre
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  ///< rows: local axes (loft: axis, e1, e2)
    double length = 0.0;   ///< loft axis length
    double cap0 = 0.01, cap1 = 0.01;  ///< loft end-cap lengths
    double exponent = 2.0; ///< loft cross-section superellipse exponent
    std::vector<Section> sections;  ///< loft keyframes, increasing t, first 0, last 1
    std::vector<Section> slopes;    ///< d(section)/dt at each keyframe (Catmull-Rom)
    std::array<double, 6> radii{};  ///< ellipsoid: +x, -x, +y, -y, +z, -z local half-axes
    Eigen::AlignedBox3d bounds;     ///< box holding the part's surface

    double value(const Eigen::Vector3d& p) const;
    Section section_at(double t) const;
    void finish();  ///< computes slopes and bounds after the fields above are set
};

/// Anatomical reference values of a design, used to place landmarks.
struct MannequinAnatomy {
    double navel_y = 0, bust_y = 0, furrow_y = 0, calf_y = 0, buttock_y = 0;
    Eigen::Vector3d hand_tip[2];  ///< [0] right, [1] left fingertip points
    Eigen::Vector3d head_centre = Eigen::Vector3d::Zero();
};

/// The implicit body of one design: smooth union of ImplicitParts, clipped flat at y = 0.
class MannequinImplicit {
public:
    explicit MannequinImplicit(const MannequinDesign& design);

    /// Approximate signed distance (metres), negative inside. Far from the body it returns
    /// a positive constant (kFarValue).
    double value(const Eigen::Vector3d& p) const;
    /// Central-difference gradient of value().
    Eigen::Vector3d gradient(const Eigen::Vector3d& p) const;
    /// Joint (skeleton.hpp index) that drives the part nearest to p.
    int bone_at(const Eigen::Vector3d& p) const;
    /// Relative target edge length at p (1 on the trunk, smaller on face, hands, feet).
    double relative_edge_length(const Eigen::Vector3d& p) const;

    const JointMatrix& joints() const { return joints_; }
    const Eigen::AlignedBox3d& bounds() const { return bounds_; }
    const MannequinAnatomy& anatomy() const { return anatomy_; }
    const MannequinDesign& design() const { return design_; }
    const std::vector<ImplicitPart>& parts() const { return parts_; }

    static constexpr double kFarValue = 0.07;  ///< value() outside every part's margin

private:
    int torso_bone(const Eigen::Vector3d& p) const;

    MannequinDesign design_;
    std::vector<ImplicitPart> parts_;
    JointMatrix joints_ = JointMatrix::Zero();
    MannequinAnatomy anatomy_;
    Eigen::AlignedBox3d bounds_;
};

/// Indexed triangle surface used while meshing.
struct SurfaceMesh {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::array<int, 3>> faces;
};

/// Marching tetrahedra (Freudenthal split of a cubic grid, narrow band) of value() < 0;
/// welded, consistently outward oriented, largest component only.
SurfaceMesh polygonize_implicit(const MannequinImplicit& body, double cell_size);

/// Isotropic remeshing onto the implicit surface (split / collapse / flip / tangential
/// relaxation / projection) to about `target_vertices` vertices.
void remesh_on_implicit(const MannequinImplicit& body, int target_vertices, int iterations,
                        SurfaceMesh& mesh);

/// Newton projection of p onto value() = 0 along the gradient.
Eigen::Vector3d project_onto_implicit(const MannequinImplicit& body, Eigen::Vector3d p,
                                      int max_iterations = 20, double tolerance = 1e-10);

/// Joint regressor: for each joint a ring of vertices around it, non-negative weights
/// summing to 1 that reproduce `joints` exactly (head_top: its vertex).
Eigen::SparseMatrix<double> mannequin_joint_regressor(const MannequinImplicit& body,
                                                      const Eigen::MatrixXd& V,
                                                      const Eigen::MatrixXi& F,
                                                      const JointMatrix& joints,
                                                      int head_top_vertex);

/// Skinning weights: part labels diffused over the mesh, at most 4 per vertex.
Eigen::SparseMatrix<double> mannequin_skin_weights(const MannequinImplicit& body,
                                                   const Eigen::MatrixXd& V,
                                                   const Eigen::MatrixXi& F);

/// Tailor landmarks picked as extreme vertices of anatomical regions.
Landmarks mannequin_landmarks(const MannequinImplicit& body, const Eigen::MatrixXd& V);

/// Area-weighted vertex normals (#V x 3, unit; zero rows for isolated vertices).
inline Eigen::MatrixXd mannequin_vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    return core::vertex_normals(V, F);
}

/// Parallel loops come from the geometry layer (deterministic when f(i) only writes slot i).
using core::parallel_for;

}  // namespace drape::body::detail
