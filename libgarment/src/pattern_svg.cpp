#include <drape/garment/pattern_svg.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace drape::garment {

namespace {

constexpr double kChordCm = 0.5;

// Outward offset of a closed counter-clockwise polygon by d (miter joins, limited to 3 d).
std::vector<Eigen::Vector2d> offset_outline(const std::vector<Eigen::Vector2d>& poly, double d) {
    const size_t n = poly.size();
    std::vector<Eigen::Vector2d> out(n);
    for (size_t i = 0; i < n; ++i) {
        const Eigen::Vector2d a = (poly[i] - poly[(i + n - 1) % n]).normalized();
        const Eigen::Vector2d b = (poly[(i + 1) % n] - poly[i]).normalized();
        const Eigen::Vector2d na(a.y(), -a.x()), nb(b.y(), -b.x());  // right = outward (CCW)
        Eigen::Vector2d m = na + nb;
        if (m.norm() < 1e-9) m = na;
        m.normalize();
        const double c = std::max(m.dot(na), 1.0 / 3.0);
        out[i] = poly[i] + m * (d / c);
    }
    return out;
}

struct Frame {  // panel cm -> SVG user units (cm, y down)
    Eigen::Vector2d offset;
    double height;
    Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
        return Eigen::Vector2d(p.x() + offset.x(), height - (p.y() + offset.y()));
    }
};

void path(std::ostringstream& os, const std::vector<Eigen::Vector2d>& pts, const Frame& f,
          bool closed, const char* style) {
    os << "<path d=\"";
    for (size_t i = 0; i < pts.size(); ++i) {
        const Eigen::Vector2d q = f(pts[i]);
        os << (i ? " L" : "M") << q.x() << "," << q.y();
    }
    os << (closed ? " Z" : "") << "\" " << style << "/>\n";
}

}  // namespace

bool SvgOptions::is_valid(std::string* why) const {
    if (!(seam_allowance_cm >= 0 && seam_allowance_cm <= 5)) {
        if (why) *why = "SvgOptions::seam_allowance_cm = " + std::to_string(seam_allowance_cm) +
                        " must be in [0, 5] cm";
        return false;
    }
    if (!(gap_cm >= 0 && gap_cm <= 100)) {
        if (why) *why = "SvgOptions::gap_cm = " + std::to_string(gap_cm) + " must be in [0, 100] cm";
        return false;
    }
    return true;
}

std::string pattern_to_svg(const Pattern& pattern, const SvgOptions& options) {
    std::string why;
    require(options.is_valid(&why), "pattern_to_svg: ", why);
    pattern.validate();
    const double margin = options.gap_cm + options.seam_allowance_cm;
    const std::vector<Eigen::Vector2d> offsets = layout_offsets(pattern, margin);
    double width = margin, height = 0;
    for (size_t i = 0; i < pattern.panels.size(); ++i) {
        Eigen::Vector2d lo, hi;
        pattern.panels[i].bounds(&lo, &hi);
        width = std::max(width, hi.x() + offsets[i].x() + margin);
        height = std::max(height, hi.y() + offsets[i].y() + margin);
    }
    height += 4.0;  // room for the scale bar
    const Frame scale_frame{Eigen::Vector2d::Zero(), height};

    std::ostringstream os;
    os << std::fixed << std::setprecision(3);
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "cm\" height=\""
       << height << "cm\" viewBox=\"0 0 " << width << " " << height << "\">\n"
       << "<title>" << pattern.name << " (true scale: 1 unit = 1 cm)</title>\n"
       << "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" "
          "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto-start-reverse\">"
          "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"black\"/></marker></defs>\n"
       << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (size_t i = 0; i < pattern.panels.size(); ++i) {
        const Panel& panel = pattern.panels[i];
        const Frame f{offsets[i], height};
        const std::vector<Eigen::Vector2d> seam_line = panel.outline(kChordCm);
        os << "<g id=\"" << panel.name << "\">\n";
        if (options.seam_allowance_cm > 0)
            path(os, offset_outline(seam_line, options.seam_allowance_cm), f, true,
                 "fill=\"none\" stroke=\"black\" stroke-width=\"0.06\"");
        path(os, seam_line, f, true,
             options.seam_allowance_cm > 0
                 ? "fill=\"#f4f0e6\" stroke=\"black\" stroke-width=\"0.04\" stroke-dasharray=\"0.4,0.2\""
                 : "fill=\"#f4f0e6\" stroke=\"black\" stroke-width=\"0.06\"");
        for (const InternalLine& l : panel.internal_lines)
            path(os, {l.a, l.b}, f, false,
                 "stroke=\"#555\" stroke-width=\"0.04\" stroke-dasharray=\"1,0.3,0.2,0.3\"");
        const double notch_len = std::max(0.6, options.seam_allowance_cm);
        for (const Notch& n : panel.notches) {
            const Edge& e = panel.edges[n.edge];
            const Eigen::Vector2d p = e.point_at_fraction(n.fraction);
            const Eigen::Vector2d t = e.tangent_at_fraction(n.fraction);
            path(os, {p, p + notch_len * Eigen::Vector2d(t.y(), -t.x())}, f, false,
                 "stroke=\"black\" stroke-width=\"0.08\"");
        }
        Eigen::Vector2d lo, hi;
        panel.bounds(&lo, &hi);
        const Eigen::Vector2d c = 0.5 * (lo + hi), g = panel.grain.normalized();
        const double half = 0.3 * std::min((hi - lo).cwiseAbs().maxCoeff(), 60.0);
        path(os, {c - half * g, c + half * g}, f, false,
             "stroke=\"black\" stroke-width=\"0.06\" marker-start=\"url(#arrow)\" "
             "marker-end=\"url(#arrow)\"");
        const Eigen::Vector2d label = f(c + Eigen::Vector2d(0.8, 0.2 * half));
        os << "<text x=\"" << label.x() << "\" y=\"" << label.y()
           << "\" font-family=\"sans-serif\" font-size=\"1.6\">" << panel.name << "</text>\n"
           << "<text x=\"" << label.x() << "\" y=\"" << label.y() + 1.4
           << "\" font-family=\"sans-serif\" font-size=\"0.9\">" << pattern.name
           << " · cut 1 · grain ↕ · seam allowance " << options.seam_allowance_cm
           << " cm</text>\n</g>\n";
    }
    // A 10 cm scale bar to check the print scale.
    const Eigen::Vector2d s0 = scale_frame(Eigen::Vector2d(margin, 1.5));
    os << "<path d=\"M" << s0.x() << "," << s0.y() << " h10\" stroke=\"black\" stroke-width=\"0.1\"/>\n"
       << "<text x=\"" << s0.x() + 10.5 << "\" y=\"" << s0.y() + 0.3
       << "\" font-family=\"sans-serif\" font-size=\"0.8\">10 cm</text>\n</svg>\n";
    return os.str();
}

std::string grading_sheet_to_svg(const std::vector<GradedSize>& sizes) {
    require(!sizes.empty(), "grading_sheet_to_svg: no size given");
    for (size_t k = 0; k < sizes.size(); ++k) {
        require(sizes[k].pattern != nullptr, "grading_sheet_to_svg: size ", k, " has no pattern");
        sizes[k].pattern->validate();
        const Pattern& p = *sizes[k].pattern;
        const Pattern& first = *sizes[0].pattern;
        require(p.panels.size() == first.panels.size(), "grading_sheet_to_svg: size '", sizes[k].label, "' has ",
                p.panels.size(), " panels, size '", sizes[0].label, "' ", first.panels.size());
        for (size_t i = 0; i < p.panels.size(); ++i)
            require(p.panels[i].name == first.panels[i].name, "grading_sheet_to_svg: panel ", i, " is '",
                    p.panels[i].name, "' in size '", sizes[k].label, "' but '", first.panels[i].name, "' in '",
                    sizes[0].label, "'");
    }
    // The nest of each panel: the union of the sizes' boxes once aligned on the bottom centre.
    const size_t panels = sizes[0].pattern->panels.size();
    std::vector<Eigen::Vector2d> anchor(sizes.size() * panels);  // bottom centre of each (size, panel)
    std::vector<double> half_width(panels, 0), top(panels, 0);
    for (size_t k = 0; k < sizes.size(); ++k)
        for (size_t i = 0; i < panels; ++i) {
            Eigen::Vector2d lo, hi;
            sizes[k].pattern->panels[i].bounds(&lo, &hi);
            anchor[k * panels + i] = Eigen::Vector2d(0.5 * (lo.x() + hi.x()), lo.y());
            half_width[i] = std::max(half_width[i], 0.5 * (hi.x() - lo.x()));
            top[i] = std::max(top[i], hi.y() - lo.y());
        }
    const double gap = SvgOptions{}.gap_cm;
    std::vector<double> centre_x(panels);
    double x = gap, height = 0;
    for (size_t i = 0; i < panels; ++i) {
        centre_x[i] = x + half_width[i];
        x += 2 * half_width[i] + gap;
        height = std::max(height, top[i] + 2 * gap);
    }
    const double legend = 2.0 + 1.4 * double(sizes.size());
    height += legend;
    const double width = std::max(x, 40.0);
    static const char* colours[] = {"#1f5fbf", "#c0392b", "#27864a", "#8e44ad", "#d35400"};

    std::ostringstream os;
    os << std::fixed << std::setprecision(3);
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "cm\" height=\"" << height
       << "cm\" viewBox=\"0 0 " << width << " " << height << "\">\n"
       << "<title>grading sheet: " << sizes[0].pattern->name << " (true scale: 1 unit = 1 cm)</title>\n"
       << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (size_t i = 0; i < panels; ++i) {
        os << "<g id=\"" << sizes[0].pattern->panels[i].name << "\">\n";
        for (size_t k = 0; k < sizes.size(); ++k) {
            const Eigen::Vector2d& a = anchor[k * panels + i];
            const Frame f{Eigen::Vector2d(centre_x[i] - a.x(), gap - a.y()), height - legend};
            const std::string style = std::string("fill=\"none\" stroke=\"") + colours[k % 5] +
                                      "\" stroke-width=\"0.08\"" + (k ? " stroke-dasharray=\"0.6,0.3\"" : "");
            path(os, sizes[k].pattern->panels[i].outline(kChordCm), f, true, style.c_str());
        }
        const Frame f0{Eigen::Vector2d(centre_x[i], gap), height - legend};
        const Eigen::Vector2d label = f0(Eigen::Vector2d(-half_width[i] + 0.5, top[i] + 1.5));
        os << "<text x=\"" << label.x() << "\" y=\"" << label.y() << "\" font-family=\"sans-serif\" font-size=\"1.6\">"
           << sizes[0].pattern->panels[i].name << "</text>\n</g>\n";
    }
    for (size_t k = 0; k < sizes.size(); ++k) {
        const double y = height - legend + 1.5 + 1.4 * double(k);
        os << "<path d=\"M" << gap << "," << y << " h4\" stroke=\"" << colours[k % 5] << "\" stroke-width=\"0.12\""
           << (k ? " stroke-dasharray=\"0.6,0.3\"" : "") << "/>\n"
           << "<text x=\"" << gap + 4.6 << "\" y=\"" << y + 0.4 << "\" font-family=\"sans-serif\" font-size=\"1.0\">"
           << sizes[k].label << "</text>\n";
    }
    const double yb = height - 0.8;
    os << "<path d=\"M" << width - gap - 10 << "," << yb << " h10\" stroke=\"black\" stroke-width=\"0.1\"/>\n"
       << "<text x=\"" << width - gap - 10 << "\" y=\"" << yb - 0.4
       << "\" font-family=\"sans-serif\" font-size=\"0.8\">10 cm</text>\n</svg>\n";
    return os.str();
}

void write_grading_sheet_svg(const std::filesystem::path& path, const std::vector<GradedSize>& sizes) {
    write_text_atomically(path, grading_sheet_to_svg(sizes));
}

void write_pattern_svg(const std::filesystem::path& path, const Pattern& pattern,
                       const SvgOptions& options) {
    write_text_atomically(path, pattern_to_svg(pattern, options));
}

}  // namespace drape::garment
