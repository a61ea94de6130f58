#include <drape/body/shape_body.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <sstream>
#include <vector>

namespace drape::body {

namespace {

constexpr int kMatched = 8;  // height, shoulder, crotch, chest, waist, hip, thigh, calf
constexpr double kWeightResidualScale = 0.5;   // weight matters, but less than a girth
// Weight of |c - c_linear|^2 against the squared relative errors: it only breaks ties
// (a free column with no effect on any measurement stays at its linear value).
constexpr double kPull = 1e-5;

using Measured = Eigen::Matrix<double, kMatched + 1, 1>;

Measured measured_vector(const BodyMeasurements& m) {
    Measured v;
    v << m.height_m, m.shoulder_height_m, m.crotch_height_m, m.chest_girth_m, m.waist_girth_m,
        m.hip_girth_m, m.thigh_girth_m, m.calf_girth_m, m.weight_kg;
    return v;
}

}  // namespace

bool ShapeOptions::is_valid(std::string* why) const {
    if (max_iterations < 0 || max_iterations > 1000) {
        if (why) *why = "ShapeOptions::max_iterations must be in [0, 1000], got " + std::to_string(max_iterations);
        return false;
    }
    if (!(relative_tolerance > 0 && relative_tolerance < 0.1)) {
        if (why) *why = "ShapeOptions::relative_tolerance must be in (0, 0.1), got " + std::to_string(relative_tolerance);
        return false;
    }
    return true;
}

std::string ShapeSummary::brief_report() const {
    std::ostringstream os;
    static const char* names[] = {"converged", "max_iterations", "linear_only", "failed"};
    os << "shape_body: " << names[static_cast<int>(termination)] << " after " << iterations
       << " iterations, max relative measurement error " << max_relative_error * 100 << " %";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

ShapeSummary shape_body(const BodyModel& model, const SemanticShape& shape,
                        const ShapeOptions& options, ShapedBody& out) {
    std::string why;
    if (!shape.is_valid(&why)) throw InvalidInput("shape_body: " + why);
    if (!options.is_valid(&why)) throw InvalidInput("shape_body: " + why);
    const SemanticMap& map = model.semantic_map;
    Eigen::Matrix<double, 1 + kSemanticCount, 1> v;
    v[0] = shape.gender == Gender::female ? 1.0 : 0.0;
    v.tail<kSemanticCount>() = shape.values;
    const Eigen::VectorXd c_linear = map.A * (v - map.reference) + map.b;

    ShapeSummary summary;
    out = shape_from_coefficients(model, c_linear);
    Measured target;
    target << shape[Semantic::height_m], shape[Semantic::shoulder_height_m],
        shape[Semantic::crotch_height_m], shape[Semantic::chest_girth_m],
        shape[Semantic::waist_girth_m], shape[Semantic::hip_girth_m],
        shape[Semantic::thigh_girth_m], shape[Semantic::calf_girth_m], shape[Semantic::weight_kg];
    auto relative_errors = [&](const Measured& m) {
        Measured r = (target - m).cwiseQuotient(target);
        r[kMatched] *= kWeightResidualScale;
        return r;
    };
    summary.measured = measure_body(model, out.vertices);
    Measured r = relative_errors(measured_vector(summary.measured));
    summary.max_relative_error = r.head<kMatched>().cwiseAbs().maxCoeff();
    if (!options.match_measurements || options.max_iterations == 0) {
        summary.termination = ShapeTermination::linear_only;
        summary.message = "linear semantic map only";
        return summary;
    }

    std::vector<int> free;
    for (int k = 0; k < model.shape_count(); ++k)
        if (map.refinable.size() == model.shape_count() && map.refinable[k] != 0) free.push_back(k);
    if (free.empty()) {
        summary.termination = ShapeTermination::linear_only;
        summary.message = "the model has no refinable shape coefficients";
        return summary;
    }
    const int nf = static_cast<int>(free.size());
    const Eigen::Index nv = model.vertex_count();
    auto displacement = [&](int k) {
        Eigen::MatrixXd D(nv, 3);
        for (Eigen::Index i = 0; i < nv; ++i)
            D.row(i) = model.shape_basis.block<3, 1>(3 * i, k).transpose();
        return D;
    };
    // Jacobian of the residual w.r.t. the free coefficients by one-sided differences at the
    // start, then Broyden rank-one updates (the measurements are nearly linear in c).
    Eigen::MatrixXd Jr(kMatched + 1, nf);
    const double h = 2e-3;
    for (int i = 0; i < nf; ++i) {
        const Measured m = measured_vector(measure_body(model, out.vertices + h * displacement(free[i])));
        Jr.col(i) = (relative_errors(m) - r) / h;
    }
    Eigen::VectorXd c = c_linear;
    double cost = r.squaredNorm();
    for (int iter = 0; iter < options.max_iterations; ++iter) {
        summary.iterations = iter + 1;
        // Gauss-Newton on r(c) plus a small pull towards the linear coefficients.
        Eigen::MatrixXd H = Jr.transpose() * Jr;
        Eigen::VectorXd g = Jr.transpose() * r;
        for (int i = 0; i < nf; ++i) {
            H(i, i) += kPull;
            g[i] += kPull * (c[free[i]] - c_linear[free[i]]);
        }
        const Eigen::VectorXd step = -H.ldlt().solve(g);
        if (!step.allFinite()) {
            summary.termination = ShapeTermination::failed;
            summary.message = "singular measurement Jacobian";
            return summary;
        }
        Eigen::VectorXd c_new = c;
        for (int i = 0; i < nf; ++i) c_new[free[i]] += step[i];
        ShapedBody trial = shape_from_coefficients(model, c_new);
        const BodyMeasurements m_new = measure_body(model, trial.vertices);
        const Measured r_new = relative_errors(measured_vector(m_new));
        // Broyden update of the Jacobian along the step actually taken.
        Jr += ((r_new - r) - Jr * step) * step.transpose() / step.squaredNorm();
        if (r_new.squaredNorm() <= cost * 1.5 || iter == 0) {
            c = c_new;
            out = std::move(trial);
            summary.measured = m_new;
            r = r_new;
            cost = r.squaredNorm();
        }
        summary.max_relative_error = r.head<kMatched>().cwiseAbs().maxCoeff();
        if (summary.max_relative_error < options.relative_tolerance) {
            summary.termination = ShapeTermination::converged;
            return summary;
        }
    }
    summary.termination = ShapeTermination::max_iterations;
    summary.message = "measurements not matched to the tolerance";
    return summary;
}

}  // namespace drape::body
