#include <drape/garment/grading.hpp>

#include <drape/body/measurements.hpp>
#include <drape/body/skeleton.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/garment/tshirt.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

namespace drape::garment {

namespace {

// The navel height as a fraction of stature: the proposal's convention (sizing_proposal.cpp)
// for where trousers' waist sits, so that graded lengths stay consistent with proposed ones.
constexpr double kNavelHeightRatio = 0.60;
// The knee girth estimate from the thigh (as propose_pants_sizing).
constexpr double kKneeToThigh = 0.65;

double cm(double m) { return 100.0 * m; }

double navel_height(const GradingBody& b) { return kNavelHeightRatio * b.height_cm; }

// The neckline of a top (front and back arcs; they scale with r).
double neckline_cm(const TShirtSizing& g) {
    const Pattern p = make_tshirt(g);
    return p.panels[0].edges[4].length() + p.panels[1].edges[4].length();
}

// The graded values of a template before clamping, with the rule of each (sizing_parameters
// order of that template, without the dress's group prefix).
struct Rule {
    double value;
    const char* rule;
};

std::vector<Rule> grade_skirt(const SkirtSizing& g, const GradingBody& a, const GradingBody& b) {
    const double l1 = g.l1 + 0.5 * (b.waistband_girth_cm - a.waistband_girth_cm);
    const double length = navel_height(b) / navel_height(a);
    return {{l1, "ease over the waistband girth kept"},
            {g.r1 * l1 / g.l1, "waist arc curvature r1/l1 kept (style)"},
            {g.r2 * length, "follows the navel height"},
            {g.alpha, "flare (style)"}};
}

std::vector<Rule> grade_pants(const PantsSizing& g, const GradingBody& a, const GradingBody& b) {
    const double w3 = g.w3 + kKneeToThigh * (b.thigh_girth_cm - a.thigh_girth_cm);
    const double rise = (navel_height(b) - b.crotch_height_cm) / (navel_height(a) - a.crotch_height_cm);
    return {{g.w1 + b.waist_girth_cm - a.waist_girth_cm, "ease over the waist girth kept"},
            {g.w2 + b.hip_girth_cm - a.hip_girth_cm, "ease over the hip girth kept"},
            {w3, "ease over the knee (0.65 x thigh girth) kept"},
            {g.w4 * w3 / g.w3, "leg taper w4/w3 kept (style)"},
            {g.h1 * navel_height(b) / navel_height(a), "follows the navel height"},
            {g.h2 * rise, "follows the rise (navel - crotch height)"},
            {g.h3 * rise, "follows the rise (navel - crotch height)"}};
}

// A top's torso lengths span `torso_a` on the source body and `torso_b` on the target.
std::vector<Rule> grade_top(const TShirtSizing& g, const GradingBody& a, const GradingBody& b, double torso_a,
                            double torso_b, const char* length_rule) {
    const double neck = neckline_cm(g);
    const double torso = torso_b / torso_a;
    return {{g.r * (neck + b.neck_girth_cm - a.neck_girth_cm) / neck, "ease over the neck girth kept"},
            {g.l1 > 0 ? g.w1 + b.upper_arm_girth_cm - a.upper_arm_girth_cm : g.w1,
             g.l1 > 0 ? "ease over the upper-arm girth kept" : "no sleeve: unchanged"},
            {g.w2 + 0.5 * (b.chest_girth_cm - a.chest_girth_cm), "ease over the chest girth kept"},
            {g.h1 * torso, length_rule},
            {g.h2 * torso, length_rule},
            {g.l1 * b.arm_length_cm / a.arm_length_cm, "sleeve length / arm length kept (style)"}};
}

std::vector<Rule> rules_of(const GarmentSizing& g, const GradingBody& a, const GradingBody& b) {
    switch (g.type) {
        case GarmentType::skirt: return grade_skirt(g.skirt, a, b);
        case GarmentType::pants: return grade_pants(g.pants, a, b);
        case GarmentType::tshirt:
            return grade_top(g.tshirt, a, b, a.shoulder_height_cm - a.crotch_height_cm,
                             b.shoulder_height_cm - b.crotch_height_cm, "follows shoulder - crotch height");
        case GarmentType::dress: {
            std::vector<Rule> r = grade_top(g.dress.bodice, a, b, a.shoulder_height_cm - navel_height(a),
                                            b.shoulder_height_cm - navel_height(b), "follows shoulder - navel height");
            // The waist seam: skirt.l1 follows bodice.w2 (make_dress requires them equal).
            std::vector<Rule> s = grade_skirt(g.dress.skirt, a, b);
            const double l1 = g.dress.skirt.l1 * r[2].value / g.dress.bodice.w2;
            s[0] = {l1, "waist seam: follows bodice.w2"};
            s[1] = {g.dress.skirt.r1 * l1 / g.dress.skirt.l1, "waist arc curvature r1/l1 kept (style)"};
            r.insert(r.end(), s.begin(), s.end());
            return r;
        }
    }
    return {};
}

std::vector<StyleParameter> style_of(const GarmentSizing& g, const GarmentSizing& h, const GradingBody& a,
                                     const GradingBody& b) {
    std::vector<StyleParameter> out;
    const auto add = [&](const std::string& name, double before, double after) {
        StyleParameter s;
        s.name = name;
        s.original = before;
        s.graded = after;
        s.relative_change = before != 0 ? std::abs(after - before) / std::abs(before) : std::abs(after);
        out.push_back(s);
    };
    const auto skirt = [&](const std::string& prefix, const SkirtSizing& x, const SkirtSizing& y) {
        add(prefix + "alpha (flare, deg)", x.alpha, y.alpha);
        add(prefix + "r1 / l1 (waist arc curvature)", x.r1 / x.l1, y.r1 / y.l1);
        add(prefix + "r2 / navel height (length)", x.r2 / navel_height(a), y.r2 / navel_height(b));
    };
    const auto top = [&](const std::string& prefix, const TShirtSizing& x, const TShirtSizing& y, double torso_a,
                         double torso_b) {
        if (x.l1 > 0) add(prefix + "l1 / arm length (sleeve length ratio)", x.l1 / a.arm_length_cm, y.l1 / b.arm_length_cm);
        add(prefix + "h2 / torso (length)", x.h2 / torso_a, y.h2 / torso_b);
        add(prefix + "h1 / h2 (armhole position)", x.h1 / x.h2, y.h1 / y.h2);
    };
    switch (g.type) {
        case GarmentType::skirt: skirt("", g.skirt, h.skirt); break;
        case GarmentType::pants:
            add("w4 / w3 (leg taper)", g.pants.w4 / g.pants.w3, h.pants.w4 / h.pants.w3);
            add("h1 / navel height (length)", g.pants.h1 / navel_height(a), h.pants.h1 / navel_height(b));
            add("h2 / h3 (back/front rise)", g.pants.h2 / g.pants.h3, h.pants.h2 / h.pants.h3);
            break;
        case GarmentType::tshirt:
            top("", g.tshirt, h.tshirt, a.shoulder_height_cm - a.crotch_height_cm,
                b.shoulder_height_cm - b.crotch_height_cm);
            break;
        case GarmentType::dress:
            top("bodice.", g.dress.bodice, h.dress.bodice, a.shoulder_height_cm - navel_height(a),
                b.shoulder_height_cm - navel_height(b));
            skirt("skirt.", g.dress.skirt, h.dress.skirt);
            break;
    }
    return out;
}

std::vector<EaseCheck> ease_of(const GarmentSizing& g, const GarmentSizing& h, const GradingBody& a,
                               const GradingBody& b) {
    std::vector<EaseCheck> out;
    const auto add = [&](const std::string& name, double before, double after) { out.push_back({name, before, after}); };
    const auto top = [&](const std::string& prefix, const TShirtSizing& x, const TShirtSizing& y) {
        add(prefix + "chest", 2 * x.w2 - a.chest_girth_cm, 2 * y.w2 - b.chest_girth_cm);
        add(prefix + "neck", neckline_cm(x) - a.neck_girth_cm, neckline_cm(y) - b.neck_girth_cm);
        if (x.l1 > 0) add(prefix + "upper arm", x.w1 - a.upper_arm_girth_cm, y.w1 - b.upper_arm_girth_cm);
    };
    switch (g.type) {
        case GarmentType::skirt:
            add("waistband", 2 * g.skirt.l1 - a.waistband_girth_cm, 2 * h.skirt.l1 - b.waistband_girth_cm);
            break;
        case GarmentType::pants:
            add("waist", g.pants.w1 - a.waist_girth_cm, h.pants.w1 - b.waist_girth_cm);
            add("hip", g.pants.w2 - a.hip_girth_cm, h.pants.w2 - b.hip_girth_cm);
            add("knee (0.65 x thigh)", g.pants.w3 - kKneeToThigh * a.thigh_girth_cm,
                h.pants.w3 - kKneeToThigh * b.thigh_girth_cm);
            break;
        case GarmentType::tshirt: top("", g.tshirt, h.tshirt); break;
        case GarmentType::dress: top("bodice.", g.dress.bodice, h.dress.bodice); break;
    }
    return out;
}

void check_body(const GradingBody& b, const char* which) {
    std::string why;
    require(b.is_valid(&why), "grade_sizing: the ", which, " body: ", why);
}

const char* kNumberWords[] = {"zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"};

}  // namespace

bool GradingBody::is_valid(std::string* why) const {
    const std::pair<const char*, double> values[] = {
        {"height_cm", height_cm},           {"chest_girth_cm", chest_girth_cm},
        {"waist_girth_cm", waist_girth_cm}, {"hip_girth_cm", hip_girth_cm},
        {"thigh_girth_cm", thigh_girth_cm}, {"shoulder_height_cm", shoulder_height_cm},
        {"crotch_height_cm", crotch_height_cm}, {"waistband_girth_cm", waistband_girth_cm},
        {"neck_girth_cm", neck_girth_cm},   {"upper_arm_girth_cm", upper_arm_girth_cm},
        {"arm_length_cm", arm_length_cm}};
    for (const auto& [name, v] : values)
        if (!(std::isfinite(v) && v > 0)) {
            if (why) *why = std::string("GradingBody::") + name + " = " + std::to_string(v) + " must be positive";
            return false;
        }
    if (!(crotch_height_cm < kNavelHeightRatio * height_cm && kNavelHeightRatio * height_cm < shoulder_height_cm &&
          shoulder_height_cm < height_cm)) {
        if (why)
            *why = "GradingBody: heights must be ordered crotch (" + std::to_string(crotch_height_cm) +
                   " cm) < navel (0.6 x stature = " + std::to_string(kNavelHeightRatio * height_cm) +
                   " cm) < shoulder (" + std::to_string(shoulder_height_cm) + " cm) < stature";
        return false;
    }
    return true;
}

GradingBody measure_for_grading(const body::BodyModel& model, const body::ShapedBody& shaped) {
    require(shaped.vertices.rows() == model.vertex_count() && shaped.vertices.cols() == 3,
            "measure_for_grading: the shaped body does not fit the model");
    const body::BodyMeasurements m = body::measure_body(model, shaped.vertices);
    GradingBody b;
    b.height_cm = cm(m.height_m);
    b.chest_girth_cm = cm(m.chest_girth_m);
    b.waist_girth_cm = cm(m.waist_girth_m);
    b.hip_girth_cm = cm(m.hip_girth_m);
    b.thigh_girth_cm = cm(m.thigh_girth_m);
    b.shoulder_height_cm = cm(m.shoulder_height_m);
    b.crotch_height_cm = cm(m.crotch_height_m);
    b.waistband_girth_cm = cm(skirt_waistband(model, shaped).girth_m);
    b.neck_girth_cm = cm(neck_girth(model, shaped));
    b.upper_arm_girth_cm = cm(upper_arm_girth(model, shaped, 1000.0));  // the whole upper arm
    const auto joint = [&](body::Joint j) { return shaped.joints.row(body::index(j)); };
    b.arm_length_cm = cm((joint(body::Joint::right_elbow) - joint(body::Joint::right_shoulder)).norm() +
                         (joint(body::Joint::right_wrist) - joint(body::Joint::right_elbow)).norm());
    return b;
}

bool SizeChart::is_valid(std::string* why) const {
    if (!(std::isfinite(girth_step_cm) && girth_step_cm >= 1 && girth_step_cm <= 20)) {
        if (why) *why = "SizeChart::girth_step_cm = " + std::to_string(girth_step_cm) + " must be in [1, 20] cm";
        return false;
    }
    return true;
}

bool GradingOptions::is_valid(std::string* why) const {
    if (!chart.is_valid(why)) return false;
    if (!(std::isfinite(style_tolerance) && style_tolerance >= 0 && style_tolerance <= 1)) {
        if (why) *why = "GradingOptions::style_tolerance = " + std::to_string(style_tolerance) + " must be in [0, 1]";
        return false;
    }
    return true;
}

std::string primary_dimension(GarmentType type) {
    return type == GarmentType::tshirt || type == GarmentType::dress ? "chest" : "waist";
}

std::string size_grade_text(int sizes) {
    if (sizes == 0) return "same size";
    const int n = std::abs(sizes);
    const std::string count = n <= 10 ? kNumberWords[n] : std::to_string(n);
    return count + (n == 1 ? " size " : " sizes ") + (sizes > 0 ? "up" : "down");
}

SizeGrade size_grade(GarmentType type, const GradingBody& from, const GradingBody& to, const SizeChart& chart) {
    check_body(from, "source");
    check_body(to, "target");
    std::string why;
    require(chart.is_valid(&why), "size_grade: ", why);
    SizeGrade g;
    g.chart = chart.name;
    g.dimension = primary_dimension(type);
    g.from_cm = g.dimension == "chest" ? from.chest_girth_cm : from.waist_girth_cm;
    g.to_cm = g.dimension == "chest" ? to.chest_girth_cm : to.waist_girth_cm;
    g.sizes = int(std::lround((g.to_cm - g.from_cm) / chart.girth_step_cm));
    g.text = size_grade_text(g.sizes);
    return g;
}

std::string GradingSummary::brief_report() const {
    std::ostringstream os;
    os << std::fixed << std::setprecision(1);
    os << (termination == GradingTermination::graded    ? "graded"
           : termination == GradingTermination::clamped ? "graded with clamps"
                                                        : "invalid pattern")
       << ": " << grade.text << " (" << grade.chart << ", " << grade.dimension << " " << grade.from_cm << " -> "
       << grade.to_cm << " cm), " << clamped << " of " << parameters.size() << " parameters clamped, style change max "
       << std::setprecision(2) << 100 * max_style_change << " %";
    if (!message.empty()) os << "; " << message;
    return os.str();
}

GradingSummary grade_sizing(const GarmentSizing& sizing, const GradingBody& from, const GradingBody& to,
                            const GradingOptions& options, GarmentSizing& graded) {
    std::string why;
    require(options.is_valid(&why), "grade_sizing: ", why);
    check_body(from, "source");
    check_body(to, "target");
    make_pattern(sizing);  // throws naming the parameter if the original is not a valid G

    GradingSummary s;
    s.style_tolerance = options.style_tolerance;
    s.grade = size_grade(sizing.type, from, to, options.chart);
    const std::vector<SizingParameter> specs = sizing_parameters(sizing.type);
    const std::vector<double> original = sizing_values(sizing);
    const std::vector<Rule> rules = rules_of(sizing, from, to);
    std::vector<double> values(rules.size());
    for (size_t i = 0; i < rules.size(); ++i) {
        GradedParameter p;
        p.name = specs[i].name;
        p.unit = specs[i].unit;
        p.original = original[i];
        p.unclamped = rules[i].value;
        p.graded = std::clamp(p.unclamped, specs[i].min, specs[i].max);
        p.clamped = p.graded != p.unclamped;
        p.rule = rules[i].rule;
        s.clamped += p.clamped ? 1 : 0;
        values[i] = p.graded;
        s.parameters.push_back(p);
    }
    graded = with_sizing_values(sizing, values);
    if (graded.type == GarmentType::dress && s.clamped > 0) {
        // A clamp of either side of the waist seam: the skirt follows the bodice again.
        DressSizing& d = graded.dress;
        const double r = d.skirt.r1 / d.skirt.l1;
        d.skirt.l1 = d.bodice.w2;
        d.skirt.r1 = r * d.skirt.l1;
    }
    s.termination = s.clamped > 0 ? GradingTermination::clamped : GradingTermination::graded;
    try {
        make_pattern(graded);
    } catch (const InvalidInput& first) {
        // The panels' self-intersection test runs on a polyline and can trip on a vertex that
        // lands exactly on another chord (seen on random_05's skirt graded to the male median:
        // valid at every value within 0.01 mm of the graded one). A pattern maker grades to
        // the millimetre: retry once with the values rounded to 0.01 mm.
        std::vector<double> rounded = sizing_values(graded);
        for (double& v : rounded) v = std::round(v * 1000.0) / 1000.0;
        const GarmentSizing retry = with_sizing_values(graded, rounded);
        try {
            make_pattern(retry);
            graded = retry;
            s.message = "rounded to 0.01 mm (the exact values tripped the pattern check: " + std::string(first.what()) + ")";
        } catch (const InvalidInput&) {
            s.termination = GradingTermination::invalid_pattern;
            s.message = first.what();
        }
    }
    // The recorded values are the final ones (after the waist seam's re-tie or the rounding).
    const std::vector<double> final_values = sizing_values(graded);
    for (size_t i = 0; i < s.parameters.size(); ++i) s.parameters[i].graded = final_values[i];
    s.style = style_of(sizing, graded, from, to);
    s.ease = ease_of(sizing, graded, from, to);
    for (const StyleParameter& p : s.style) s.max_style_change = std::max(s.max_style_change, p.relative_change);
    if (s.message.empty() && s.clamped > 0) {
        std::ostringstream os;
        os << "clamped to the template's range:";
        for (const GradedParameter& p : s.parameters)
            if (p.clamped) os << " " << p.name << " " << p.unclamped << " -> " << p.graded << " " << p.unit;
        s.message = os.str();
    }
    return s;
}

}  // namespace drape::garment
