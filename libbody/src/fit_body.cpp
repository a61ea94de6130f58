#include <drape/body/fit_body.hpp>

#include "fit_distance_transform.hpp"
#include "fit_kinematics.hpp"
#include "fit_residuals.hpp"
#include "fit_taylor_init.hpp"

#include <drape/body/measurements.hpp>
#include <drape/core/errors.hpp>

#include <ceres/ceres.h>
#include <ceres/manifold.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>

namespace drape::body {

bool FitOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    auto weight_ok = [](double w) { return std::isfinite(w) && w >= 0; };
    std::ostringstream os;
    if (camera == CameraModel::pinhole && !(std::isfinite(focal_px) && focal_px > 0)) {
        os << "FitOptions.focal_px must be > 0 for the pinhole camera, got " << focal_px;
        return fail(os.str());
    }
    if (max_iterations < 1) {
        os << "FitOptions.max_iterations must be >= 1, got " << max_iterations;
        return fail(os.str());
    }
    if (threads < 1) {
        os << "FitOptions.threads must be >= 1, got " << threads;
        return fail(os.str());
    }
    const std::pair<const char*, double> weights[] = {
        {"joint_weight", joint_weight},           {"silhouette_weight", silhouette_weight},
        {"skin_weight", skin_weight},             {"pose_prior_weight", pose_prior_weight},
        {"posture_weight", posture_weight},       {"lean_weight", lean_weight},
        {"shape_prior_weight", shape_prior_weight}};
    for (const auto& [name, w] : weights) {
        if (!weight_ok(w)) {
            os << "FitOptions." << name << " must be a finite number >= 0, got " << w;
            return fail(os.str());
        }
    }
    if (!(joint_weight > 0)) return fail("FitOptions.joint_weight must be > 0, got 0");
    std::string offsets_why;
    if (image_joints && !image_joints->is_valid(&offsets_why)) return fail("FitOptions.image_joints: " + offsets_why);
    return true;
}

ImageJointOffsets ImageJointOffsets::of(core::JointMarks marks) {
    return marks == core::JointMarks::model ? none() : hand_marked();
}

Eigen::Matrix<double, kImageJointCount, 3> image_joint_positions(const PosedSkeleton& skeleton,
                                                                 const ImageJointOffsets& offsets) {
    Eigen::Matrix<double, kImageJointCount, 3> out;
    for (int i = 0; i < kImageJointCount; ++i) {
        const int j = index(kImageJoints[static_cast<size_t>(i)]);
        const int bone = std::max(0, kJointParents[static_cast<size_t>(j)]);
        out.row(i) = (skeleton.joints.row(j).transpose() +
                      skeleton.global[static_cast<size_t>(bone)].linear() * offsets.offset_m.row(i).transpose())
                         .transpose();
    }
    return out;
}

bool ImageJointOffsets::is_valid(std::string* why) const {
    for (int i = 0; i < kImageJointCount; ++i) {
        const double n = offset_m.row(i).norm();
        if (!std::isfinite(n) || n > kMaxImageJointOffsetM) {
            if (why) {
                std::ostringstream os;
                os << "offset_m of image joint '" << kImageJointNames[static_cast<size_t>(i)] << "' is "
                   << n << " m long; it must be finite and at most " << kMaxImageJointOffsetM << " m";
                *why = os.str();
            }
            return false;
        }
    }
    return true;
}

std::string FitSummary::brief_report() const {
    static const char* names[] = {"converged", "max_iterations", "failed", "cancelled"};
    std::ostringstream os;
    os << "fit_body: " << names[static_cast<int>(termination)] << ", " << iterations
       << " iterations, cost " << std::setprecision(4) << initial_cost << " -> " << final_cost
       << ", mean joint error " << std::fixed << std::setprecision(2) << mean_joint_error_px
       << " px, " << std::setprecision(2) << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

namespace {

using detail::kCameraParams;
using detail::kRotationParams;
using detail::kShapeParams;
using detail::kTranslationParams;
using Clock = std::chrono::steady_clock;

constexpr int kSampleVertices = 800;  // vertices sampled for the silhouette terms
constexpr int kChunk = 100;            // sampled vertices per residual block (threading)
constexpr int kMaxPulls = 400;         // uncovered skin pixels pulled per outer round
constexpr int kSilhouetteRounds = 3;

void check_mask(const Mask& m, const char* name) {
    require(m.width > 0 && m.height > 0, "fit_body: the ", name, " mask is empty (", m.width,
            " x ", m.height, " pixels)");
    require(m.pixels.size() == static_cast<size_t>(m.width) * static_cast<size_t>(m.height),
            "fit_body: the ", name, " mask has ", m.pixels.size(), " pixels, expected ",
            m.width, " x ", m.height);
}

void validate(const BodyModel& model, const FitInputs& in, const FitOptions& options) {
    std::string why;
    require(options.is_valid(&why), "fit_body: ", why);
    check_mask(in.person, "person");
    require(in.person.count() > 0, "fit_body: the person mask has no pixel set");
    if (in.skin.width != 0 || in.skin.height != 0 || !in.skin.pixels.empty()) {
        check_mask(in.skin, "skin");
        require(in.skin.width == in.person.width && in.skin.height == in.person.height,
                "fit_body: the skin mask is ", in.skin.width, " x ", in.skin.height,
                " but the person mask is ", in.person.width, " x ", in.person.height);
    }
    for (int i = 0; i < kImageJointCount; ++i) {
        const double x = in.joints_px(i, 0), y = in.joints_px(i, 1);
        require(std::isfinite(x) && std::isfinite(y), "fit_body: joint ", i, " (",
                kImageJointNames[static_cast<size_t>(i)], ") is not finite: (", x, ", ", y, ")");
        require(x >= 0 && x <= in.person.width && y >= 0 && y <= in.person.height,
                "fit_body: joint ", i, " (", kImageJointNames[static_cast<size_t>(i)], ") at (",
                x, ", ", y, ") px lies outside the ", in.person.width, " x ", in.person.height,
                " image");
    }
    if (in.height_m)
        require(std::isfinite(*in.height_m) && *in.height_m > 0.5 && *in.height_m < 2.5,
                "fit_body: height_m must be a stature in metres within (0.5, 2.5), got ",
                *in.height_m);
    require(model.vertex_count() > 0 && model.faces.rows() > 0,
            "fit_body: the body model has no mesh");
    require(model.skin_weights.rows() == model.vertex_count() &&
                model.skin_weights.cols() == kJointCount,
            "fit_body: the model's skin weights must be #V x ", kJointCount);
    require(model.joint_regressor.rows() == kJointCount &&
                model.joint_regressor.cols() == model.vertex_count(),
            "fit_body: the model's joint regressor must be ", kJointCount, " x #V");
    require(model.shape_basis.rows() == 3 * model.vertex_count(),
            "fit_body: the model's shape basis must have 3 #V rows");
}

/// The person's height in pixels: from the head-top joint down to the lower ankle.
double person_height_px(const FitInputs& in) {
    const double ankle = std::max(in.joints_px(0, 1), in.joints_px(5, 1));
    const double h = ankle - in.joints_px(13, 1);
    if (h > 1) return h;
    // Degenerate joints: fall back to the mask's vertical extent.
    int top = in.person.height, bottom = -1;
    for (int y = 0; y < in.person.height; ++y)
        for (int x = 0; x < in.person.width; ++x)
            if (in.person.inside(x, y)) {
                top = std::min(top, y);
                bottom = std::max(bottom, y);
            }
    return std::max(1.0, double(bottom - top + 1));
}

/// Parameter blocks of the fit.
struct Params {
    Eigen::Matrix<double, kRotationParams, 1> rot = Eigen::Matrix<double, kRotationParams, 1>::Zero();
    Eigen::Vector3d trans = Eigen::Vector3d::Zero();
    Eigen::Vector3d cam = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, kShapeParams, 1> z = Eigen::Matrix<double, kShapeParams, 1>::Zero();

    Pose pose() const {
        Pose p;
        p.translation = trans;
        for (int j = 0; j < kJointCount; ++j) {
            Eigen::Vector3d r = rot.segment<3>(3 * j);
            // Pose wants angles <= pi: use the equivalent shorter rotation.
            const double angle = r.norm();
            if (angle > M_PI) r *= (angle - 2.0 * M_PI * std::ceil((angle - M_PI) / (2.0 * M_PI))) / angle;
            p.rotations.row(j) = r.transpose();
        }
        return p;
    }
    Camera camera(const Camera& fixed) const {
        Camera c = fixed;
        if (c.model == CameraModel::weak_perspective) {
            c.scale_px_per_m = cam[0];
            c.offset_px = cam.tail<2>();
        }
        return c;
    }
};

bool is_end_site(int j) {
    return j == index(Joint::head_top) || j == index(Joint::right_toe) ||
           j == index(Joint::left_toe);
}

enum class Stage { global, pose, full };

// The pose prior's weight per radian of each rotation parameter: the rest-pose term of
// pose_prior_weight everywhere but the root, plus the posture term on the trunk and legs, and
// the lean term on the root's tilt (its x and z components; the turn about the vertical, y,
// stays free).
std::array<double, kRotationParams> rest_weights(const FitOptions& options) {
    std::array<double, kRotationParams> w{};
    const double rest = 0.3 * std::sqrt(options.pose_prior_weight);
    const double posture = std::sqrt(options.posture_weight);
    for (int j = 1; j < kJointCount; ++j)
        for (int c = 0; c < 3; ++c) w[static_cast<size_t>(3 * j + c)] = rest;
    for (const Joint j : {Joint::spine, Joint::chest, Joint::right_hip, Joint::left_hip, Joint::right_knee,
                          Joint::left_knee})
        for (int c = 0; c < 3; ++c)
            w[static_cast<size_t>(3 * index(j) + c)] = std::hypot(rest, posture);
    const double lean = std::sqrt(options.lean_weight);
    w[0] = lean;  // the root's tilt forwards / backwards (about x)
    w[2] = lean;  // and sideways (about z)
    return w;
}

class Cancel : public ceres::IterationCallback {
public:
    Cancel(const std::function<bool(double)>& progress, double from, double to, int max_iter)
        : progress_(progress), from_(from), to_(to), max_iter_(max_iter) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
        if (!progress_) return ceres::SOLVER_CONTINUE;
        const double f = std::min(1.0, double(s.iteration) / std::max(1, max_iter_));
        if (!progress_(from_ + (to_ - from_) * f)) {
            cancelled = true;
            return ceres::SOLVER_ABORT;
        }
        return ceres::SOLVER_CONTINUE;
    }
    bool cancelled = false;

private:
    const std::function<bool(double)>& progress_;
    double from_, to_;
    int max_iter_;
};

struct Fitter {
    Fitter(const BodyModel& m, const FitInputs& i, const FitOptions& o) : model(m), in(i), options(o) {}
    const BodyModel& model;
    const FitInputs& in;
    const FitOptions& options;
    ImageJointOffsets offsets;  // options.image_joints, or those of in.marks
    Gender gender = Gender::female;
    Camera fixed;  // the camera model and the pinhole constants
    detail::LinearRest rest;
    detail::DistanceField outside;  // distance to the person mask
    double unit_px = 1;
    JointLimits limits;
    detail::ShapePriorResidual shape_prior;

    int iterations = 0;
    double initial_cost = std::numeric_limits<double>::quiet_NaN();
    double final_cost = 0;
    ceres::TerminationType last_termination = ceres::CONVERGENCE;
    bool cancelled = false;
    std::string message;

    using CostFn4 = ceres::AutoDiffCostFunction<detail::JointResidual, 2 * kImageJointCount,
                                                kRotationParams, kTranslationParams,
                                                kCameraParams, kShapeParams>;

    void solve(Params& p, Stage stage, const std::vector<detail::Pull>& pulls, double from,
               double to, int max_iterations) {
        ceres::Problem problem;
        double* blocks[] = {p.rot.data(), p.trans.data(), p.cam.data(), p.z.data()};
        {
            auto* f = new detail::JointResidual{&rest, fixed, in.joints_px, offsets.offset_m,
                                                std::sqrt(options.joint_weight), unit_px};
            problem.AddResidualBlock(new CostFn4(f), nullptr, blocks, 4);
        }
        if (options.pose_prior_weight + options.posture_weight + options.lean_weight > 0) {
            auto* f = new detail::PosePriorResidual{limits, 10.0 * std::sqrt(options.pose_prior_weight),
                                                    rest_weights(options)};
            problem.AddResidualBlock(
                new ceres::AutoDiffCostFunction<detail::PosePriorResidual, 2 * kRotationParams,
                                                kRotationParams, kTranslationParams, kCameraParams,
                                                kShapeParams>(f),
                nullptr, blocks, 4);
        }
        const bool shape_free = stage == Stage::full && options.fit_shape;
        if (shape_free) {
            auto* f = new detail::ShapePriorResidual(shape_prior);
            problem.AddResidualBlock(
                new ceres::AutoDiffCostFunction<detail::ShapePriorResidual, kShapeParams + 1,
                                                kRotationParams, kTranslationParams, kCameraParams,
                                                kShapeParams>(f),
                nullptr, blocks, 4);
        }
        if (stage == Stage::full && options.silhouette_weight + options.skin_weight > 0) {
            const int n = rest.vertex_count();
            const double inside_w =
                std::sqrt(options.silhouette_weight * 2.0 * kImageJointCount / std::max(1, n));
            const double pull_w = pulls.empty() ? 0.0
                                                : std::sqrt(options.skin_weight * kImageJointCount /
                                                            double(pulls.size()));
            // Chunks of vertices (and of pulls) so that Ceres can evaluate them in parallel.
            const int chunks = std::max(1, (n + kChunk - 1) / kChunk);
            for (int c = 0; c < chunks; ++c) {
                detail::VertexResidual r;
                r.rest = &rest;
                r.fixed = fixed;
                r.outside = &outside;
                r.first = c * kChunk;
                r.count = options.silhouette_weight > 0 ? std::min(kChunk, n - r.first) : 0;
                r.inside_weight = inside_w;
                r.pull_weight = pull_w;
                r.unit_px = unit_px;
                for (size_t i = static_cast<size_t>(c); i < pulls.size(); i += static_cast<size_t>(chunks))
                    r.pulls.push_back(pulls[i]);
                const int count = r.residual_count();
                if (count == 0) continue;
                auto* f = new detail::VertexResidual(std::move(r));
                problem.AddResidualBlock(
                    new ceres::AutoDiffCostFunction<detail::VertexResidual, ceres::DYNAMIC,
                                                    kRotationParams, kTranslationParams,
                                                    kCameraParams, kShapeParams>(f, count),
                    nullptr, blocks, 4);
            }
        }
        // Which parameters move in this stage.
        std::vector<int> fixed_rot;
        for (int j = 0; j < kJointCount; ++j)
            if ((stage == Stage::global && j != 0) || is_end_site(j))
                for (int c = 0; c < 3; ++c) fixed_rot.push_back(3 * j + c);
        problem.SetManifold(p.rot.data(), new ceres::SubsetManifold(kRotationParams, fixed_rot));
        if (fixed.model == CameraModel::weak_perspective) {
            problem.SetParameterBlockConstant(p.trans.data());
            problem.SetParameterLowerBound(p.cam.data(), 0, 1e-3);
        } else {
            problem.SetParameterBlockConstant(p.cam.data());
        }
        if (!shape_free) problem.SetParameterBlockConstant(p.z.data());

        ceres::Solver::Options so;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = max_iterations;
        so.num_threads = options.threads;
        so.function_tolerance = 1e-6;
        so.parameter_tolerance = 1e-9;
        so.logging_type = ceres::SILENT;
        Cancel cancel(options.progress, from, to, max_iterations);
        so.callbacks.push_back(&cancel);
        ceres::Solver::Summary summary;
        ceres::Solve(so, &problem, &summary);
        iterations += static_cast<int>(summary.iterations.size()) - 1;
        if (std::isnan(initial_cost)) initial_cost = summary.initial_cost;
        final_cost = summary.final_cost;
        last_termination = summary.termination_type;
        if (cancel.cancelled) cancelled = true;
        if (summary.termination_type == ceres::FAILURE) message = summary.message;
    }

    /// Uncovered skin pixels, each pulling the nearest (projected) sampled vertex.
    std::vector<detail::Pull> skin_pulls(const Params& p) const {
        std::vector<detail::Pull> pulls;
        if (in.skin.width == 0 || options.skin_weight <= 0) return pulls;
        const ShapedBody shaped =
            shape_from_coefficients(model, detail::semantic_to_coefficients(model, gender, p.z));
        const PosedBody posed = pose_body(model, shaped, p.pose());
        const Camera camera = p.camera(fixed);
        const Mask body = render_silhouette(posed.vertices, model.faces, camera, in.person.width,
                                            in.person.height);
        std::vector<Eigen::Vector2d> uncovered;
        for (int y = 0; y < in.skin.height; ++y)
            for (int x = 0; x < in.skin.width; ++x)
                if (in.skin.inside(x, y) && !body.inside(x, y)) uncovered.emplace_back(x + 0.5, y + 0.5);
        if (uncovered.empty()) return pulls;
        const int n = rest.vertex_count();
        std::vector<Eigen::Vector2d> projected(static_cast<size_t>(n));
        for (int k = 0; k < n; ++k)
            projected[static_cast<size_t>(k)] =
                camera.project(posed.vertices.row(rest.vertex_ids[static_cast<size_t>(k)]).transpose());
        const size_t step = std::max<size_t>(1, uncovered.size() / kMaxPulls);
        for (size_t i = 0; i < uncovered.size(); i += step) {
            double best = std::numeric_limits<double>::infinity();
            int best_k = 0;
            for (int k = 0; k < n; ++k) {
                const double d = (projected[static_cast<size_t>(k)] - uncovered[i]).squaredNorm();
                if (d < best) {
                    best = d;
                    best_k = k;
                }
            }
            pulls.push_back({best_k, uncovered[i]});
        }
        return pulls;
    }
};

std::vector<int> sample_vertices(const BodyModel& model) {
    const int V = model.vertex_count();
    const int step = std::max(1, (V + kSampleVertices - 1) / kSampleVertices);
    std::vector<int> ids;
    for (int v = 0; v < V; v += step) ids.push_back(v);
    return ids;
}

}  // namespace

FitSummary fit_body(const BodyModel& model, const FitInputs& inputs, const FitOptions& options,
                    BodyFit& fit) {
    const auto start = Clock::now();
    validate(model, inputs, options);
    FitSummary summary;

    // Initial shape: the prior's (conditional) mean given what is known.
    SemanticRequest request;
    request.gender = inputs.gender;
    if (inputs.height_m) request[Semantic::height_m] = *inputs.height_m;
    const SemanticShape initial_shape = model.prior.complete(request);

    Fitter F(model, inputs, options);
    F.offsets = options.image_joints.value_or(ImageJointOffsets::of(inputs.marks));
    F.gender = initial_shape.gender;
    F.fixed.model = options.camera;
    F.rest = detail::make_linear_rest(model, F.gender, sample_vertices(model));
    F.outside = detail::distance_transform(inputs.person, true);
    F.unit_px = 0.01 * person_height_px(inputs);
    {
        const GaussianPrior& g = model.prior.of(F.gender);
        const Eigen::LLT<Eigen::Matrix<double, kSemanticCount, kSemanticCount>> llt(g.covariance);
        require(llt.info() == Eigen::Success,
                "fit_body: the model's shape prior covariance is not positive definite");
        F.shape_prior.sqrt_information =
            llt.matrixL().solve(Eigen::Matrix<double, kSemanticCount, kSemanticCount>::Identity());
        F.shape_prior.mean = g.mean;
        F.shape_prior.weight = std::sqrt(options.shape_prior_weight);
        F.shape_prior.height_m = inputs.height_m.value_or(0.0);
    }

    Params p;
    p.z = initial_shape.values;
    {
        Eigen::Matrix<double, kJointCount, 3> rest_joints;
        Eigen::Matrix<double, 3 * kJointCount, 1> flat =
            F.rest.joint_offset + F.rest.joint_jacobian * p.z;
        for (int j = 0; j < kJointCount; ++j) rest_joints.row(j) = flat.segment<3>(3 * j).transpose();
        F.limits = JointLimits::standard(rest_joints);
        // Taylor's bone lengths between the marked points: the image joints at rest.
        Eigen::Matrix<double, kJointCount, 3> marked = rest_joints;
        for (int i = 0; i < kImageJointCount; ++i)
            marked.row(index(kImageJoints[static_cast<size_t>(i)])) += F.offsets.offset_m.row(i);
        const detail::TaylorInit init = detail::taylor_initialize(marked, inputs.joints_px, F.limits);
        for (int j = 0; j < kJointCount; ++j) p.rot.segment<3>(3 * j) = init.rotations.row(j).transpose();
        p.trans = init.translation;
        p.cam << init.scale_px_per_m, init.offset_px.x(), init.offset_px.y();
        if (!p.rot.allFinite() || !p.trans.allFinite() || !p.cam.allFinite() || !(p.cam[0] > 0)) {
            // Degenerate joints (e.g. all at one pixel): start from the rest pose.
            p.rot.setZero();
            p.trans.setZero();
            p.cam << 100.0 * F.unit_px / std::max(0.5, p.z[0]), 0.5 * inputs.person.width,
                0.5 * inputs.person.height;
        }
        if (options.camera == CameraModel::pinhole) {
            // The hip midpoint at depth 0 seen at the same scale: distance = f / s.
            F.fixed.focal_px = options.focal_px;
            F.fixed.offset_px = Eigen::Vector2d(0.5 * inputs.person.width, 0.5 * inputs.person.height);
            const double s = p.cam[0];
            F.fixed.distance_m = options.focal_px / s;
            p.trans.x() += (p.cam[1] - F.fixed.offset_px.x()) / s;
            p.trans.y() -= (p.cam[2] - F.fixed.offset_px.y()) / s;
        }
    }

    Params good = p;  // the last finite parameters, reported if a stage diverges
    auto finish = [&]() {
        const bool finite = p.rot.allFinite() && p.z.allFinite() && p.cam.allFinite() &&
                            p.trans.allFinite() && (options.camera == CameraModel::pinhole || p.cam[0] > 0);
        if (!finite) {
            p = good;
            F.last_termination = ceres::FAILURE;
            if (F.message.empty()) F.message = "the solver produced non-finite parameters";
        }
        fit.pose = p.pose();
        fit.camera = p.camera(F.fixed);
        fit.coefficients = detail::semantic_to_coefficients(model, F.gender, p.z);
        const ShapedBody shaped = shape_from_coefficients(model, fit.coefficients);
        const Eigen::Matrix<double, kImageJointCount, 3> marked =
            image_joint_positions(forward_kinematics(shaped.joints, fit.pose), F.offsets);
        double error = 0;
        for (int i = 0; i < kImageJointCount; ++i) {
            const Eigen::Vector2d q = fit.camera.project(marked.row(i).transpose());
            fit.joints_2d.row(i) = q.transpose();
            error += (q - inputs.joints_px.row(i).transpose()).norm();
        }
        summary.mean_joint_error_px = error / kImageJointCount;
        fit.shape.gender = F.gender;
        fit.shape.values = p.z;
        try {
            const Eigen::Matrix<double, kSemanticCount, 1> measured =
                measure_body(model, shaped.vertices).as_semantic();
            for (int s = 0; s < kSemanticCount; ++s)
                if (std::isfinite(measured[s])) fit.shape.values[s] = measured[s];
        } catch (const InvalidInput&) {
            // A model without landmarks cannot be measured: report the fitted z instead.
        }
        summary.iterations = F.iterations;
        summary.initial_cost = std::isnan(F.initial_cost) ? 0.0 : F.initial_cost;
        summary.final_cost = F.final_cost;
        summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        if (F.cancelled) {
            summary.termination = Termination::cancelled;
            summary.message = "cancelled by the progress callback";
        } else if (F.last_termination == ceres::FAILURE) {
            summary.termination = Termination::failed;
            summary.message = F.message.empty() ? "the solver failed" : F.message;
        } else if (F.last_termination == ceres::NO_CONVERGENCE) {
            summary.termination = Termination::max_iterations;
        } else {
            summary.termination = Termination::converged;
        }
        return summary;
    };

    auto report = [&](double f) { return !options.progress || options.progress(f); };
    auto cancel = [&]() {
        F.cancelled = true;
        return finish();
    };
    if (!report(0.0)) return cancel();
    const int it = options.max_iterations;
    auto keep = [&]() {
        const bool ok = p.rot.allFinite() && p.z.allFinite() && p.cam.allFinite() &&
                        p.trans.allFinite();
        if (ok) good = p;
        return ok;
    };
    F.solve(p, Stage::global, {}, 0.0, 0.1, it);
    if (!keep()) return finish();
    if (F.cancelled || !report(0.1)) return cancel();
    // The joints-only stages only prepare the silhouette rounds: a few iterations suffice.
    F.solve(p, Stage::pose, {}, 0.1, 0.3, std::min(it, 30));
    if (!keep()) return finish();
    if (F.cancelled || !report(0.3)) return cancel();
    for (int round = 0; round < kSilhouetteRounds; ++round) {
        const double from = 0.3 + 0.7 * round / kSilhouetteRounds;
        const double to = 0.3 + 0.7 * (round + 1) / kSilhouetteRounds;
        const bool last = round + 1 == kSilhouetteRounds;
        F.solve(p, Stage::full, F.skin_pulls(p), from, to, last ? it : std::min(it, 20));
        if (!keep()) return finish();
        if (F.cancelled || !report(to)) return cancel();
    }
    return finish();
}

FitQuality fit_quality(const BodyModel& model, const FitInputs& inputs, const BodyFit& fit,
                       const FitSummary& summary) {
    require(inputs.skin.width == 0 || (inputs.skin.width == inputs.person.width && inputs.skin.height == inputs.person.height),
            "fit_quality: the skin mask is ", inputs.skin.width, " x ", inputs.skin.height,
            " pixels but the person mask is ", inputs.person.width, " x ", inputs.person.height);
    const ShapedBody shaped = shape_from_coefficients(model, fit.coefficients);
    const PosedBody posed = pose_body(model, shaped, fit.pose);
    FitQuality q;
    q.silhouette = render_silhouette(posed.vertices, model.faces, fit.camera, inputs.person.width, inputs.person.height);
    int inter = 0, uni = 0, skin_total = 0, skin_covered = 0;
    for (size_t i = 0; i < q.silhouette.pixels.size(); ++i) {
        const bool b = q.silhouette.pixels[i] != 0, p = inputs.person.pixels[i] != 0;
        inter += b && p;
        uni += b || p;
        if (!inputs.skin.pixels.empty() && inputs.skin.pixels[i]) {
            ++skin_total;
            skin_covered += b;
        }
    }
    q.person_iou = uni > 0 ? double(inter) / uni : 0.0;
    if (skin_total > 0) q.skin_coverage = double(skin_covered) / skin_total;
    q.person_height_px = std::max(inputs.joints_px(0, 1), inputs.joints_px(5, 1)) - inputs.joints_px(13, 1);
    q.mean_joint_error_percent = 100.0 * summary.mean_joint_error_px / std::max(1.0, q.person_height_px);
    // Posture in depth: the camera looks along z (both camera models), so a bone's angle out
    // of the image plane is asin(|dz| / length).
    const auto joint = [&](Joint j) -> Eigen::Vector3d { return posed.joints.row(index(j)).transpose(); };
    const auto out_of_plane = [](const Eigen::Vector3d& d) {
        const double n = d.norm();
        return n > 0 ? std::asin(std::min(1.0, std::abs(d.z()) / n)) * 180.0 / M_PI : 0.0;
    };
    q.trunk_out_of_plane_deg = out_of_plane(joint(Joint::neck) - joint(Joint::pelvis));
    for (const auto& [hip, knee, ankle] : {std::array<Joint, 3>{Joint::right_hip, Joint::right_knee, Joint::right_ankle},
                                           std::array<Joint, 3>{Joint::left_hip, Joint::left_knee, Joint::left_ankle}}) {
        const Eigen::Vector3d thigh = joint(knee) - joint(hip), shin = joint(ankle) - joint(knee);
        q.leg_out_of_plane_deg = std::max({q.leg_out_of_plane_deg, out_of_plane(thigh), out_of_plane(shin)});
        if (thigh.norm() > 0 && shin.norm() > 0) {
            const double c = std::clamp(thigh.normalized().dot(shin.normalized()), -1.0, 1.0);
            q.knee_bend_deg = std::max(q.knee_bend_deg, std::acos(c) * 180.0 / M_PI);
        }
    }
    return q;
}

}  // namespace drape::body
