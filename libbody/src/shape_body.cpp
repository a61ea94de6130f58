#include <drape/body/shape_body.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace drape::body {

namespace {

constexpr int kMatched = 8;  // height, shoulder, crotch, chest, waist, hip, thigh, calf

using Geometry = Eigen::Matrix<double, kMatched, 1>;

Geometry geometry_vector(const BodyMeasurements& m) {
    Geometry v;
    v << m.height_m, m.shoulder_height_m, m.crotch_height_m, m.chest_girth_m, m.waist_girth_m,
        m.hip_girth_m, m.thigh_girth_m, m.calf_girth_m;
    return v;
}

// Gauss-Newton on the relative errors of the eight girths/heights over the geometric
// columns, with a Broyden-updated Jacobian shared across calls.
struct GeometrySolver {
    const BodyModel& model;
    Geometry target;
    std::vector<int> columns;
    Eigen::MatrixXd jacobian;  // kMatched x columns, of the relative errors
    int measurements = 0;

    Geometry errors(const BodyMeasurements& m) const {
        return (target - geometry_vector(m)).cwiseQuotient(target);
    }

    BodyMeasurements measure(const ShapedBody& b) {
        ++measurements;
        return measure_body(model, b.vertices);
    }

    void init_jacobian(const ShapedBody& at, const Geometry& r0) {
        const Eigen::Index nv = model.vertex_count();
        jacobian.resize(kMatched, static_cast<Eigen::Index>(columns.size()));
        const double h = 2e-3;
        for (size_t i = 0; i < columns.size(); ++i) {
            Eigen::MatrixXd V = at.vertices;
            for (Eigen::Index v = 0; v < nv; ++v)
                V.row(v) += h * model.shape_basis.block<3, 1>(3 * v, columns[i]).transpose();
            ++measurements;
            jacobian.col(static_cast<Eigen::Index>(i)) = (errors(measure_body(model, V)) - r0) / h;
        }
    }

    /// Refines `body` (and `m`, its measurements) in place; returns the max |relative error|.
    double solve(ShapedBody& body, BodyMeasurements& m, int max_iterations, double tolerance, int& iterations) {
        Geometry r = errors(m);
        double err = r.cwiseAbs().maxCoeff();
        for (int it = 0; it < max_iterations && err >= tolerance; ++it) {
            ++iterations;
            // Minimum-norm Gauss-Newton step (columns may outnumber measurements).
            const Eigen::MatrixXd& J = jacobian;
            Eigen::VectorXd step =
                -J.transpose() * (J * J.transpose() + 1e-10 * Eigen::MatrixXd::Identity(kMatched, kMatched)).ldlt().solve(r);
            if (!step.allFinite()) return err;
            // Trust region: no coefficient moves more than 0.15 per iteration.
            const double biggest = step.cwiseAbs().maxCoeff();
            if (biggest > 0.15) step *= 0.15 / biggest;
            Eigen::VectorXd c = body.coefficients;
            for (size_t i = 0; i < columns.size(); ++i) c[columns[i]] += step[static_cast<Eigen::Index>(i)];
            ShapedBody trial = shape_from_coefficients(model, c);
            const BodyMeasurements m_new = measure(trial);
            const Geometry r_new = errors(m_new);
            jacobian += ((r_new - r) - J * step) * step.transpose() / step.squaredNorm();
            const double err_new = r_new.cwiseAbs().maxCoeff();
            if (err_new < err || r_new.squaredNorm() < r.squaredNorm()) {
                body = std::move(trial);
                m = m_new;
                r = r_new;
                err = err_new;
            }
        }
        return err;
    }
};

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
    GeometrySolver solver{model, {}, {}, {}, 0};
    solver.target << shape[Semantic::height_m], shape[Semantic::shoulder_height_m],
        shape[Semantic::crotch_height_m], shape[Semantic::chest_girth_m],
        shape[Semantic::waist_girth_m], shape[Semantic::hip_girth_m],
        shape[Semantic::thigh_girth_m], shape[Semantic::calf_girth_m];
    summary.measured = measure_body(model, out.vertices);
    summary.max_relative_error = solver.errors(summary.measured).cwiseAbs().maxCoeff();
    if (!options.match_measurements || options.max_iterations == 0) {
        summary.termination = ShapeTermination::linear_only;
        summary.message = "linear semantic map only";
        return summary;
    }
    int weight_column = -1;
    if (map.refinable.size() == model.shape_count())
        for (int k = 0; k < model.shape_count(); ++k) {
            if (map.refinable[k] == 1) solver.columns.push_back(k);
            if (map.refinable[k] == 2 && weight_column < 0) weight_column = k;
        }
    if (solver.columns.size() < static_cast<size_t>(kMatched)) {
        summary.termination = ShapeTermination::linear_only;
        summary.message = "the model has fewer than 8 refinable shape columns";
        return summary;
    }
    solver.init_jacobian(out, solver.errors(summary.measured));
    int iterations = 0;
    double err = solver.solve(out, summary.measured, options.max_iterations, options.relative_tolerance, iterations);

    // Weight: a 1-D secant search on the soft-tissue column, re-matching the geometry at
    // each trial, within +-1 of the linear map's value (the range the column was built for).
    const double weight_target = shape[Semantic::weight_kg];
    if (weight_column >= 0 && err < options.relative_tolerance) {
        const double f_lin = c_linear[weight_column];
        auto weight_error = [&](const BodyMeasurements& m) { return m.weight_kg - weight_target; };
        double f0 = f_lin, g0 = weight_error(summary.measured);
        double f1 = std::clamp(f0 - 0.3 * (g0 > 0 ? 1 : -1), f_lin - 1.0, f_lin + 1.0);
        for (int it = 0; it < 4 && std::abs(g0) > 0.002 * weight_target; ++it) {
            ShapedBody trial = out;
            Eigen::VectorXd c = trial.coefficients;
            c[weight_column] = f1;
            trial = shape_from_coefficients(model, c);
            BodyMeasurements m = solver.measure(trial);
            const double trial_err = solver.solve(trial, m, options.max_iterations, options.relative_tolerance, iterations);
            const double g1 = weight_error(m);
            if (trial_err < options.relative_tolerance && std::abs(g1) < std::abs(g0)) {
                out = std::move(trial);
                summary.measured = m;
                err = trial_err;
            }
            if (std::abs(g1 - g0) < 1e-9) break;
            const double f2 = std::clamp(f1 - g1 * (f1 - f0) / (g1 - g0), f_lin - 1.0, f_lin + 1.0);
            f0 = f1;
            g0 = g1;
            if (std::abs(f2 - f1) < 1e-4) break;
            f1 = f2;
        }
    }
    summary.iterations = iterations;
    summary.max_relative_error = err;
    if (err < options.relative_tolerance) {
        summary.termination = ShapeTermination::converged;
        return summary;
    }
    summary.termination = ShapeTermination::max_iterations;
    summary.message = "measurements not matched to the tolerance";
    return summary;
}

}  // namespace drape::body
