// The built-in body model: the procedural mannequin (mannequin.hpp) plus a shape basis in
// which each column is one interpretable deformation (default_model.hpp, Basis), so that
// every tailor's measurement is (almost) linear in the coefficients.
#include "default_model.hpp"

#include "mannequin.hpp"

#include <drape/body/measurements.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace drape::body {

namespace detail {

namespace {

double smoothstep(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// 0 below `lo`, rising to 1 at `peak`, falling to 0 at `hi` (C1, piecewise smoothstep).
double bump(double y, double lo, double peak, double hi) {
    if (y <= peak) return lo < peak ? smoothstep((y - lo) / (peak - lo)) : 1.0;
    return hi > peak ? smoothstep((hi - y) / (hi - peak)) : 1.0;
}

double ramp(double y, double lo, double hi) { return std::clamp((y - lo) / (hi - lo), 0.0, 1.0); }

struct Parts {
    Eigen::VectorXd arm_r, arm_l, leg_r, leg_l, head, clavicle;
    Eigen::VectorXd trunk;  // 1 - arms - legs - head
};

Parts part_weights(const Eigen::SparseMatrix<double>& W) {
    const Eigen::Index n = W.rows();
    Parts p;
    auto sum = [&](std::initializer_list<Joint> joints) {
        Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
        for (Joint j : joints) s += Eigen::VectorXd(W.col(index(j)));
        return s;
    };
    p.arm_r = sum({Joint::right_shoulder, Joint::right_elbow, Joint::right_wrist});
    p.arm_l = sum({Joint::left_shoulder, Joint::left_elbow, Joint::left_wrist});
    p.leg_r = sum({Joint::right_hip, Joint::right_knee, Joint::right_ankle, Joint::right_toe});
    p.leg_l = sum({Joint::left_hip, Joint::left_knee, Joint::left_ankle, Joint::left_toe});
    p.head = sum({Joint::head, Joint::head_top});
    p.clavicle = sum({Joint::right_clavicle, Joint::left_clavicle});
    p.trunk = (Eigen::VectorXd::Ones(n) - p.arm_r - p.arm_l - p.leg_r - p.leg_l - p.head)
                  .cwiseMax(0.0);
    return p;
}

// Horizontal centre of the trunk as a function of height, tabulated from the template.
struct TrunkAxis {
    double y0 = 0, dy = 0.01;
    std::vector<Eigen::Vector2d> centre;  // (x, z) per bin

    Eigen::Vector2d at(double y) const {
        const double t = std::clamp((y - y0) / dy, 0.0, static_cast<double>(centre.size() - 1));
        const size_t i = std::min(static_cast<size_t>(t), centre.size() - 2);
        const double f = t - static_cast<double>(i);
        return (1 - f) * centre[i] + f * centre[i + 1];
    }
};

TrunkAxis trunk_axis(const Eigen::MatrixXd& V, const Eigen::VectorXd& trunk) {
    TrunkAxis axis;
    const double ymin = V.col(1).minCoeff(), ymax = V.col(1).maxCoeff();
    axis.y0 = ymin;
    const int bins = static_cast<int>((ymax - ymin) / axis.dy) + 2;
    std::vector<Eigen::Vector2d> lo(bins, Eigen::Vector2d::Constant(1e9)),
        hi(bins, Eigen::Vector2d::Constant(-1e9));
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
        if (trunk[v] < 0.5) continue;
        const int b = std::clamp(static_cast<int>((V(v, 1) - ymin) / axis.dy + 0.5), 0, bins - 1);
        const Eigen::Vector2d xz(V(v, 0), V(v, 2));
        lo[b] = lo[b].cwiseMin(xz);
        hi[b] = hi[b].cwiseMax(xz);
    }
    axis.centre.assign(bins, Eigen::Vector2d::Zero());
    // Fill bins without trunk vertices from their nearest filled neighbour.
    int last = -1;
    for (int b = 0; b < bins; ++b) {
        if (lo[b].x() <= hi[b].x()) {
            axis.centre[b] = 0.5 * (lo[b] + hi[b]);
            axis.centre[b].x() = 0;  // the body is symmetric about x = 0
            if (last < 0)
                for (int k = 0; k < b; ++k) axis.centre[k] = axis.centre[b];
            last = b;
        } else if (last >= 0) {
            axis.centre[b] = axis.centre[last];
        }
    }
    return axis;
}

// Component of (p - a) perpendicular to the line through a with direction d (unit).
Eigen::Vector3d radial(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& d) {
    const Eigen::Vector3d r = p - a;
    return r - r.dot(d) * d;
}

}  // namespace

BodyModel build_default_model() {
    const MannequinMesh base = generate_mannequin(MannequinDesign{});
    const Eigen::MatrixXd& V = base.V;
    const Eigen::Index n = V.rows();

    BodyModel model;
    model.name = "drape-mannequin-1";
    model.template_vertices = V;
    model.faces = base.F;
    model.template_joints = base.joints;
    model.joint_regressor = base.joint_regressor;
    model.skin_weights = base.skin_weights;
    model.landmarks = base.landmarks;
    model.prior = ShapePrior::ansur2();
    // Whole-body density: Siri's two-compartment model, D = 4.95 / (f + 4.5) g/cm^3, gives
    // 1.04 at f = 25 % body fat (typical of the ANSUR II population) before lung air;
    // residual lung volume lowers it by ~1-2 % (Siri 1961; Brozek et al. 1963).
    model.density_kg_m3 = 1030.0;

    const Parts parts = part_weights(base.skin_weights);
    const TrunkAxis axis = trunk_axis(V, parts.trunk);
    const Landmarks& L = base.landmarks;
    auto J = [&](Joint j) -> Eigen::Vector3d { return base.joints.row(index(j)).transpose(); };
    auto y_of = [&](int vtx) { return V(vtx, 1); };
    const double y_crotch = y_of(L.crotch), y_acromion = y_of(L.right_acromion);
    const double y_top = y_of(L.head_top);
    const double y_chest = 0.5 * (y_of(L.right_bust) + y_of(L.left_bust));
    const double y_waist = y_of(L.navel), y_hip = y_of(L.buttock);
    const double y_thigh = y_of(L.right_thigh), y_calf = y_of(L.right_calf);
    const double y_knee = J(Joint::right_knee).y(), y_ankle = J(Joint::right_ankle).y();
    const double y_shoulder = J(Joint::right_shoulder).y();

    Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(3 * n, kBasisCount);
    auto set = [&](Basis b, Eigen::Index v, const Eigen::Vector3d& d) {
        Z.block<3, 1>(3 * v, static_cast<int>(b)) = d;
    };
    auto flat = [&](const Eigen::MatrixXd& D, Basis b, double scale) {
        for (Eigen::Index v = 0; v < n; ++v) set(b, v, scale * D.row(v).transpose());
    };
    // Shape directions of the implicit body design (same topology by construction).
    flat(conform_mannequin(base, {1.0, 0.0, 0.0}) - conform_mannequin(base, {0.0, 0.0, 0.0}),
         Basis::femininity, 1.0);
    flat(conform_mannequin(base, {0.5, 1.0, 0.0}) - conform_mannequin(base, {0.5, -1.0, 0.0}),
         Basis::fat, 0.5);
    flat(conform_mannequin(base, {0.5, 0.0, 1.0}) - conform_mannequin(base, {0.5, 0.0, -1.0}),
         Basis::muscle, 0.5);

    // Vertical stretch functions: arms follow their shoulder joint rigidly.
    auto vertical = [&](Basis b, auto&& f) {
        const double at_shoulder = f(y_shoulder);
        for (Eigen::Index v = 0; v < n; ++v) {
            const double arm = parts.arm_r[v] + parts.arm_l[v];
            set(b, v, Eigen::Vector3d(0, (1 - arm) * f(V(v, 1)) + arm * at_shoulder, 0));
        }
    };
    vertical(Basis::crotch_height, [&](double y) { return ramp(y, 0.0, y_crotch); });
    vertical(Basis::torso_length, [&](double y) { return ramp(y, y_crotch, y_acromion); });
    vertical(Basis::head_neck, [&](double y) { return ramp(y, y_acromion, y_top); });

    const Eigen::Vector3d sh_r = J(Joint::right_shoulder), sh_l = J(Joint::left_shoulder);
    for (Eigen::Index v = 0; v < n; ++v) {
        const Eigen::Vector3d p = V.row(v).transpose();
        set(Basis::arm_scale, v, parts.arm_r[v] * (p - sh_r) + parts.arm_l[v] * (p - sh_l));
        const double side = p.x() >= 0 ? 1.0 : -1.0;
        const double lateral = parts.arm_r[v] + parts.arm_l[v] + 0.5 * parts.clavicle[v];
        set(Basis::shoulder_breadth, v, Eigen::Vector3d(side * lateral, 0, 0));
        set(Basis::head_scale, v, parts.head[v] * (p - J(Joint::head)));
    }

    // Girths: radial scaling of horizontal trunk sections about the trunk axis, and of
    // leg sections about the bone axis, each confined to a smooth band around its landmark.
    const Eigen::Vector3d femur_r = (J(Joint::right_knee) - J(Joint::right_hip)).normalized();
    const Eigen::Vector3d femur_l = (J(Joint::left_knee) - J(Joint::left_hip)).normalized();
    const Eigen::Vector3d tibia_r = (J(Joint::right_ankle) - J(Joint::right_knee)).normalized();
    const Eigen::Vector3d tibia_l = (J(Joint::left_ankle) - J(Joint::left_knee)).normalized();
    for (Eigen::Index v = 0; v < n; ++v) {
        const Eigen::Vector3d p = V.row(v).transpose();
        const double y = p.y();
        const Eigen::Vector2d c = axis.at(y);
        const Eigen::Vector3d trunk_radial(p.x() - c.x(), 0, p.z() - c.y());
        const bool right = p.x() < 0;
        const double leg = right ? parts.leg_r[v] : parts.leg_l[v];
        const Eigen::Vector3d thigh_radial =
            right ? radial(p, J(Joint::right_hip), femur_r) : radial(p, J(Joint::left_hip), femur_l);
        const Eigen::Vector3d calf_radial =
            right ? radial(p, J(Joint::right_knee), tibia_r) : radial(p, J(Joint::left_knee), tibia_l);
        const double trunk = parts.trunk[v];
        set(Basis::chest_girth, v, trunk * bump(y, y_waist, y_chest, y_acromion) * trunk_radial);
        set(Basis::waist_girth, v, trunk * bump(y, y_hip, y_waist, y_chest) * trunk_radial);
        set(Basis::hip_girth, v,
            bump(y, y_thigh, y_hip, y_waist) * (trunk * trunk_radial + leg * thigh_radial));
        set(Basis::thigh_girth, v, leg * bump(y, y_knee, y_thigh, y_hip) * thigh_radial);
        set(Basis::calf_girth, v, leg * bump(y, y_ankle, y_calf, y_knee) * calf_radial);
    }
    model.shape_basis = std::move(Z);
    model.shape_names = {"femininity",   "fat",         "muscle",      "crotch_height",
                         "torso_length", "head_neck",   "arm_scale",   "shoulder_breadth",
                         "chest_girth",  "waist_girth", "hip_girth",   "thigh_girth",
                         "calf_girth",   "head_scale"};

    // The semantic map, linear by construction: evaluate the linear rule at the reference
    // and at unit steps of each semantic value.
    const BodyMeasurements m0 = measure_body(model, V);
    Eigen::Matrix<double, 1 + kSemanticCount, 1> ref;
    ref << 0.5, m0.height_m, m0.weight_kg, 0.5, m0.chest_girth_m, m0.waist_girth_m,
        m0.hip_girth_m, m0.thigh_girth_m, m0.calf_girth_m, m0.shoulder_height_m, m0.crotch_height_m;
    model.semantic_map.reference = ref;
    model.semantic_map.A.resize(kBasisCount, 1 + kSemanticCount);
    model.semantic_map.b = Eigen::VectorXd::Zero(kBasisCount);
    model.semantic_map.refinable = Eigen::VectorXd::Zero(kBasisCount);
    for (Basis b : {Basis::crotch_height, Basis::torso_length, Basis::head_neck, Basis::chest_girth,
                    Basis::waist_girth, Basis::hip_girth, Basis::thigh_girth, Basis::calf_girth})
        model.semantic_map.refinable[static_cast<int>(b)] = 1.0;
    model.semantic_map.refinable[static_cast<int>(Basis::fat)] = 2.0;
    // A needs measurement Jacobians, which need the basis in place: fill it column by column.
    model.semantic_map.A.setZero();
    const LinearRule rule = linear_rule(model);
    const Eigen::VectorXd c_ref = default_linear_coefficients(rule, ref);
    model.semantic_map.b = c_ref;
    for (int k = 0; k < 1 + kSemanticCount; ++k) {
        Eigen::Matrix<double, 1 + kSemanticCount, 1> v = ref;
        v[k] += 1.0;
        model.semantic_map.A.col(k) = default_linear_coefficients(rule, v) - c_ref;
    }
    std::string why;
    if (!model.is_valid(&why)) throw std::logic_error("built-in body model is invalid: " + why);
    return model;
}

// Measurement Jacobian of the matched measurements (and weight) w.r.t. every column at the
// template: the mesh is linear in c, the measurements nearly so.
LinearRule linear_rule(const BodyModel& model) {
    const Eigen::MatrixXd& V0 = model.template_vertices;
    const auto measure = [&](const Eigen::MatrixXd& X) {
        const BodyMeasurements m = measure_body(model, X);
        Eigen::Matrix<double, kMatchedCount + 1, 1> out;
        out << m.height_m, m.shoulder_height_m, m.crotch_height_m, m.chest_girth_m,
            m.waist_girth_m, m.hip_girth_m, m.thigh_girth_m, m.calf_girth_m, m.weight_kg;
        return out;
    };
    LinearRule rule;
    rule.m0 = measure(V0);
    rule.jacobian.resize(kMatchedCount + 1, model.shape_count());
    const double h = 1e-3;
    for (int k = 0; k < model.shape_count(); ++k) {
        const Eigen::VectorXd col = model.shape_basis.col(k);
        const Eigen::MatrixXd D =
            Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(col.data(), V0.rows(), 3);
        rule.jacobian.col(k) = (measure(V0 + h * D) - measure(V0 - h * D)) / (2 * h);
    }
    return rule;
}

Eigen::VectorXd default_linear_coefficients(const LinearRule& rule,
                                            const Eigen::Matrix<double, 1 + kSemanticCount, 1>& v) {
    const Eigen::MatrixXd& jac = rule.jacobian;
    const auto& m0 = rule.m0;
    const double female = v[0], height = v[1], weight = v[2], muscle = v[3];
    const double ref_height = m0[0];
    Eigen::VectorXd c = Eigen::VectorXd::Zero(kBasisCount);
    c[static_cast<int>(Basis::femininity)] = female - 0.5;
    c[static_cast<int>(Basis::muscle)] = 2.0 * (muscle - 0.5);
    // Soft tissue from the linearised body-mass index: 0 at 24 kg/m^2, +1 (the design's
    // fullest) at 40 kg/m^2, so that ANSUR II's range (BMI ~17-45) stays near [-1, 1].
    const double bmi_lin = weight / (ref_height * ref_height) -
                           2.0 * 70.0 / (ref_height * ref_height * ref_height) * (height - ref_height);
    c[static_cast<int>(Basis::fat)] = (bmi_lin - 24.0) / 16.0;
    // Arms and shoulders scale with stature (arm span ~ stature; ANSUR II biacromial
    // breadth ~ 0.23 x stature).
    c[static_cast<int>(Basis::arm_scale)] = height / ref_height - 1.0;
    c[static_cast<int>(Basis::shoulder_breadth)] = 0.5 * 0.23 * (height - ref_height);
    c[static_cast<int>(Basis::head_scale)] = 0.5 * (height / ref_height - 1.0);
    // The eight geometric columns solve for the requested measurements given the rest.
    const int geo[kMatchedCount] = {
        static_cast<int>(Basis::head_neck),     static_cast<int>(Basis::torso_length),
        static_cast<int>(Basis::crotch_height), static_cast<int>(Basis::chest_girth),
        static_cast<int>(Basis::waist_girth),   static_cast<int>(Basis::hip_girth),
        static_cast<int>(Basis::thigh_girth),   static_cast<int>(Basis::calf_girth)};
    Eigen::Matrix<double, kMatchedCount, 1> target;
    target << height, v[1 + static_cast<int>(Semantic::shoulder_height_m)],
        v[1 + static_cast<int>(Semantic::crotch_height_m)],
        v[1 + static_cast<int>(Semantic::chest_girth_m)], v[1 + static_cast<int>(Semantic::waist_girth_m)],
        v[1 + static_cast<int>(Semantic::hip_girth_m)], v[1 + static_cast<int>(Semantic::thigh_girth_m)],
        v[1 + static_cast<int>(Semantic::calf_girth_m)];
    Eigen::Matrix<double, kMatchedCount, 1> rhs = target - m0.head<kMatchedCount>();
    rhs -= jac.topRows<kMatchedCount>() * c;
    Eigen::Matrix<double, kMatchedCount, kMatchedCount> Jg;
    for (int i = 0; i < kMatchedCount; ++i) Jg.col(i) = jac.col(geo[i]).head<kMatchedCount>();
    const Eigen::Matrix<double, kMatchedCount, 1> cg = Jg.colPivHouseholderQr().solve(rhs);
    for (int i = 0; i < kMatchedCount; ++i) c[geo[i]] = cg[i];
    return c;
}

}  // namespace detail

const BodyModel& BodyModel::default_model() {
    static const BodyModel model = detail::build_default_model();
    return model;
}

}  // namespace drape::body
