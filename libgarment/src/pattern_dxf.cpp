#include <drape/garment/pattern_dxf.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace drape::garment {

namespace {

class DxfWriter {
public:
    DxfWriter() { os_ << std::fixed << std::setprecision(4); }
    void code(int c, const std::string& v) { os_ << c << "\n" << v << "\n"; }
    void code(int c, int v) { os_ << c << "\n" << v << "\n"; }
    void code(int c, double v) { os_ << c << "\n" << v << "\n"; }
    void point(const Eigen::Vector2d& p, int base = 10) {
        code(base, p.x());
        code(base + 10, p.y());
        code(base + 20, 0.0);
    }
    void line(int layer, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        code(0, "LINE");
        code(8, std::to_string(layer));
        point(a, 10);
        point(b, 11);
    }
    void text(int layer, const Eigen::Vector2d& at, double size, const std::string& s) {
        code(0, "TEXT");
        code(8, std::to_string(layer));
        point(at);
        code(40, size);
        code(1, s);
    }
    std::string str() const { return os_.str(); }

private:
    std::ostringstream os_;
};

}  // namespace

std::string pattern_to_dxf(const Pattern& pattern, double max_chord_cm) {
    require(std::isfinite(max_chord_cm) && max_chord_cm > 0, "pattern_to_dxf: max_chord_cm = ",
            max_chord_cm, " must be > 0");
    pattern.validate();
    DxfWriter w;
    w.code(999, "Drape sewing pattern '" + pattern.name + "', AAMA/ASTM style, units cm");
    w.code(0, "SECTION");
    w.code(2, "HEADER");
    w.code(9, "$ACADVER");
    w.code(1, "AC1009");
    w.code(9, "$MEASUREMENT");
    w.code(70, 1);  // metric
    w.code(0, "ENDSEC");

    w.code(0, "SECTION");
    w.code(2, "TABLES");
    w.code(0, "TABLE");
    w.code(2, "LAYER");
    const int layers[] = {0, kDxfLayerBoundary, kDxfLayerNotches, kDxfLayerGrain, kDxfLayerInternal};
    w.code(70, static_cast<int>(std::size(layers)));
    for (int layer : layers) {
        w.code(0, "LAYER");
        w.code(2, std::to_string(layer));
        w.code(70, 0);
        w.code(62, 7);
        w.code(6, "CONTINUOUS");
    }
    w.code(0, "ENDTAB");
    w.code(0, "ENDSEC");

    w.code(0, "SECTION");
    w.code(2, "BLOCKS");
    for (const Panel& panel : pattern.panels) {
        w.code(0, "BLOCK");
        w.code(8, "0");
        w.code(2, panel.name);
        w.code(70, 0);
        w.point(Eigen::Vector2d::Zero());
        w.code(3, panel.name);
        // Boundary (the seam line) as one closed polyline.
        w.code(0, "POLYLINE");
        w.code(8, std::to_string(kDxfLayerBoundary));
        w.code(66, 1);
        w.point(Eigen::Vector2d::Zero());
        w.code(70, 1);  // closed
        for (const Eigen::Vector2d& p : panel.outline(max_chord_cm)) {
            w.code(0, "VERTEX");
            w.code(8, std::to_string(kDxfLayerBoundary));
            w.point(p);
        }
        w.code(0, "SEQEND");
        w.code(8, std::to_string(kDxfLayerBoundary));
        for (const InternalLine& l : panel.internal_lines) w.line(kDxfLayerInternal, l.a, l.b);
        Eigen::Vector2d lo, hi;
        panel.bounds(&lo, &hi);
        const Eigen::Vector2d c = 0.5 * (lo + hi), g = panel.grain.normalized();
        const double half = 0.3 * std::min((hi - lo).maxCoeff(), 60.0);
        w.line(kDxfLayerGrain, c - half * g, c + half * g);
        for (const Notch& n : panel.notches) {
            const Edge& e = panel.edges[n.edge];
            const Eigen::Vector2d p = e.point_at_fraction(n.fraction), t = e.tangent_at_fraction(n.fraction);
            w.line(kDxfLayerNotches, p, p + 0.6 * Eigen::Vector2d(t.y(), -t.x()));
        }
        w.text(kDxfLayerBoundary, c + Eigen::Vector2d(1.0, 2.0), 1.5, "Piece Name: " + panel.name);
        w.text(kDxfLayerBoundary, c + Eigen::Vector2d(1.0, 0.0), 1.0, "Quantity: 1");
        w.code(0, "ENDBLK");
        w.code(8, "0");
    }
    w.code(0, "ENDSEC");

    w.code(0, "SECTION");
    w.code(2, "ENTITIES");
    const std::vector<Eigen::Vector2d> offsets = layout_offsets(pattern);
    for (size_t i = 0; i < pattern.panels.size(); ++i) {
        w.code(0, "INSERT");
        w.code(8, "0");
        w.code(2, pattern.panels[i].name);
        w.point(offsets[i]);
    }
    w.code(0, "ENDSEC");
    w.code(0, "EOF");
    return w.str();
}

void write_pattern_dxf(const std::filesystem::path& path, const Pattern& pattern,
                       double max_chord_cm) {
    write_text_atomically(path, pattern_to_dxf(pattern, max_chord_cm));
}

}  // namespace drape::garment
