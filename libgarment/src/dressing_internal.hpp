// Shared between the dressing_*.cpp files (not installed).
#pragma once

#include <drape/body/skeleton.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace drape::garment::detail {

using Joints = Eigen::Matrix<double, body::kJointCount, 3>;

/// Positions (#V x 3, metres) of the mesh wrapped around a body whose rest joints are
/// `joints`: torso panels on vertical cylinders/cones around the spine, leg panels around
/// the leg axes, sleeves around the arm chains. Panels of unknown patterns: placement hint.
/// `torso_section(y)` gives the body's torso half-width and half-depth (metres) about the
/// spine axis at height y (garment frame), so torso panels wrap on matching ellipses.
/// \param pelvis_weight if not null, receives per vertex the weight of the pelvis tube for
/// pants panels (1 above the crotch blend, 0 on the leg tubes; 1 for other panels).
/// \param base if not null, place only sleeve panels (others keep `base`'s rows): used to
/// put sleeves on the posed arms around the placed torso.
/// \param sleeve_offset_m how far down the arm, beyond where it leaves the torso panels'
/// nominal cylinder, a sleeve's cap starts (the cap seam is sewn by the simulation).
Eigen::MatrixX3d wrap_panels(const Pattern& pattern, const GarmentMesh& mesh, const Joints& joints,
                             const std::function<Eigen::Vector2d(double)>& torso_section,
                             Eigen::VectorXd* pelvis_weight = nullptr, const Eigen::MatrixX3d* base = nullptr,
                             double sleeve_offset_m = 0.04,
                             double skirt_waist_y = std::numeric_limits<double>::quiet_NaN());
// (skirt_waist_y: garment-frame height at which a circle skirt's waist is placed; NaN: the
// spine joint's.)

/// The waist of a skirt or pants panel: its open edge (in no seam) whose points lie highest
/// in the panel's pattern frame, or -1 (no open edge).
int waist_edge(const Pattern& pattern, size_t panel);

/// How a panel is wrapped and placed: its declared PanelRole without front / back (the
/// placement's body part says that; hint: PanelRole::other).
enum class Role { torso, sleeve, skirt, leg, hint };
Role role_of(const Pattern& pattern, size_t panel);

/// Whether every panel is a skirt panel (a skirt hanging from the waist; a dress's skirt
/// hangs from its bodice).
bool is_skirt(const Pattern& pattern);

/// A radial envelope around a joint chain (a polyline, extended beyond both ends): for
/// each arc length s along the axis (1 cm bins) and angle about it (5 degree bins), the
/// largest distance from the axis of the points added. Used to place cloth outside the
/// body (or outside another garment layer) by moving it radially, which keeps the angle
/// and height of every point and so cannot make two layers cross.
class AxisEnvelope {
public:
    /// \param chain axis points in order; \param extend_m length added before the first and
    /// after the last point along the end segments.
    AxisEnvelope(std::vector<Eigen::Vector3d> chain, double extend_m);
    void add(const Eigen::Vector3d& p);
    /// Grows every bin to the maximum of its neighbours (`dilate` bins each way); call once
    /// after the last add.
    void finish(int dilate = 1);
    /// Moves p radially so that it lies at least `clearance_m` outside the envelope; the
    /// distance beyond the envelope is mapped by a smooth increasing function (identity
    /// beyond clearance + `soft_m`), so points keep their radial order.
    Eigen::Vector3d push(const Eigen::Vector3d& p, double clearance_m, double soft_m) const;

private:
    struct Coords {
        int s_bin = 0, a_bin = 0;
        double r = 0;
        Eigen::Vector3d foot, radial;
    };
    Coords coords(const Eigen::Vector3d& p) const;
    std::vector<Eigen::Vector3d> chain_;
    std::vector<double> length_;  // arc length at each chain point
    int s_bins_ = 0;
    std::vector<double> r_;       // s_bins_ x kAngleBins, -1 = empty
};

/// d for d >= soft, else a smooth (C1) increasing map of d into (0, soft): a distance that
/// must stay positive keeps its order.
double soft_floor(double d, double soft);

/// Per vertex, one representative of its stitched group (vertices sewn together, transitively).
std::vector<int> sewn_representatives(int vertex_count, const std::vector<std::array<int, 2>>& stitches);

/// The mesh's faces with every vertex replaced by its stitched group's representative: the
/// sewn surface, whose crossings are counted as the simulator counts them.
Eigen::MatrixX3i sewn_faces(const GarmentMesh& mesh);

/// Whether any panel of the pattern is a sleeve.
bool has_sleeves(const Pattern& pattern);

/// A vertex and a triangle that may come into contact (see layer_pairs).
struct LayerPair {
    int vertex;
    int face;
    double distance_m;
    Eigen::Vector3d closest;  ///< closest point on the face
};

/// Vertex–triangle pairs closer than radius_m at X, except a vertex with a triangle of its
/// own or of a stitched partner, and pairs on one panel closer than rest_radius_m in pattern
/// space (the simulator's rest-neighbour filter).
std::vector<LayerPair> layer_pairs(const GarmentMesh& mesh, const Eigen::MatrixX3d& X, double radius_m,
                                   double rest_radius_m);

/// The body joints whose transforms may move a panel when it is skinned to the pose (empty:
/// any joint): trunk joints for torso panels, pelvis and spine for skirts, the pelvis and
/// the panel's leg for pants, the panel's arm for sleeves. Skin weights copied from the
/// nearest body vertex are restricted to these, so a hand next to the hip in the rest pose
/// does not carry the pants with it.
std::vector<int> skinning_joints(const Pattern& pattern, int panel);

/// Garment edges (i, j), i < j, from the faces.
std::vector<std::array<int, 2>> mesh_edges(const Eigen::MatrixX3i& faces);

}  // namespace drape::garment::detail
