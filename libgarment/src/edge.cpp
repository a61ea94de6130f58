#include <drape/garment/edge.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace drape::garment {

namespace {

constexpr double kPi = 3.14159265358979323846;

// 5-point Gauss-Legendre rule on [0, 1].
constexpr std::array<double, 5> kGaussX = {0.04691007703066800, 0.23076534494715845, 0.5,
                                           0.76923465505284155, 0.95308992296933200};
constexpr std::array<double, 5> kGaussW = {0.11846344252809454, 0.23931433524968323,
                                           0.28444444444444444, 0.23931433524968323,
                                           0.11846344252809454};
constexpr int kCubicSegments = 64;  // sub-intervals of the arc-length table

Eigen::Vector2d cubic_point(const Edge& e, double t) {
    const double s = 1.0 - t;
    return s * s * s * e.start + 3 * s * s * t * e.control1 + 3 * s * t * t * e.control2 +
           t * t * t * e.end;
}

Eigen::Vector2d cubic_derivative(const Edge& e, double t) {
    const double s = 1.0 - t;
    return 3 * s * s * (e.control1 - e.start) + 6 * s * t * (e.control2 - e.control1) +
           3 * t * t * (e.end - e.control2);
}

double cubic_length_between(const Edge& e, double t0, double t1) {
    double sum = 0;
    for (int k = 0; k < 5; ++k) sum += kGaussW[k] * cubic_derivative(e, t0 + (t1 - t0) * kGaussX[k]).norm();
    return sum * (t1 - t0);
}

// Cumulative arc length of a cubic at t = i / kCubicSegments.
std::array<double, kCubicSegments + 1> cubic_table(const Edge& e) {
    std::array<double, kCubicSegments + 1> table{};
    for (int i = 0; i < kCubicSegments; ++i)
        table[i + 1] = table[i] + cubic_length_between(e, double(i) / kCubicSegments,
                                                        double(i + 1) / kCubicSegments);
    return table;
}

// Curve parameter at which the cubic's arc length from the start equals `target`.
double cubic_param_at_length(const Edge& e, const std::array<double, kCubicSegments + 1>& table,
                             double target) {
    if (target <= 0) return 0.0;
    if (target >= table.back()) return 1.0;
    const auto it = std::upper_bound(table.begin(), table.end(), target);
    const int i = std::max(0, int(it - table.begin()) - 1);
    double lo = double(i) / kCubicSegments, hi = double(i + 1) / kCubicSegments;
    for (int iter = 0; iter < 40; ++iter) {
        const double mid = 0.5 * (lo + hi);
        if (table[i] + cubic_length_between(e, double(i) / kCubicSegments, mid) < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

Edge Edge::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    Edge e;
    e.kind = EdgeKind::line;
    e.start = a;
    e.end = b;
    return e;
}

Edge Edge::arc(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double bulge) {
    require(std::isfinite(bulge) && bulge != 0.0 && std::abs(bulge) < 50.0,
            "Edge::arc: bulge ", bulge, " must be finite, non-zero and |bulge| < 50");
    require((b - a).norm() > 1e-9, "Edge::arc: start and end coincide");
    Edge e;
    e.kind = EdgeKind::arc;
    e.start = a;
    e.end = b;
    e.bulge = bulge;
    return e;
}

Edge Edge::cubic(const Eigen::Vector2d& a, const Eigen::Vector2d& c1, const Eigen::Vector2d& c2,
                 const Eigen::Vector2d& b) {
    Edge e;
    e.kind = EdgeKind::cubic;
    e.start = a;
    e.control1 = c1;
    e.control2 = c2;
    e.end = b;
    return e;
}

Edge Edge::reversed() const {
    Edge e = *this;
    std::swap(e.start, e.end);
    std::swap(e.control1, e.control2);
    e.bulge = -bulge;
    return e;
}

Edge Edge::mirrored_x() const {
    Edge e = *this;
    for (Eigen::Vector2d* p : {&e.start, &e.end, &e.control1, &e.control2}) p->x() = -p->x();
    e.bulge = -bulge;  // a reflection turns counter-clockwise sweeps into clockwise ones
    return e;
}

void Edge::arc_geometry(Eigen::Vector2d* centre, double* radius, double* start_angle,
                        double* sweep) const {
    const double theta = 4.0 * std::atan(bulge);
    const Eigen::Vector2d d = end - start;
    const double c = d.norm();
    const Eigen::Vector2d left(-d.y() / c, d.x() / c);
    const Eigen::Vector2d o = 0.5 * (start + end) + left * (0.5 * c / std::tan(0.5 * theta));
    if (centre) *centre = o;
    if (radius) *radius = 0.5 * c / std::abs(std::sin(0.5 * theta));
    if (start_angle) *start_angle = std::atan2(start.y() - o.y(), start.x() - o.x());
    if (sweep) *sweep = theta;
}

double Edge::length() const {
    switch (kind) {
        case EdgeKind::line: return (end - start).norm();
        case EdgeKind::arc: {
            double r = 0, sweep = 0;
            arc_geometry(nullptr, &r, nullptr, &sweep);
            return r * std::abs(sweep);
        }
        case EdgeKind::cubic: return cubic_table(*this).back();
    }
    return 0.0;
}

Eigen::Vector2d Edge::point(double t) const {
    switch (kind) {
        case EdgeKind::line: return start + t * (end - start);
        case EdgeKind::arc: {
            if (t <= 0) return start;
            if (t >= 1) return end;
            Eigen::Vector2d o;
            double r = 0, a0 = 0, sweep = 0;
            arc_geometry(&o, &r, &a0, &sweep);
            const double a = a0 + t * sweep;
            return o + r * Eigen::Vector2d(std::cos(a), std::sin(a));
        }
        case EdgeKind::cubic: return cubic_point(*this, t);
    }
    return start;
}

Eigen::Vector2d Edge::point_at_fraction(double s) const {
    s = std::clamp(s, 0.0, 1.0);
    if (kind != EdgeKind::cubic) return point(s);
    if (s == 0.0) return start;
    if (s == 1.0) return end;
    const auto table = cubic_table(*this);
    return cubic_point(*this, cubic_param_at_length(*this, table, s * table.back()));
}

Eigen::Vector2d Edge::tangent_at_fraction(double s) const {
    s = std::clamp(s, 0.0, 1.0);
    Eigen::Vector2d d = end - start;
    switch (kind) {
        case EdgeKind::line: break;
        case EdgeKind::arc: {
            double a0 = 0, sweep = 0;
            arc_geometry(nullptr, nullptr, &a0, &sweep);
            const double a = a0 + s * sweep;
            d = Eigen::Vector2d(-std::sin(a), std::cos(a)) * (sweep > 0 ? 1.0 : -1.0);
            break;
        }
        case EdgeKind::cubic: {
            const auto table = cubic_table(*this);
            d = cubic_derivative(*this, cubic_param_at_length(*this, table, s * table.back()));
            if (d.norm() < 1e-12) d = end - start;
            break;
        }
    }
    return d.normalized();
}

double Edge::area_term() const {
    switch (kind) {
        case EdgeKind::line: return 0.5 * (start.x() * end.y() - start.y() * end.x());
        case EdgeKind::arc: {
            Eigen::Vector2d o;
            double r = 0, a0 = 0, sweep = 0;
            arc_geometry(&o, &r, &a0, &sweep);
            const double a1 = a0 + sweep;
            return 0.5 * (r * r * sweep + r * (o.x() * (std::sin(a1) - std::sin(a0)) -
                                                o.y() * (std::cos(a1) - std::cos(a0))));
        }
        case EdgeKind::cubic: {
            // x y' - y x' is a polynomial of degree 5: the 5-point rule is exact.
            double sum = 0;
            for (int k = 0; k < 5; ++k) {
                const Eigen::Vector2d p = cubic_point(*this, kGaussX[k]);
                const Eigen::Vector2d d = cubic_derivative(*this, kGaussX[k]);
                sum += kGaussW[k] * (p.x() * d.y() - p.y() * d.x());
            }
            return 0.5 * sum;
        }
    }
    return 0.0;
}

std::vector<Eigen::Vector2d> Edge::sample_uniform(int n) const {
    require(n >= 1, "Edge::sample_uniform: n = ", n, " must be >= 1");
    std::vector<Eigen::Vector2d> pts(n + 1);
    if (kind == EdgeKind::cubic) {
        const auto table = cubic_table(*this);
        for (int i = 0; i <= n; ++i)
            pts[i] = cubic_point(*this, cubic_param_at_length(*this, table, table.back() * i / n));
    } else {
        for (int i = 0; i <= n; ++i) pts[i] = point(double(i) / n);
    }
    pts.front() = start;
    pts.back() = end;
    return pts;
}

std::vector<Eigen::Vector2d> Edge::polyline(double max_chord_cm) const {
    require(max_chord_cm > 0, "Edge::polyline: max_chord_cm = ", max_chord_cm, " must be > 0");
    const double len = length();
    int n = std::max(1, int(std::ceil(len / max_chord_cm)));
    if (kind == EdgeKind::arc) {
        const double sweep = std::abs(4.0 * std::atan(bulge));
        n = std::max(n, int(std::ceil(sweep / (2.0 * kPi / 180.0))));
    } else if (kind == EdgeKind::cubic) {
        n = std::max(n, 32);
    }
    return sample_uniform(n);
}

}  // namespace drape::garment
