// Separating the crossing parts of a dressed garment (see untangle.hpp).
#include <drape/garment/untangle.hpp>

#include "dressing_internal.hpp"

#include <drape/cloth/intersections.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace drape::garment {

bool UntangleOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& t) {
        if (why) *why = t;
        return false;
    };
    if (max_iterations < 1)
        return fail("UntangleOptions::max_iterations = " + std::to_string(max_iterations) + " must be >= 1");
    if (!(step_m > 0 && step_m <= 0.05))
        return fail("UntangleOptions::step_m = " + std::to_string(step_m) + " must be in (0, 0.05] m");
    if (!(clearance_m >= 0 && std::isfinite(clearance_m)))
        return fail("UntangleOptions::clearance_m = " + std::to_string(clearance_m) + " must be >= 0");
    return true;
}

std::string UntangleSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "untangled" : "NOT untangled") << ": " << initial_self_intersections << " -> "
       << self_intersections << " self-intersections in " << iterations << " round(s), " << vertices_moved
       << " vertices moved (at most " << 1000 * max_displacement_m << " mm), " << seconds << " s";
    return os.str();
}

UntangleSummary untangle_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& body_vertices,
                                 const Eigen::MatrixX3i& body_faces, const UntangleOptions& options,
                                 Eigen::MatrixX3d& positions) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    require(options.is_valid(&why), "untangle_garment: ", why);
    const int nv = mesh.cloth.vertex_count();
    require(positions.rows() == nv && positions.allFinite(), "untangle_garment: positions have ", positions.rows(),
            " rows (need ", nv, ", all finite)");
    UntangleSummary summary;
    const std::vector<int> rep = detail::sewn_representatives(nv, mesh.stitches);
    const Eigen::MatrixX3i merged = detail::sewn_faces(mesh);
    std::vector<std::vector<int>> ring(static_cast<size_t>(nv));  // between representatives
    for (const auto& e : detail::mesh_edges(merged)) {
        ring[size_t(e[0])].push_back(e[1]);
        ring[size_t(e[1])].push_back(e[0]);
    }
    const cloth::Obstacle body(body_vertices, body_faces);
    const Eigen::MatrixX3d start = positions;
    Eigen::MatrixX3d X = positions, best = positions;
    std::vector<std::pair<int, int>> pairs;
    int best_count = std::numeric_limits<int>::max(), since_best = 0;
    double step = options.step_m;
    bool local = false;
    for (int it = 0;; ++it) {
        pairs.clear();
        const int count = cloth::count_self_intersections(X, merged, &pairs);
        if (it == 0) summary.initial_self_intersections = count;
        if (count < best_count) {
            best_count = count, best = X, since_best = 0;
        } else if (++since_best % 10 == 0) {
            step = std::min(4 * options.step_m, 1.5 * step);  // stuck: larger moves
        }
        if (count == 0 || it >= options.max_iterations) break;
        if (!local && since_best >= 20) {
            // Layering along the body normal is stuck (where that normal is ambiguous, as in
            // an armpit, or the two triangles are side by side): from the best state on,
            // each crossing is undone locally.
            local = true, X = best, since_best = 0, step = options.step_m;
        }
        summary.iterations = it + 1;
        Eigen::MatrixX3d push = Eigen::MatrixX3d::Zero(nv, 3);
        std::vector<int> hits(static_cast<size_t>(nv), 0);
        const auto corner = [&](int f, int k) { return Eigen::Vector3d(X.row(merged(f, k)).transpose()); };
        const auto add = [&](int v, const Eigen::Vector3d& d) {
            push.row(v) += d.transpose();
            ++hits[size_t(v)];
        };
        for (const auto& [f, g] : pairs) {
            if (!local) {
                // The two triangles move apart along the body normal at the crossing, the
                // outer one (farther along that normal) outwards.
                const Eigen::Vector3d cf = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
                const Eigen::Vector3d cg = (corner(g, 0) + corner(g, 1) + corner(g, 2)) / 3.0;
                const cloth::ObstacleQuery q = body.closest(0.5 * (cf + cg), std::numeric_limits<double>::infinity());
                if (!q.found) continue;
                const double sign = (cf - cg).dot(q.normal) >= 0 ? 1.0 : -1.0;
                for (int k = 0; k < 3; ++k) {
                    add(merged(f, k), sign * step * q.normal);
                    add(merged(g, k), -sign * step * q.normal);
                }
                continue;
            }
            // Local: the corner of each triangle that lies alone on its side of the other's
            // plane is moved across it (halfway each), with the other corners staying put.
            for (const auto& [a, b] : {std::pair<int, int>{f, g}, std::pair<int, int>{g, f}}) {
                const Eigen::Vector3d n = (corner(b, 1) - corner(b, 0)).cross(corner(b, 2) - corner(b, 0)).normalized();
                if (!n.allFinite()) continue;
                double d[3];
                for (int k = 0; k < 3; ++k) d[k] = (corner(a, k) - corner(b, 0)).dot(n);
                const int positive = (d[0] > 0) + (d[1] > 0) + (d[2] > 0);
                const double majority = positive >= 2 ? 1.0 : -1.0;
                for (int k = 0; k < 3; ++k)
                    if (d[k] * majority <= 0) add(merged(a, k), (majority * step - d[k]) * 0.5 * n);
            }
        }
        Eigen::MatrixX3d D = Eigen::MatrixX3d::Zero(nv, 3);
        for (int v = 0; v < nv; ++v) {
            if (hits[size_t(v)] == 0) continue;
            D.row(v) = push.row(v) / hits[size_t(v)];
        }
        // One ring of neighbours follows halfway, so the moved vertices do not form spikes
        // that cross their own neighbourhood.
        Eigen::MatrixX3d spread = D;
        for (int v = 0; v < nv; ++v) {
            if (hits[size_t(v)] > 0 || rep[size_t(v)] != v) continue;
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            int k = 0;
            for (int w : ring[size_t(v)])
                if (hits[size_t(w)] > 0) sum += D.row(w).transpose(), ++k;
            if (k > 0) spread.row(v) = (0.5 * sum / k).transpose();
        }
        // The inner side stops at the clearance (or where it is, if already closer).
        for (int v = 0; v < nv; ++v) {
            if (rep[size_t(v)] != v || spread.row(v).squaredNorm() == 0) continue;
            const Eigen::Vector3d x = X.row(v).transpose();
            const cloth::ObstacleQuery q = body.closest(x, std::numeric_limits<double>::infinity());
            if (!q.found) continue;
            const double sd = (x - q.point).dot(q.normal);
            const double floor = std::min(sd, options.clearance_m);
            const double after = sd + spread.row(v).dot(q.normal.transpose());
            if (after < floor) spread.row(v) += (floor - after) * q.normal.transpose();
        }
        for (int v = 0; v < nv; ++v) X.row(v) += spread.row(rep[size_t(v)]);
    }
    positions = best;
    summary.self_intersections = best_count;
    for (int v = 0; v < nv; ++v) {
        const double d = (best.row(v) - start.row(v)).norm();
        if (d > 0) ++summary.vertices_moved;
        summary.max_displacement_m = std::max(summary.max_displacement_m, d);
    }
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return summary;
}

}  // namespace drape::garment
