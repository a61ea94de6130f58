// The implicit body of the mannequin: a torso loft, neck, head parts, limb lofts, hands,
// feet and soft-tissue ellipsoids (buttocks, breasts, pectorals, belly, deltoids), joined
// by cubic smooth unions and clipped flat at the floor. All sizes in metres; the design
// knobs interpolate between male / female and add fat / muscle.
#include "mannequin.hpp"

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::body::detail {
namespace {

using Eigen::Vector3d;
using Section = ImplicitPart::Section;

constexpr double kPi = 3.14159265358979323846;

double smooth_min(double a, double b, double k) {
    if (k <= 0.0) return std::min(a, b);
    const double h = std::max(k - std::abs(a - b), 0.0) / k;
    return std::min(a, b) - h * h * h * k * (1.0 / 6.0);
}

double smooth_max(double a, double b, double k) { return -smooth_min(-a, -b, k); }

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

Section operator+(const Section& a, const Section& b) {
    return {a.t + b.t, a.r1 + b.r1, a.r2_pos + b.r2_pos, a.r2_neg + b.r2_neg, a.c1 + b.c1,
            a.c2 + b.c2};
}
Section operator*(double s, const Section& a) {
    return {s * a.t, s * a.r1, s * a.r2_pos, s * a.r2_neg, s * a.c1, s * a.c2};
}

// Frame with `axis` first and e2 as close as possible to `hint`.
Eigen::Matrix3d frame_from(const Vector3d& axis, const Vector3d& hint) {
    const Vector3d u = axis.normalized();
    Vector3d e2 = hint - hint.dot(u) * u;
    e2.normalize();
    const Vector3d e1 = e2.cross(u).normalized();
    Eigen::Matrix3d R;
    R.row(0) = u.transpose();
    R.row(1) = e1.transpose();
    R.row(2) = e2.transpose();
    return R;
}

ImplicitPart make_loft(int bone, double blend, const Vector3d& from, const Vector3d& to,
                       const Vector3d& e2_hint, double cap0, double cap1,
                       std::vector<Section> sections, double exponent = 2.0) {
    ImplicitPart part;
    part.shape = ImplicitPart::Shape::loft;
    part.bone = bone;
    part.blend = blend;
    part.origin = from;
    part.frame = frame_from(to - from, e2_hint);
    part.length = (to - from).norm();
    part.cap0 = cap0;
    part.cap1 = cap1;
    part.exponent = exponent;
    part.sections = std::move(sections);
    part.finish();
    return part;
}

// Flips e1 so that it points along `lateral` (mirror-symmetric limbs use the same keys).
void orient_e1(ImplicitPart& part, const Vector3d& lateral) {
    if (part.frame.row(1).dot(lateral) < 0.0) part.frame.row(1) *= -1.0;
    part.finish();
}

ImplicitPart make_ellipsoid(int bone, double blend, const Vector3d& centre,
                            const Eigen::Matrix3d& frame, std::array<double, 6> radii) {
    ImplicitPart part;
    part.shape = ImplicitPart::Shape::ellipsoid;
    part.bone = bone;
    part.blend = blend;
    part.origin = centre;
    part.frame = frame;
    part.radii = radii;
    part.finish();
    return part;
}

double lerp(double a, double b, double t) { return a + (b - a) * t; }

}  // namespace

// ---- ImplicitPart ---------------------------------------------------------------------

void ImplicitPart::finish() {
    if (shape == Shape::loft) {
        const size_t n = sections.size();
        slopes.assign(n, Section{});
        for (size_t i = 0; i < n; ++i) {
            const size_t lo = i == 0 ? 0 : i - 1;
            const size_t hi = i + 1 < n ? i + 1 : n - 1;
            const double dt = sections[hi].t - sections[lo].t;
            if (dt > 0.0) slopes[i] = (1.0 / dt) * (sections[hi] + (-1.0) * sections[lo]);
            // Keep the end keyframes flat so that the caps join smoothly.
            if (i == 0 || i + 1 == n) slopes[i] = Section{};
        }
        double rmax = 0.0;
        for (const auto& s : sections) {
            rmax = std::max({rmax, s.r1 + std::abs(s.c1), s.r2_pos + std::abs(s.c2),
                             s.r2_neg + std::abs(s.c2)});
        }
        rmax *= 1.5;  // superellipse corners and spline overshoot
        const Vector3d a = origin - cap0 * frame.row(0).transpose();
        const Vector3d b = origin + (length + cap1) * frame.row(0).transpose();
        bounds = Eigen::AlignedBox3d(a.cwiseMin(b), a.cwiseMax(b));
        bounds.min().array() -= rmax;
        bounds.max().array() += rmax;
    } else {
        const double r = *std::max_element(radii.begin(), radii.end());
        bounds = Eigen::AlignedBox3d(origin - Vector3d::Constant(r), origin + Vector3d::Constant(r));
    }
}

ImplicitPart::Section ImplicitPart::section_at(double t) const {
    const size_t n = sections.size();
    if (t <= sections.front().t) return sections.front();
    if (t >= sections.back().t) return sections.back();
    size_t k = 0;
    while (k + 2 < n && sections[k + 1].t < t) ++k;
    const Section& p0 = sections[k];
    const Section& p1 = sections[k + 1];
    const double h = p1.t - p0.t;
    const double s = (t - p0.t) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    Section out = (h00 * p0) + (h10 * h) * slopes[k] + (h01 * p1) + (h11 * h) * slopes[k + 1];
    out.t = t;
    return out;
}

double ImplicitPart::value(const Vector3d& p) const {
    const Vector3d d = frame * (p - origin);
    if (shape == Shape::ellipsoid) {
        const double rx = d.x() >= 0 ? radii[0] : radii[1];
        const double ry = d.y() >= 0 ? radii[2] : radii[3];
        const double rz = d.z() >= 0 ? radii[4] : radii[5];
        const double q1 = d.x() / rx, q2 = d.y() / ry, q3 = d.z() / rz;
        const double rho = std::sqrt(q1 * q1 + q2 * q2 + q3 * q3);
        if (rho < 1e-12) return -std::min({rx, ry, rz});
        const double g1 = q1 / rx, g2 = q2 / ry, g3 = q3 / rz;
        const double g = std::sqrt(g1 * g1 + g2 * g2 + g3 * g3) / rho;
        return (rho - 1.0) / g;
    }
    const double s = d.x();
    const Section sec = section_at(s / length);
    const double y1 = d.y() - sec.c1;
    const double y2 = d.z() - sec.c2;
    const double a = sec.r1;
    const double b = y2 >= 0 ? sec.r2_pos : sec.r2_neg;
    double q3 = 0.0, rc = 1.0;
    if (s < 0.0) {
        rc = cap0;
        q3 = s / cap0;
    } else if (s > length) {
        rc = cap1;
        q3 = (s - length) / cap1;
    }
    const double q1 = y1 / a, q2 = y2 / b;
    double rho_xy, d1, d2;  // cross-section "radius" and its partials wrt q1, q2
    if (exponent == 2.0) {
        rho_xy = std::sqrt(q1 * q1 + q2 * q2);
        if (rho_xy < 1e-12) {
            d1 = d2 = 0.0;
        } else {
            d1 = q1 / rho_xy;
            d2 = q2 / rho_xy;
        }
    } else {
        const double n = exponent;
        const double a1 = std::pow(std::abs(q1), n), a2 = std::pow(std::abs(q2), n);
        rho_xy = std::pow(a1 + a2, 1.0 / n);
        if (rho_xy < 1e-12) {
            d1 = d2 = 0.0;
        } else {
            d1 = std::copysign(std::pow(std::abs(q1) / rho_xy, n - 1.0), q1);
            d2 = std::copysign(std::pow(std::abs(q2) / rho_xy, n - 1.0), q2);
        }
    }
    const double rho = std::sqrt(rho_xy * rho_xy + q3 * q3);
    if (rho < 1e-12) return -std::min(a, b);
    const double w = rho_xy / rho;
    const double g1 = w * d1 / a, g2 = w * d2 / b, g3 = q3 / (rho * rc);
    const double g = std::sqrt(g1 * g1 + g2 * g2 + g3 * g3);
    if (g < 1e-12) return -std::min(a, b);
    return (rho - 1.0) / g;
}

// ---- MannequinDesign ------------------------------------------------------------------

bool MannequinDesign::is_valid(std::string* why) const {
    auto fail = [&](const char* msg) {
        if (why) *why = msg;
        return false;
    };
    if (!std::isfinite(femininity) || !std::isfinite(fat) || !std::isfinite(muscle))
        return fail("MannequinDesign: non-finite value");
    if (femininity < 0.0 || femininity > 1.0) return fail("MannequinDesign: femininity outside [0, 1]");
    if (fat < -1.0 || fat > 1.0) return fail("MannequinDesign: fat outside [-1, 1]");
    if (muscle < -1.0 || muscle > 1.0) return fail("MannequinDesign: muscle outside [-1, 1]");
    return true;
}

// ---- MannequinImplicit ----------------------------------------------------------------

MannequinImplicit::MannequinImplicit(const MannequinDesign& design) : design_(design) {
    std::string why;
    require(design.is_valid(&why), why);
    const double fem = design.femininity;
    const double fat = design.fat;
    const double mus = design.muscle;
    auto M = [fem](double male, double female) { return lerp(male, female, fem); };
    const Vector3d X = Vector3d::UnitX(), Y = Vector3d::UnitY(), Z = Vector3d::UnitZ();
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    auto J = [this](Joint j) -> Vector3d { return joints_.row(index(j)).transpose(); };
    auto setJ = [this](Joint j, const Vector3d& p) { joints_.row(index(j)) = p.transpose(); };

    // ---- skeleton (left side; right mirrored) ----
    const double hip_x = M(0.080, 0.091) + 0.004 * fat;
    const double hip_y = 0.895;
    const double leg_angle = 7.5 * kPi / 180.0;
    const double knee_y = 0.485, ankle_y = 0.080;
    const double shoulder_x = M(0.184, 0.157) + 0.006 * mus + 0.003 * fat;
    const double shoulder_y = 1.355;
    const double arm_angle = 45.0 * kPi / 180.0;
    const double upper_len = 0.290, fore_len = 0.245;

    setJ(Joint::pelvis, {0.0, hip_y + 0.03, -0.01});
    setJ(Joint::spine, {0.0, 1.065, -0.035});
    setJ(Joint::chest, {0.0, 1.250, -0.030});
    setJ(Joint::neck, {0.0, 1.445, -0.035});
    setJ(Joint::head, {0.0, 1.555, -0.020});
    setJ(Joint::head_top, {0.0, 1.700, -0.018});  // replaced by the top vertex later
    for (int side = 0; side < 2; ++side) {
        const double s = side == 0 ? -1.0 : 1.0;  // right, left
        const bool left = side == 1;
        const Vector3d hip(s * hip_x, hip_y, 0.005);
        const Vector3d leg_dir(s * std::sin(leg_angle), -std::cos(leg_angle), 0.0);
        const Vector3d knee = hip + leg_dir * ((hip_y - knee_y) / std::cos(leg_angle)) +
                              Vector3d(0, 0, 0.005);
        const Vector3d ankle = knee + leg_dir * ((knee_y - ankle_y) / std::cos(leg_angle)) +
                               Vector3d(0, 0, -0.025);
        const Vector3d shoulder(s * shoulder_x, shoulder_y, -0.020);
        const Vector3d arm_dir(s * std::cos(arm_angle), -std::sin(arm_angle), 0.0);
        const Vector3d elbow = shoulder + upper_len * arm_dir;
        const Vector3d wrist = elbow + fore_len * arm_dir;
        const Vector3d clavicle(s * M(0.040, 0.036), 1.385, 0.010);
        setJ(left ? Joint::left_hip : Joint::right_hip, hip);
        setJ(left ? Joint::left_knee : Joint::right_knee, knee);
        setJ(left ? Joint::left_ankle : Joint::right_ankle, ankle);
        setJ(left ? Joint::left_shoulder : Joint::right_shoulder, shoulder);
        setJ(left ? Joint::left_elbow : Joint::right_elbow, elbow);
        setJ(left ? Joint::left_wrist : Joint::right_wrist, wrist);
        setJ(left ? Joint::left_clavicle : Joint::right_clavicle, clavicle);
    }

    // ---- torso: one loft along +Y, elliptic halves front / back ----
    {
        const double y0 = 0.828, y1 = 1.460;
        const double L = y1 - y0;
        auto T = [&](double y) { return (y - y0) / L; };
        // y, half-width, front, back
        std::vector<Section> keys = {
            {T(0.828), 0.045, 0.055, 0.060, 0, 0},
            {T(0.858), M(0.140, 0.158) + 0.010 * fat, 0.090, 0.092, 0, 0},
            {T(0.895), M(0.162, 0.185) + 0.016 * fat, 0.090 + 0.012 * fat, 0.095, 0, 0},
            {T(0.960), M(0.158, 0.172) + 0.022 * fat, 0.112 + 0.022 * fat, 0.090, 0, 0},
            {T(1.030), M(0.164, 0.154) + 0.030 * fat, M(0.138, 0.128) + 0.035 * fat,
             0.100 + 0.012 * fat, 0, 0},
            {T(1.120), M(0.164, 0.142) + 0.028 * fat, 0.120 + 0.022 * fat, 0.100 + 0.008 * fat, 0,
             0},
            {T(1.200), M(0.180, 0.160) + 0.016 * fat + 0.004 * mus, 0.118 + 0.010 * fat,
             0.120 + 0.004 * fat, 0, 0},
            {T(1.280), M(0.198, 0.172) + 0.010 * mus + 0.008 * fat, 0.114, 0.132 + 0.004 * mus, 0,
             0},
            {T(1.340), M(0.196, 0.164) + 0.012 * mus + 0.006 * fat, 0.095, 0.115 + 0.004 * mus, 0,
             0},
            {T(1.385), M(0.172, 0.152) + 0.010 * mus, 0.075, 0.100 + 0.004 * mus, 0, 0},
            {T(1.425), 0.112 + 0.012 * mus + 0.005 * fat, 0.050, 0.085 + 0.006 * mus, 0, 0},
            {T(1.460), 0.068 + 0.008 * fat, 0.035, 0.070, 0, 0},
        };
        ImplicitPart torso = make_loft(-1, 0.0, {0, y0, 0}, {0, y1, 0}, Z, 0.028, 0.015, keys);
        orient_e1(torso, X);
        parts_.push_back(torso);
    }
    // ---- soft tissue of the trunk ----
    {
        // Belly: buried in the torso for fat <= 0, a soft paunch for fat > 0.
        parts_.push_back(make_ellipsoid(
            index(Joint::spine), 0.05, {0.0, 1.00, 0.02}, I,
            {0.13 + 0.02 * fat, 0.13 + 0.02 * fat, 0.11, 0.10, 0.062 + 0.075 * fat, 0.05}));
        // Pubic mound: fills the groove between the fronts of the thighs.
        parts_.push_back(make_ellipsoid(index(Joint::pelvis), 0.030, {0.0, 0.848, 0.040}, I,
                                        {0.060, 0.060, 0.045, 0.030, 0.045 + 0.008 * fat, 0.03}));
        for (int side = 0; side < 2; ++side) {
            const double s = side == 0 ? -1.0 : 1.0;
            // Buttock cheeks: their smooth union leaves the intergluteal cleft.
            const double glute = M(0.074, 0.092) + 0.012 * fat + 0.004 * mus;
            parts_.push_back(make_ellipsoid(index(Joint::pelvis), 0.050,
                                            {s * 0.072, 0.868, -0.048}, I,
                                            s > 0 ? std::array<double, 6>{0.100, 0.070, 0.100,
                                                                          0.072, 0.05, glute}
                                                  : std::array<double, 6>{0.070, 0.100, 0.100,
                                                                          0.072, 0.05, glute}));
            // Pectorals (male, muscle) and breasts (female, fat).
            const double pec = std::clamp(1.0 - fem + 0.8 * mus, 0.0, 2.0);
            parts_.push_back(make_ellipsoid(index(Joint::chest), 0.030,
                                            {s * 0.072, 1.280, 0.050}, I,
                                            {0.080, 0.080, 0.050, 0.048, 0.040 + 0.022 * pec,
                                             0.04}));
            const double bust = std::clamp(fem + 0.25 * fat, 0.0, 1.3);
            // Breasts: a long upper slope, a fuller lower pole, pointing slightly outwards.
            const double rb = 0.052 + 0.024 * bust;
            const Eigen::Matrix3d outwards =
                Eigen::AngleAxisd(s * 0.22, Y).toRotationMatrix().transpose();
            parts_.push_back(make_ellipsoid(index(Joint::chest), 0.045,
                                            {s * 0.090, 1.240 - 0.022 * bust, 0.036 + 0.030 * bust},
                                            outwards, {rb, rb, 0.072 + 0.02 * bust, 0.046 + 0.018 * bust,
                                                       0.040 + 0.050 * bust, 0.04}));
        }
    }
    // ---- neck and head ----
    {
        const double neck_r = M(0.061, 0.052) + 0.008 * fat + 0.004 * mus;
        ImplicitPart neck = make_loft(index(Joint::neck), 0.040, {0, 1.405, -0.030},
                                      {0, 1.575, -0.018}, Z, 0.02, 0.02,
                                      {{0.0, neck_r + 0.006, neck_r, neck_r + 0.004, 0, 0},
                                       {0.5, neck_r, neck_r, neck_r, 0, 0},
                                       {1.0, neck_r, neck_r, neck_r, 0, 0}});
        orient_e1(neck, X);
        parts_.push_back(neck);
        const int head = index(Joint::head);
        const Vector3d cranium(0.0, 1.612, -0.018);
        anatomy_.head_centre = cranium;
        parts_.push_back(make_ellipsoid(head, 0.025, cranium, I,
                                        {0.076, 0.076, 0.088, 0.070, 0.090, 0.100}));
        const double jaw = M(0.064, 0.058) + 0.006 * fat;
        parts_.push_back(make_ellipsoid(head, 0.030, {0.0, 1.556, 0.012}, I,
                                        {jaw, jaw, 0.055, 0.074, 0.082, 0.05}));
        parts_.push_back(make_ellipsoid(head, 0.035, {0.0, 1.494, 0.058}, I,
                                        {0.024, 0.024, 0.018, 0.016, 0.020, 0.02}));
        parts_.push_back(make_ellipsoid(head, 0.030, {0.0, 1.628, 0.052}, I,
                                        {0.055, 0.055, 0.016, 0.012, 0.028, 0.02}));
        // Nose: a tapered ridge from the bridge to the tip.
        ImplicitPart nose = make_loft(head, 0.012, {0.0, 1.607, 0.068}, {0.0, 1.566, 0.100}, Z,
                                      0.01, 0.011,
                                      {{0.0, 0.0075, 0.007, 0.007, 0, 0},
                                       {0.7, 0.0105, 0.010, 0.010, 0, 0},
                                       {1.0, 0.0130, 0.011, 0.011, 0, 0}});
        orient_e1(nose, X);
        parts_.push_back(nose);
        for (int side = 0; side < 2; ++side) {
            const double s = side == 0 ? -1.0 : 1.0;
            // Eye sockets under the brow.
            ImplicitPart socket = make_ellipsoid(head, 0.012, {s * 0.033, 1.604, 0.074}, I,
                                                 {0.017, 0.017, 0.011, 0.010, 0.016, 0.016});
            socket.carve = true;
            parts_.push_back(socket);
            const Eigen::Matrix3d ear =
                Eigen::AngleAxisd(s * 0.25, Y).toRotationMatrix().transpose();
            parts_.push_back(make_ellipsoid(head, 0.008, {s * 0.073, 1.585, -0.014}, ear,
                                            {0.012, 0.012, 0.031, 0.027, 0.019, 0.019}));
        }
    }
    // ---- arms ----
    for (int side = 0; side < 2; ++side) {
        const bool left = side == 1;
        const double s = left ? 1.0 : -1.0;
        const Vector3d shoulder = J(left ? Joint::left_shoulder : Joint::right_shoulder);
        const Vector3d elbow = J(left ? Joint::left_elbow : Joint::right_elbow);
        const Vector3d wrist = J(left ? Joint::left_wrist : Joint::right_wrist);
        const Vector3d u = (elbow - shoulder).normalized();
        const Vector3d up = Vector3d(s * std::sin(arm_angle), std::cos(arm_angle), 0.0);
        const double g = M(1.0, 0.92);
        const double ft = 0.008 * fat;
        ImplicitPart upper = make_loft(
            index(left ? Joint::left_shoulder : Joint::right_shoulder), 0.030, shoulder, elbow,
            Z, 0.045, 0.03,
            {{0.00, 0.052 * g + ft, 0.052 * g + ft, 0.052 * g + ft, 0, 0},
             {0.35, 0.047 * g + ft, (0.049 + 0.004 * mus) * g + ft, 0.048 * g + ft, 0, 0},
             {0.60, 0.044 * g + ft, (0.049 + 0.008 * mus) * g + ft,
              (0.045 + 0.005 * mus) * g + ft, 0, 0},
             {0.90, 0.041 * g + 0.5 * ft, 0.040 * g, 0.042 * g + 0.5 * ft, 0, 0},
             {1.00, 0.040 * g, 0.037 * g, 0.040 * g, 0, 0}});
        orient_e1(upper, up);
        parts_.push_back(upper);
        const double delt = M(1.0, 0.93) * (1.0 + 0.12 * mus) + 0.04 * fat;
        parts_.push_back(make_ellipsoid(
            upper.bone, 0.022, shoulder + 0.030 * u + 0.014 * up + Vector3d(0, 0, -0.002),
            upper.frame,
            {0.085 * delt, 0.075 * delt, 0.046 * delt, 0.030, 0.052 * delt, 0.050 * delt}));
        ImplicitPart fore = make_loft(
            index(left ? Joint::left_elbow : Joint::right_elbow), 0.020, elbow, wrist, Z, 0.03,
            0.02,
            {{0.00, 0.040 * g, 0.040 * g, 0.042 * g, 0, 0},
             {0.22, 0.039 * g + 0.5 * ft, (0.045 + 0.003 * mus) * g + ft,
              (0.043 + 0.003 * mus) * g + ft, 0, 0},
             {0.55, 0.032 * g + 0.4 * ft, 0.036 * g + 0.5 * ft, 0.034 * g + 0.5 * ft, 0, 0},
             {0.90, 0.021 * g, 0.030 * g, 0.028 * g, 0, 0},
             {1.00, 0.020 * g, 0.030 * g, 0.027 * g, 0, 0}});
        orient_e1(fore, up);
        parts_.push_back(fore);
        // Hand: a palm in line with the forearm and a finger block curled 25 degrees towards
        // the palm (mitten), plus a thumb along the front edge.
        const double hg = M(1.0, 0.92);
        const int wrist_bone = index(left ? Joint::left_wrist : Joint::right_wrist);
        const Vector3d knuckles = wrist + 0.100 * hg * u;
        ImplicitPart hand = make_loft(wrist_bone, 0.016, wrist, knuckles, Z, 0.02, 0.016,
                                      {{0.00, 0.021 * hg, 0.030 * hg, 0.027 * hg, 0, 0},
                                       {0.40, 0.0195 * hg, 0.040 * hg, 0.037 * hg, -0.002, 0},
                                       {1.00, 0.0170 * hg, 0.041 * hg, 0.038 * hg, -0.001, 0}},
                                      2.6);
        orient_e1(hand, up);
        parts_.push_back(hand);
        const Vector3d palm = -hand.frame.row(1).transpose();  // palm side faces the body
        const Vector3d front = hand.frame.row(2).transpose();
        const double curl = 25.0 * kPi / 180.0;
        const Vector3d finger_dir = std::cos(curl) * u + std::sin(curl) * palm;
        const Vector3d tip = knuckles + 0.088 * hg * finger_dir;
        anatomy_.hand_tip[side] = tip;
        ImplicitPart fingers = make_loft(wrist_bone, 0.020, knuckles - 0.015 * finger_dir, tip, Z,
                                         0.015, 0.012,
                                         {{0.00, 0.0165 * hg, 0.040 * hg, 0.037 * hg, 0, 0},
                                          {0.55, 0.0135 * hg, 0.036 * hg, 0.034 * hg, 0, 0},
                                          {1.00, 0.0100 * hg, 0.028 * hg, 0.026 * hg, 0, 0}},
                                         2.6);
        orient_e1(fingers, up);
        parts_.push_back(fingers);
        const Vector3d tb = wrist + 0.030 * u + 0.024 * hg * front + 0.003 * palm;
        const Vector3d tt = wrist + 0.094 * u + 0.044 * hg * front + 0.012 * palm;
        ImplicitPart thumb = make_loft(
            hand.bone, 0.014, tb, tt, palm, 0.012, 0.010,
            {{0.0, 0.013 * hg, 0.012 * hg, 0.012 * hg, 0, 0},
             {0.6, 0.010 * hg, 0.0095 * hg, 0.0095 * hg, 0, 0},
             {1.0, 0.0085 * hg, 0.008 * hg, 0.008 * hg, 0, 0}});
        parts_.push_back(thumb);
    }
    // ---- legs ----
    for (int side = 0; side < 2; ++side) {
        const bool left = side == 1;
        const double s = left ? 1.0 : -1.0;
        const Vector3d hip = J(left ? Joint::left_hip : Joint::right_hip);
        const Vector3d knee = J(left ? Joint::left_knee : Joint::right_knee);
        const Vector3d ankle = J(left ? Joint::left_ankle : Joint::right_ankle);
        const Vector3d lateral(s, 0, 0);
        const double tf = 0.010 * fat;
        const double tw = M(0.0, 0.006);
        ImplicitPart thigh = make_loft(
            index(left ? Joint::left_hip : Joint::right_hip), 0.050, hip, knee, Z, 0.05, 0.04,
            {{0.00, 0.086 + tw + tf, 0.080 + tf, 0.090 + tf, 0.0, 0},
             {0.30, 0.088 + tw + tf, 0.098 + 0.4 * tw + tf + 0.004 * mus, 0.102 + tf, 0.018, 0},
             {0.55, 0.077 + 0.5 * tw + tf, 0.086 + 0.6 * tf + 0.005 * mus, 0.083 + 0.6 * tf,
              0.012, 0},
             {0.82, 0.063 + 0.4 * tf, 0.066 + 0.4 * tf + 0.003 * mus, 0.062 + 0.4 * tf, 0.004,
              0},
             {1.00, 0.056, 0.056, 0.055, 0.0, 0}});
        orient_e1(thigh, lateral);
        parts_.push_back(thigh);
        parts_.push_back(make_ellipsoid(thigh.bone, 0.025, knee + Vector3d(0, 0.005, 0.038),
                                        I, {0.030, 0.030, 0.036, 0.030, 0.022, 0.02}));
        const double cm = 0.006 * mus + 0.005 * fat;
        ImplicitPart shin = make_loft(
            index(left ? Joint::left_knee : Joint::right_knee), 0.022, knee, ankle, Z, 0.04,
            0.03,
            {{0.00, 0.055, 0.054, 0.056, 0, 0},
             {0.13, 0.052 + 0.5 * cm, 0.048, 0.066 + cm, 0.0, -0.004},
             {0.32, 0.056 + cm, 0.047 + 0.3 * cm, 0.082 + 1.5 * cm, -0.003, -0.008},
             {0.62, 0.041 + 0.5 * cm, 0.039, 0.054 + cm, -0.002, -0.008},
             {0.87, 0.031, 0.032, 0.035, 0, -0.002},
             {1.00, 0.031, 0.034, 0.034, 0, 0}});
        orient_e1(shin, lateral);
        parts_.push_back(shin);
        const Vector3d e1 = shin.frame.row(1).transpose();
        parts_.push_back(make_ellipsoid(shin.bone, 0.010, ankle + 0.024 * e1 - 0.008 * Y, I,
                                        {0.014, 0.014, 0.02, 0.02, 0.016, 0.016}));
        parts_.push_back(make_ellipsoid(shin.bone, 0.010, ankle - 0.022 * e1 + 0.004 * Y, I,
                                        {0.014, 0.014, 0.02, 0.02, 0.016, 0.016}));
        // Foot: heel to toe tip, turned out 8 degrees; the floor clip flattens the sole.
        const double out = 8.0 * kPi / 180.0;
        const Vector3d fwd(s * std::sin(out), 0.0, std::cos(out));
        const Vector3d heel = ankle + Vector3d(0, -0.045, 0) - 0.035 * fwd;
        const Vector3d toe_tip = ankle + Vector3d(0, -0.062, 0) + 0.175 * fwd;
        const double fw = M(1.0, 0.93);
        ImplicitPart foot = make_loft(
            index(left ? Joint::left_ankle : Joint::right_ankle), 0.030, heel, toe_tip, Y, 0.03,
            0.02,
            {{0.00, 0.031 * fw, 0.040, 0.048, 0, 0},
             {0.22, 0.035 * fw, 0.058, 0.046, 0, 0},
             {0.45, 0.042 * fw, 0.048, 0.042, 0.002, 0},
             {0.72, 0.049 * fw, 0.029, 0.036, 0.004, 0},
             {0.90, 0.045 * fw, 0.021, 0.032, 0.002, 0},
             {1.00, 0.040 * fw, 0.017, 0.030, 0, 0}},
            2.3);
        orient_e1(foot, lateral);
        parts_.push_back(foot);
        const Vector3d ball = heel + 0.72 * (toe_tip - heel) + Vector3d(0, 0.004, 0);
        setJ(left ? Joint::left_toe : Joint::right_toe, ball);
    }

    anatomy_.navel_y = J(Joint::spine).y() - 0.035;
    anatomy_.bust_y = 1.240 - 0.022 * std::clamp(fem + 0.25 * fat, 0.0, 1.3);
    anatomy_.furrow_y = 0.785;
    anatomy_.buttock_y = 0.875;
    anatomy_.calf_y = J(Joint::right_knee).y() - 0.32 * (J(Joint::right_knee).y() -
                                                        J(Joint::right_ankle).y());

    bounds_.setEmpty();
    for (auto& part : parts_) {
        bounds_.extend(part.bounds);
        part.bounds.min().array() -= kFarValue;
        part.bounds.max().array() += kFarValue;
    }
    bounds_.min().y() = std::max(bounds_.min().y(), -0.02);
}

double MannequinImplicit::value(const Vector3d& p) const {
    double f = std::numeric_limits<double>::infinity();
    for (const auto& part : parts_) {
        if (!part.bounds.contains(p)) continue;
        f = part.carve ? smooth_max(f, -part.value(p), part.blend)
                       : smooth_min(f, part.value(p), part.blend);
    }
    if (!std::isfinite(f)) f = kFarValue;
    return smooth_max(f, -p.y(), 0.010);
}

Vector3d MannequinImplicit::gradient(const Vector3d& p) const {
    const double h = 1e-5;
    Vector3d g;
    for (int i = 0; i < 3; ++i) {
        Vector3d a = p, b = p;
        a[i] += h;
        b[i] -= h;
        g[i] = (value(a) - value(b)) / (2 * h);
    }
    return g;
}

int MannequinImplicit::torso_bone(const Vector3d& p) const {
    const double y = p.y();
    const double pelvis_top = 0.5 * (joints_(index(Joint::pelvis), 1) + joints_(index(Joint::spine), 1));
    const double spine_top = 0.5 * (joints_(index(Joint::spine), 1) + joints_(index(Joint::chest), 1));
    if (y < pelvis_top) return index(Joint::pelvis);
    if (y < spine_top) return index(Joint::spine);
    if (y > 1.33 && std::abs(p.x()) > 0.075)
        return p.x() > 0 ? index(Joint::left_clavicle) : index(Joint::right_clavicle);
    if (y > 1.43) return index(Joint::neck);
    return index(Joint::chest);
}

int MannequinImplicit::bone_at(const Vector3d& p) const {
    double best = std::numeric_limits<double>::infinity();
    int bone = index(Joint::pelvis);
    for (const auto& part : parts_) {
        if (part.carve || !part.bounds.contains(p)) continue;
        const double v = part.value(p);
        if (v < best) {
            best = v;
            bone = part.bone < 0 ? torso_bone(p) : part.bone;
        }
    }
    return bone;
}

double MannequinImplicit::relative_edge_length(const Vector3d& p) const {
    double r = 1.0;
    // Face and ears.
    {
        const Vector3d a = anatomy_.head_centre, b(0.0, 1.50, 0.03);
        const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        const double dh = (p - (a + t * (b - a))).norm();
        r = std::min(r, lerp(0.55, 1.0, smoothstep(0.10, 0.15, dh)));
    }
    // Hands: beyond the wrist.
    for (int side = 0; side < 2; ++side) {
        const Vector3d wrist = joints_.row(side == 0 ? index(Joint::right_wrist)
                                                     : index(Joint::left_wrist)).transpose();
        const Vector3d dir = (anatomy_.hand_tip[side] - wrist).normalized();
        const double along = (p - wrist).dot(dir);
        const double radial = ((p - wrist) - along * dir).norm();
        if (radial < 0.09) r = std::min(r, lerp(1.0, 0.62, smoothstep(-0.05, 0.0, along)));
    }
    // Feet.
    r = std::min(r, lerp(0.75, 1.0, smoothstep(0.06, 0.12, p.y())));
    return r;
}

}  // namespace drape::body::detail
