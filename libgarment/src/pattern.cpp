#include <drape/garment/pattern.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace drape::garment {

bool Pattern::is_valid(std::string* why) const {
    auto fail = [&](const std::string& text) {
        if (why) *why = "pattern '" + name + "': " + text;
        return false;
    };
    if (panels.empty()) return fail("has no panels");
    if (placements.size() != panels.size())
        return fail("has " + std::to_string(placements.size()) + " placements for " +
                    std::to_string(panels.size()) + " panels");
    std::set<std::string> names;
    for (const Panel& p : panels) {
        std::string reason;
        if (!p.is_valid(&reason)) return fail(reason);
        if (!names.insert(p.name).second) return fail("panel name '" + p.name + "' repeats");
    }
    std::set<std::pair<int, int>> used;
    for (size_t s = 0; s < seams.size(); ++s) {
        const Seam& seam = seams[s];
        const std::string who = "seam " + std::to_string(s);
        for (auto [p, e] : {std::pair{seam.panel_a, seam.edge_a}, std::pair{seam.panel_b, seam.edge_b}}) {
            if (p < 0 || p >= int(panels.size()))
                return fail(who + " names panel " + std::to_string(p) + " (have " +
                            std::to_string(panels.size()) + ")");
            if (e < 0 || e >= int(panels[p].edges.size()))
                return fail(who + " names edge " + std::to_string(e) + " of panel '" +
                            panels[p].name + "' (it has " +
                            std::to_string(panels[p].edges.size()) + ")");
            if (!used.insert({p, e}).second)
                return fail(who + ": edge " + std::to_string(e) + " of panel '" +
                            panels[p].name + "' is in two seams (or sewn to itself)");
        }
        const double mismatch = seam_mismatch(seam);
        if (mismatch > kMaxSeamMismatch) {
            std::ostringstream os;
            os << who << " (" << panels[seam.panel_a].name << " edge " << seam.edge_a << " "
               << panels[seam.panel_a].edges[seam.edge_a].length() << " cm, "
               << panels[seam.panel_b].name << " edge " << seam.edge_b << " "
               << panels[seam.panel_b].edges[seam.edge_b].length() << " cm) lengths differ by "
               << 100 * mismatch << " % (max " << 100 * kMaxSeamMismatch << " %)";
            return fail(os.str());
        }
    }
    return true;
}

void Pattern::validate() const {
    std::string why;
    if (!is_valid(&why)) throw InvalidInput(why);
}

double Pattern::seam_mismatch(const Seam& seam) const {
    const double a = panels[seam.panel_a].edges[seam.edge_a].length();
    const double b = panels[seam.panel_b].edges[seam.edge_b].length();
    return std::abs(a - b) / std::max({a, b, 1e-12});
}

int Pattern::panel_index(const std::string& panel_name) const {
    for (size_t i = 0; i < panels.size(); ++i)
        if (panels[i].name == panel_name) return static_cast<int>(i);
    return -1;
}

double Pattern::total_area() const {
    double a = 0;
    for (const Panel& p : panels) a += p.area();
    return a;
}

std::vector<Eigen::Vector2d> layout_offsets(const Pattern& pattern, double gap_cm) {
    require(std::isfinite(gap_cm) && gap_cm >= 0, "layout_offsets: gap_cm = ", gap_cm,
            " must be >= 0");
    std::vector<Eigen::Vector2d> offsets;
    double x = gap_cm;
    for (const Panel& p : pattern.panels) {
        Eigen::Vector2d lo, hi;
        p.bounds(&lo, &hi);
        offsets.emplace_back(x - lo.x(), gap_cm - lo.y());
        x += (hi.x() - lo.x()) + gap_cm;
    }
    return offsets;
}

}  // namespace drape::garment
