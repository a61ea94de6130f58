#include <drape/garment/material_search.hpp>

#include <drape/core/errors.hpp>

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <algorithm>
#include <map>
#include <sstream>

namespace drape::garment {

namespace {

// The objective in z (unbounded) with a central-difference derivative; every K is cached
// by x so that repeated points cost nothing.
class BendingObjective final : public ceres::FirstOrderFunction {
  public:
    BendingObjective(double target, const CurvatureOfBending& k, const MaterialSearchOptions& o)
        : target_(target), k_(k), o_(o) {}

    // Outside the range the drape is that of the nearest bound (the cost is flat there).
    double x_of(double z) const { return std::clamp(z, o_.min_log10_bending, o_.max_log10_bending); }
    double curvature(double x) const {
        const auto it = cache_.find(x);
        if (it != cache_.end()) return it->second;
        const double k = k_(x);
        ++evaluations;
        if (!std::isfinite(k)) throw InvalidInput("material search: the drape's mean curvature is not finite at log10 s_b = " +
                                                  std::to_string(x));
        cache_[x] = k;
        if (best_x < 0 || std::abs(k - target_) < std::abs(best_k - target_)) {
            best_x = x;
            best_k = k;
        }
        return k;
    }
    double residual(double x) const { return (curvature(x) - target_) / target_; }

    bool Evaluate(const double* z, double* cost, double* gradient) const override {
        // Out of budget: the evaluation "fails", which ends Ceres' line search and the solve;
        // the best point seen is the answer.
        if (evaluations + (gradient ? 3 : 1) > o_.max_evaluations) return false;
        const double x = x_of(z[0]);
        const double r = residual(x);
        cost[0] = r * r;
        if (gradient) {
            const double h = o_.difference_step;
            const double lo = std::max(o_.min_log10_bending, x - h), hi = std::min(o_.max_log10_bending, x + h);
            const double drdx = hi > lo ? (residual(hi) - residual(lo)) / (hi - lo) : 0.0;
            const double dxdz = z[0] == x ? 1.0 : 0.0;
            gradient[0] = 2.0 * r * drdx * dxdz;
        }
        return true;
    }
    int NumParameters() const override { return 1; }

    mutable int evaluations = 0;
    mutable double best_x = -1, best_k = 0;

  private:
    double target_;
    const CurvatureOfBending& k_;
    MaterialSearchOptions o_;
    mutable std::map<double, double> cache_;
};

}  // namespace

bool MaterialSearchOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!std::isfinite(min_log10_bending) || !std::isfinite(max_log10_bending) || !(max_log10_bending > min_log10_bending))
        return fail("the log10 bending range [" + std::to_string(min_log10_bending) + ", " +
                    std::to_string(max_log10_bending) + "] is empty or not finite");
    if (!(start_log10_bending >= min_log10_bending && start_log10_bending <= max_log10_bending))
        return fail("start_log10_bending = " + std::to_string(start_log10_bending) + " is outside the range");
    if (max_iterations < 1) return fail("max_iterations must be >= 1 (got " + std::to_string(max_iterations) + ")");
    if (max_evaluations < 3) return fail("max_evaluations must be >= 3 (got " + std::to_string(max_evaluations) + ")");
    if (!(difference_step > 0) || !std::isfinite(difference_step))
        return fail("difference_step must be > 0 (got " + std::to_string(difference_step) + ")");
    if (!(relative_tolerance >= 0) || !std::isfinite(relative_tolerance))
        return fail("relative_tolerance must be >= 0 (got " + std::to_string(relative_tolerance) + ")");
    return true;
}

double MaterialSearchSummary::bending_scale() const { return std::pow(10.0, log10_bending_scale); }

std::string MaterialSearchSummary::brief_report() const {
    static const char* names[] = {"converged", "max_iterations", "at_bound", "failed"};
    std::ostringstream s;
    s << "material search: " << names[static_cast<int>(termination)] << ", bending x" << bending_scale() << ", K "
      << mean_curvature_per_m << " / target " << target_per_m << " 1/m, " << evaluations << " drapes, " << seconds
      << " s";
    if (!message.empty()) s << " (" << message << ")";
    return s.str();
}

MaterialSearchSummary search_bending(double target, const CurvatureOfBending& curvature,
                                     const MaterialSearchOptions& options) {
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("material search options: " + why);
    if (!(target > 0) || !std::isfinite(target))
        throw InvalidInput("material search: the target mean curvature must be finite and > 0 (got " +
                           std::to_string(target) + " 1/m)");
    if (!curvature) throw InvalidInput("material search: no curvature function given");
    const auto t0 = std::chrono::steady_clock::now();
    MaterialSearchSummary out;
    out.target_per_m = target;
    auto* objective = new BendingObjective(target, curvature, options);  // owned by the problem
    const ceres::GradientProblem problem(objective);
    const double span = options.max_log10_bending - options.min_log10_bending;
    double z = options.start_log10_bending;
    ceres::GradientProblemSolver::Options so;
    so.line_search_direction_type = ceres::LBFGS;
    so.max_num_iterations = options.max_iterations;
    so.logging_type = ceres::SILENT;
    so.max_num_line_search_step_size_iterations = 4;
    so.function_tolerance = 1e-10;
    so.gradient_tolerance = 1e-12;
    const double tol2 = options.relative_tolerance * options.relative_tolerance;
    struct Stop final : ceres::IterationCallback {
        double tol2;
        std::vector<double>* history;
        ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
            history->push_back(s.cost);
            return s.cost <= tol2 ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
        }
    } stop;
    stop.tol2 = tol2;
    stop.history = &out.history;
    so.callbacks.push_back(&stop);
    ceres::GradientProblemSolver::Summary summary;
    try {
        ceres::Solve(so, problem, &z, &summary);
    } catch (const InvalidInput& e) {
        out.termination = MaterialSearchTermination::failed;
        out.message = e.what();
    }
    out.evaluations = objective->evaluations;
    if (objective->best_x >= 0) {
        out.log10_bending_scale = objective->best_x;
        out.mean_curvature_per_m = objective->best_k;
    }
    if (out.message.empty()) {
        const double r = (out.mean_curvature_per_m - target) / target;
        const double edge = 0.02 * span;
        if (r * r <= tol2)
            out.termination = MaterialSearchTermination::converged;
        else if (out.log10_bending_scale <= options.min_log10_bending + edge ||
                 out.log10_bending_scale >= options.max_log10_bending - edge)
            out.termination = MaterialSearchTermination::at_bound;
        else
            out.termination = MaterialSearchTermination::max_iterations;
        if (out.termination != MaterialSearchTermination::converged) out.message = summary.message;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace drape::garment
