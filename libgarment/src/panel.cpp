#include <drape/garment/panel.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape::garment {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// True if closed segments pq and rs intersect (including touching).
bool segments_intersect(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                        const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
    const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
    const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    auto on_segment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& c, double d) {
        return std::abs(d) < 1e-12 && c.x() >= std::min(a.x(), b.x()) - 1e-12 &&
               c.x() <= std::max(a.x(), b.x()) + 1e-12 &&
               c.y() >= std::min(a.y(), b.y()) - 1e-12 && c.y() <= std::max(a.y(), b.y()) + 1e-12;
    };
    return on_segment(p, q, r, d1) || on_segment(p, q, s, d2) || on_segment(r, s, p, d3) ||
           on_segment(r, s, q, d4);
}

bool fail(std::string* why, const std::string& text) {
    if (why) *why = text;
    return false;
}

}  // namespace

bool Panel::is_valid(std::string* why) const {
    const std::string who = "panel '" + name + "'";
    if (name.empty()) return fail(why, "panel has an empty name");
    if (edges.size() < 2) return fail(why, who + " has " + std::to_string(edges.size()) +
                                               " edges (needs a closed loop of >= 2)");
    for (size_t i = 0; i < edges.size(); ++i) {
        const Edge& e = edges[i];
        if (!e.start.allFinite() || !e.end.allFinite() || !e.control1.allFinite() ||
            !e.control2.allFinite() || !std::isfinite(e.bulge))
            return fail(why, who + " edge " + std::to_string(i) + " has a non-finite number");
        if (e.length() < 1e-6)
            return fail(why, who + " edge " + std::to_string(i) + " has zero length");
        const Edge& next = edges[(i + 1) % edges.size()];
        if ((e.end - next.start).norm() > 1e-6) {
            std::ostringstream os;
            os << who << " edge " << i << " ends at (" << e.end.x() << ", " << e.end.y()
               << ") but edge " << (i + 1) % edges.size() << " starts at (" << next.start.x()
               << ", " << next.start.y() << "): the boundary is not closed";
            return fail(why, os.str());
        }
    }
    if (!grain.allFinite() || grain.norm() < 1e-9)
        return fail(why, who + " has a zero or non-finite grain direction");
    for (size_t i = 0; i < notches.size(); ++i)
        if (notches[i].edge < 0 || notches[i].edge >= int(edges.size()) ||
            !(notches[i].fraction >= 0 && notches[i].fraction <= 1))
            return fail(why, who + " notch " + std::to_string(i) + " is not on an edge");
    const double a = area();
    if (!(a > 1e-6)) {
        std::ostringstream os;
        os << who << " has signed area " << a << " cm² (the boundary must be counter-clockwise)";
        return fail(why, os.str());
    }
    const std::vector<Eigen::Vector2d> poly = outline(0.5);
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;  // adjacent through the closing segment
            if (segments_intersect(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) {
                std::ostringstream os;
                os << who << " self-intersects near (" << poly[i].x() << ", " << poly[i].y()
                   << ") cm";
                return fail(why, os.str());
            }
        }
    return true;
}

double Panel::area() const {
    double a = 0;
    for (const Edge& e : edges) a += e.area_term();
    return a;
}

double Panel::perimeter() const {
    double p = 0;
    for (const Edge& e : edges) p += e.length();
    return p;
}

std::vector<Eigen::Vector2d> Panel::outline(double max_chord_cm) const {
    std::vector<Eigen::Vector2d> pts;
    for (const Edge& e : edges) {
        const auto line = e.polyline(max_chord_cm);
        pts.insert(pts.end(), line.begin(), line.end() - 1);
    }
    return pts;
}

void Panel::bounds(Eigen::Vector2d* lo, Eigen::Vector2d* hi) const {
    Eigen::Vector2d a = Eigen::Vector2d::Constant(1e300), b = Eigen::Vector2d::Constant(-1e300);
    for (const auto& p : outline(1.0)) {
        a = a.cwiseMin(p);
        b = b.cwiseMax(p);
    }
    if (lo) *lo = a;
    if (hi) *hi = b;
}

Panel Panel::mirrored(const std::string& new_name) const {
    Panel m;
    m.name = new_name;
    const int n = static_cast<int>(edges.size());
    for (int i = n - 1; i >= 0; --i) m.edges.push_back(edges[i].mirrored_x().reversed());
    m.grain = Eigen::Vector2d(-grain.x(), grain.y());
    for (const Notch& notch : notches) m.notches.push_back({n - 1 - notch.edge, 1.0 - notch.fraction});
    for (const InternalLine& l : internal_lines)
        m.internal_lines.push_back({Eigen::Vector2d(-l.a.x(), l.a.y()),
                                    Eigen::Vector2d(-l.b.x(), l.b.y())});
    return m;
}

}  // namespace drape::garment
