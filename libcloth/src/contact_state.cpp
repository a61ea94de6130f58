// Contact and friction state of a step: closest body points and contact planes, the
// friction lagged over a step, the rest filter of self-contact and the step bounds.
#include "simulator_impl.hpp"

#include <drape/core/parallel_for.hpp>

#include <algorithm>
#include <cmath>

namespace drape::cloth {

namespace {

// A vertex's second contact plane of a step is made for a surface facing the first one:
// normals more than 90 degrees apart (a pinch), not a neighbouring patch of one surface.
constexpr double kFacingPlanesCos = 0.0;
// A vertex also gets a second plane when its first one overstates its distance to the body
// by more than this fraction of the layer: it has slid, within the step, round a sharply
// curved part of the body (the armpit's fold), where the first plane passes through the body.
constexpr double kPlaneMisfit = 0.5;
// How far a vertex that was near the obstacle at the previous contact update is searched
// for when it is no longer within the query radius (update_obstacle_contacts): deeper than
// the half-thickness of most body parts, so a vertex pushed that far in is still found.
constexpr double kLostContactRadius = 0.15;

}  // namespace

void Simulator::Impl::update_obstacle_contacts(const Eigen::MatrixX3d& p) {
    if (!obstacle) {
        contacts.clear();
        return;
    }
    const double h = options.contact_thickness_m;
    query_radius = h + std::max(2 * h, 0.01);
    // Each vertex's entry still holds its previous distance until it is overwritten.
    const bool known = contacts.size() == static_cast<std::size_t>(p.rows());
    if (!known) contacts.assign(static_cast<std::size_t>(p.rows()), VertexContact{});
    core::parallel_for(static_cast<int>(p.rows()), [&](int i) {
        VertexContact& c = contacts[static_cast<std::size_t>(i)];
        const double previous = known ? c.distance : -std::numeric_limits<double>::infinity();
        c = VertexContact{};
        c.vertex = i;
        if (pinned[static_cast<std::size_t>(i)]) return;
        ObstacleQuery q = obstacle->closest(p.row(i).transpose(), query_radius);
        if (!q.found && previous < query_radius)
            q = obstacle->closest(p.row(i).transpose(), kLostContactRadius);
        if (!q.found) return;
        c.face = q.face;
        c.weights = q.weights;
        c.point = q.point;
        c.normal = q.normal;
        c.distance = q.signed_distance_m;
        // Contact plane: through the closest point, along the direction to the vertex
        // when it is well defined (so the plane is the true distance's tangent plane).
        const Eigen::Vector3d d = p.row(i).transpose() - q.point;
        if (d.norm() > 1e-9) c.normal = (q.signed_distance_m < 0 ? -d : d).normalized();
        c.stiffness = options.contact_stiffness_n_per_m3 * area(i);
    }, 64);
    {
        plane_of_vertex.resize(static_cast<std::size_t>(p.rows()), {-1, -1});
        for (const VertexContact& c : contacts) {
            if (c.vertex < 0 || c.stiffness <= 0 || c.distance >= h) continue;
            std::array<int, 2>& own = plane_of_vertex[static_cast<std::size_t>(c.vertex)];
            bool add = own[0] < 0;
            if (!add && own[1] < 0)
                add = planes[static_cast<std::size_t>(own[0])].second.dot(c.normal) < kFacingPlanesCos ||
                      (options.strict_body_contact &&
                       plane_distance(own[0], p, c.vertex) - c.distance > kPlaneMisfit * h);
            if (!add) continue;
            own[own[0] < 0 ? 0 : 1] = static_cast<int>(planes.size());
            planes.emplace_back(c.point, c.normal);
        }
    }
}

void Simulator::Impl::lag_friction() {
    friction.clear();
    if (!friction_active() || !obstacle || options.obstacle_friction <= 0) return;
    const double h = options.contact_thickness_m;
    const Eigen::MatrixX3d& now = obstacle->positions();
    const bool moved = obstacle_start.rows() == now.rows() && step_dt > 0;
    for (const VertexContact& c : contacts) {
        if (!(c.vertex >= 0 && c.stiffness > 0 && c.distance < h)) continue;
        FrictionContact f{c.vertex, c.normal, c.stiffness * (h - std::max(c.distance, 0.0))};
        if (moved && c.face >= 0) {
            // The closest point's barycentric weights on its triangle carry the corners' motion.
            const Eigen::Vector3i t = obstacle->faces().row(c.face).transpose();
            for (int k = 0; k < 3; ++k)
                f.surface_motion += c.weights(k) * (now.row(t(k)) - obstacle_start.row(t(k))).transpose();
        }
        friction.push_back(f);
    }
}

void Simulator::Impl::drop_released_friction() {
    if (friction.empty() || contacts.empty()) return;
    const double h = options.contact_thickness_m;
    std::size_t w = 0;
    for (std::size_t k = 0; k < friction.size(); ++k) {
        const VertexContact& c = contacts[static_cast<std::size_t>(friction[k].vertex)];
        if (c.stiffness > 0 && c.distance < h) friction[w++] = friction[k];
    }
    friction.resize(w);
}

double Simulator::Impl::plane_distance(int plane, const Eigen::MatrixX3d& p, int i) const {
    const auto& [point, normal] = planes[static_cast<std::size_t>(plane)];
    return normal.dot(p.row(i).transpose() - point);
}

bool Simulator::Impl::plane_active(const Eigen::MatrixX3d& p, int i) const {
    if (static_cast<std::size_t>(i) >= plane_of_vertex.size()) return false;
    for (const int plane : plane_of_vertex[static_cast<std::size_t>(i)])
        if (plane >= 0 && plane_distance(plane, p, i) < options.contact_thickness_m) return true;
    return false;
}

double Simulator::Impl::obstacle_step_bound(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx) const {
    if (contacts.empty()) return 1.0;
    const double allowed_depth_m = options.contact_thickness_m;
    double alpha = 1.0;
    for (const VertexContact& c : contacts) {
        if (c.vertex < 0 || pinned[static_cast<std::size_t>(c.vertex)]) continue;
        const double move = dx.row(c.vertex).norm();
        if (move <= 0) continue;
        const double free_distance = std::isfinite(c.distance) ? c.distance : query_radius;
        if (free_distance <= 0) continue;
        const double depth = !options.strict_body_contact || plane_active(p, c.vertex) ? allowed_depth_m : 0.0;
        alpha = std::min(alpha, (0.9 * free_distance + depth) / move);
    }
    return alpha;
}

Eigen::MatrixX3d Simulator::Impl::start_carry(const Eigen::MatrixX3d& p) const {
    Eigen::MatrixX3d carry = Eigen::MatrixX3d::Zero(p.rows(), 3);
    for (const FrictionContact& f : friction)
        if (!pinned[static_cast<std::size_t>(f.vertex)]) carry.row(f.vertex) = f.surface_motion.transpose();
    if (carry.squaredNorm() == 0) return carry;
    // The distances of the contacts are to the body where it is now, and a vertex carried with
    // its surface keeps its distance to that surface: bounding the carry as a motion towards a
    // body standing still cut it for every vertex on a surface that moves along itself, one cut
    // for all the cloth (a walking outfit's cloth kept 45-90 % of it, and the shins ran into the
    // trouser legs left behind). With strict_body_contact each vertex is carried in full unless
    // that takes it deeper into the body than it is (into another part of the body), and a layer
    // lying on carried cloth is carried with it (else the self-contact bound, which sees the
    // layers slide over each other, cut the carry again).
    double alpha = 1;
    if (options.strict_body_contact) {
        spread_carry_to_layers(carry);
        keep_safe_carry(p, carry);
    } else {
        alpha = std::min(1.0, obstacle_step_bound(p, carry));
    }
    if (options.self_contact) alpha = std::min(alpha, self_contact.max_safe_step(p, carry * alpha, 0.9) * alpha);
    return std::max(alpha, 0.0) * carry;
}

void Simulator::Impl::spread_carry_to_layers(Eigen::MatrixX3d& carry) const {
    if (pair_friction.empty()) return;
    const Eigen::MatrixX3d own = carry;
    Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(carry.rows(), 3);
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(carry.rows());
    for (const PairFriction& f : pair_friction) {
        // The two sides of a pair: the closest points' weights are positive on one, negative on
        // the other, and sum to 1 and -1.
        Eigen::Vector3d side[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
        bool carried[2] = {false, false};
        for (int k = 0; k < 4; ++k) {
            const double w = f.frame.weights(k);
            if (w == 0) continue;
            const int s = w > 0 ? 0 : 1;
            const auto v = static_cast<Eigen::Index>(f.frame.pair.v[static_cast<std::size_t>(k)]);
            side[s] += std::abs(w) * own.row(v).transpose();
            carried[s] = carried[s] || own.row(v).squaredNorm() > 0;
        }
        for (int k = 0; k < 4; ++k) {
            const double w = f.frame.weights(k);
            const int s = w > 0 ? 0 : 1;
            const int v = f.frame.pair.v[static_cast<std::size_t>(k)];
            if (w == 0 || !carried[1 - s] || own.row(v).squaredNorm() > 0 || pinned[static_cast<std::size_t>(v)])
                continue;
            sum.row(v) += std::abs(w) * side[1 - s].transpose();
            weight(v) += std::abs(w);
        }
    }
    for (Eigen::Index v = 0; v < carry.rows(); ++v)
        if (weight(v) > 0) carry.row(v) = sum.row(v) / weight(v);
}

void Simulator::Impl::keep_safe_carry(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& carry) const {
    const double h = options.contact_thickness_m;
    core::parallel_for(static_cast<int>(carry.rows()), [&](int i) {
        if (carry.row(i).squaredNorm() == 0) return;
        const double now = contacts[static_cast<std::size_t>(i)].distance;
        const Eigen::Vector3d to = (p.row(i) + carry.row(i)).transpose();
        const ObstacleQuery q = obstacle->closest(to, kLostContactRadius);
        // Kept if the carried position is outside the body, or inside it no deeper than the
        // vertex is now (a vertex the body moved into, carried back out of it).
        if (!q.found || q.signed_distance_m >= 0 || q.signed_distance_m >= std::min(now, h) - 0.1 * h) return;
        carry.row(i).setZero();
    }, 64);
}

bool Simulator::Impl::clamp_free_approach(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& dx) const {
    bool changed = false;
    for (const VertexContact& c : contacts) {
        if (c.vertex < 0 || pinned[static_cast<std::size_t>(c.vertex)]) continue;
        // Vertices with nothing within the query radius are left to obstacle_step_bound: cut
        // one by one, a cloth in free flight would be sheared.
        const double move = dx.row(c.vertex).norm();
        if (!std::isfinite(c.distance) || c.distance <= 0 || move <= 0.9 * c.distance || plane_active(p, c.vertex))
            continue;
        dx.row(c.vertex) *= 0.9 * c.distance / move;
        changed = true;
    }
    return changed;
}

void Simulator::Impl::lag_pair_friction(const Eigen::MatrixX3d& p) {
    pair_friction.clear();
    if (!friction_active() || !options.self_contact || options.cloth_friction <= 0) return;
    const double h = options.contact_thickness_m, k = self_contact_stiffness();
    for (const internal::PairFrame& f : self_contact.contact_frames(p, h))
        pair_friction.push_back({f, k * (h - f.distance_m)});
}

double Simulator::Impl::friction_epsilon() const {
    return options.friction_slip_speed_m_per_s * (step_dt > 0 ? step_dt : options.static_damping_time_s);
}

double Simulator::Impl::self_contact_stiffness() const {
    return options.contact_stiffness_n_per_m3 * (area.size() ? area.mean() : 0.0);
}

void Simulator::Impl::set_rest_filter() {
    const int np = static_cast<int>(mesh.pattern.rows());
    std::vector<int> point_vertex(static_cast<std::size_t>(np), -1);
    DisjointSets pieces(np);
    for (int f = 0; f < mesh.face_count(); ++f)
        for (int c = 0; c < 3; ++c) {
            point_vertex[static_cast<std::size_t>(mesh.pattern_faces(f, c))] = mesh.faces(f, c);
            pieces.join(mesh.pattern_faces(f, c), mesh.pattern_faces(f, (c + 1) % 3));
        }
    // Points no face uses take vertex 0 on a piece of their own (never near anything).
    std::vector<int> piece(static_cast<std::size_t>(np));
    for (int i = 0; i < np; ++i) {
        piece[static_cast<std::size_t>(i)] = pieces.find(i);
        if (point_vertex[static_cast<std::size_t>(i)] < 0) point_vertex[static_cast<std::size_t>(i)] = 0;
    }
    self_contact.set_rest_filter(mesh.pattern, point_vertex, mesh.pattern_faces, piece,
                                 2 * options.contact_thickness_m);
}

double Simulator::Impl::max_stitch_gap(const Eigen::MatrixX3d& p) const {
    double gap = 0;
    for (const Stitch& st : stitches) gap = std::max(gap, (p.row(st.a) - p.row(st.b)).norm());
    return gap;
}

}  // namespace drape::cloth
