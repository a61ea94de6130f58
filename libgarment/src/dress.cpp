#include <drape/garment/dress.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace drape::garment {

namespace {

// Re-throws a template's error with its parameter names prefixed by the sizing group.
template <class F>
Pattern with_group(const std::string& group, F make) {
    try {
        return make();
    } catch (const InvalidInput& e) {
        std::string text = e.what();
        for (size_t pos = text.find("parameter "); pos != std::string::npos;
             pos = text.find("parameter ", pos + 1))
            text.insert(pos + 10, group + ".");
        throw InvalidInput("dress: " + text);
    }
}

}  // namespace

Pattern make_dress(const DressSizing& g) {
    const Pattern bodice = with_group("bodice", [&] { return make_tshirt(g.bodice); });
    const Pattern skirt = with_group("skirt", [&] { return make_circle_skirt(g.skirt); });
    const double mismatch = std::abs(g.skirt.l1 - g.bodice.w2) / std::max(g.skirt.l1, g.bodice.w2);
    require(mismatch <= kMaxSeamMismatch, "dress: waist seam: skirt.l1 = ", g.skirt.l1,
            " cm must equal bodice.w2 = ", g.bodice.w2, " cm within 1 % (differs by ",
            100 * mismatch, " %)");

    Pattern pattern;
    pattern.name = "dress";
    for (size_t i = 0; i < bodice.panels.size(); ++i) {
        pattern.panels.push_back(bodice.panels[i]);
        pattern.panels.back().name = "bodice_" + bodice.panels[i].name;
        pattern.placements.push_back(bodice.placements[i]);
    }
    pattern.seams = bodice.seams;
    const int offset = static_cast<int>(pattern.panels.size());
    // The skirt hangs from the bodice hem: its waist arc (centre at its origin) goes where
    // the bodice hem's middle is.
    for (size_t i = 0; i < skirt.panels.size(); ++i) {
        pattern.panels.push_back(skirt.panels[i]);
        pattern.panels.back().name = "skirt_" + skirt.panels[i].name;
        PanelPlacement pl = skirt.placements[i];
        pl.translation_cm.y() = bodice.placements[i].translation_cm.y();
        pattern.placements.push_back(pl);
    }
    for (Seam s : skirt.seams) {
        s.panel_a += offset;
        s.panel_b += offset;
        pattern.seams.push_back(s);
    }
    // Waist seams: skirt waist (edge 2, right to left) to bodice hem (edge 0, left to right).
    pattern.seams.push_back({offset + 0, 2, 0, 0, SeamOrientation::reversed});
    pattern.seams.push_back({offset + 1, 2, 1, 0, SeamOrientation::reversed});
    pattern.validate();
    return pattern;
}

}  // namespace drape::garment
