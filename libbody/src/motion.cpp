// Motion: resampling, the designed walk cycle, and BVH retargeting (assimp reads the file).
#include <drape/body/motion.hpp>

#include <drape/core/byte_codec.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/isolated.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

namespace drape::body {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The hip's swing profile g(psi), amplitude 1, odd about psi = 0 like sin psi: its rate is
// tanh(kSwingSharpness cos psi) normalised, nearly constant through each half cycle and
// reversing smoothly at the ends. A sinusoidal swing moved the stance foot at pi/2 times the
// body's mean speed at mid-stance and with it at the ends: the feet skated 0.6-0.9 m/s
// backwards and forwards (and cloth held by friction went with them). Integrated once
// (trapezoid, kSwingSamples per cycle) and interpolated.
constexpr double kSwingSharpness = 4.0;
constexpr int kSwingSamples = 4096;

double swing_profile(double psi) {
    static const std::vector<double> table = [] {
        std::vector<double> g(kSwingSamples + 1, 0.0);
        const double d = 2 * kPi / kSwingSamples;
        const auto rate = [](double x) { return std::tanh(kSwingSharpness * std::cos(x)); };
        for (int i = 1; i <= kSwingSamples; ++i) g[std::size_t(i)] = g[std::size_t(i - 1)] + 0.5 * d * (rate((i - 1) * d) + rate(i * d));
        const double peak = g[kSwingSamples / 4];  // at psi = pi / 2
        for (double& v : g) v /= peak;
        return g;
    }();
    double x = std::fmod(psi, 2 * kPi);
    if (x < 0) x += 2 * kPi;
    const double u = x / (2 * kPi) * kSwingSamples;
    const int i = std::min(int(u), kSwingSamples - 1);
    const double f = u - i;
    return (1 - f) * table[std::size_t(i)] + f * table[std::size_t(i + 1)];
}

Eigen::Vector3d axis_angle(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd a(Eigen::Quaterniond(R).normalized());
    // AngleAxis of a unit quaternion has angle in [0, 2 pi); take the shorter equivalent.
    double angle = a.angle();
    Eigen::Vector3d axis = a.axis();
    if (angle > kPi) {
        angle = 2 * kPi - angle;
        axis = -axis;
    }
    return angle * axis;
}

bool finite_positive(double x) { return std::isfinite(x) && x > 0; }

}  // namespace

bool Motion::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!finite_positive(fps)) return fail("Motion::fps = " + std::to_string(fps) + " must be > 0");
    if (frames.empty()) return fail("Motion has no frame");
    std::string w;
    for (std::size_t k = 0; k < frames.size(); ++k)
        if (!frames[k].is_valid(&w)) return fail("Motion frame " + std::to_string(k) + ": " + w);
    return true;
}

Pose Motion::at(double t_s) const {
    std::string why;
    require(is_valid(&why), "Motion::at: ", why);
    require(std::isfinite(t_s), "Motion::at: t = ", t_s, " is not finite");
    const double x = std::clamp(t_s * fps, 0.0, double(frames.size() - 1));
    const std::size_t k = std::min(std::size_t(std::floor(x)), frames.size() - 1);
    if (k + 1 >= frames.size()) return frames.back();
    return interpolate_pose(frames[k], frames[k + 1], std::clamp(x - double(k), 0.0, 1.0));
}

Motion resample_motion(const Motion& motion, double fps, double seconds) {
    std::string why;
    require(motion.is_valid(&why), "resample_motion: ", why);
    require(finite_positive(fps), "resample_motion: fps = ", fps, " must be > 0");
    require(std::isfinite(seconds), "resample_motion: seconds = ", seconds, " is not finite");
    const double length = seconds > 0 ? seconds : motion.duration_s();
    const long count = std::lround(length * fps) + 1;
    require(count <= 1000000, "resample_motion: ", count, " frames (", length, " s at ", fps, " fps) is too many");
    Motion out;
    out.fps = fps;
    out.frames.reserve(std::size_t(count));
    for (long k = 0; k < count; ++k) out.frames.push_back(motion.at(double(k) / fps));
    return out;
}

bool WalkOptions::is_valid(std::string* why) const {
    auto check = [&](bool ok, const char* name, double value, const char* range) {
        if (!ok && why) *why = std::string("WalkOptions::") + name + " = " + std::to_string(value) + " must be " + range;
        return ok;
    };
    return check(finite_positive(period_s), "period_s", period_s, "> 0") &&
           check(hip_swing_rad >= 0 && hip_swing_rad <= 1, "hip_swing_rad", hip_swing_rad, "in [0, 1]") &&
           check(knee_swing_rad >= 0 && knee_swing_rad <= 1.5, "knee_swing_rad", knee_swing_rad, "in [0, 1.5]") &&
           check(arm_swing_rad >= 0 && arm_swing_rad <= 1, "arm_swing_rad", arm_swing_rad, "in [0, 1]") &&
           check(arm_lowering_rad >= 0 && arm_lowering_rad <= 1, "arm_lowering_rad", arm_lowering_rad, "in [0, 1]") &&
           check(bob_m >= 0 && bob_m <= 0.1, "bob_m", bob_m, "in [0, 0.1]");
}

Motion walk_cycle(const Eigen::Matrix<double, kJointCount, 3>& rest_joints, double seconds, double fps,
                  const WalkOptions& options) {
    std::string why;
    require(options.is_valid(&why), "walk_cycle: ", why);
    require(finite_positive(fps), "walk_cycle: fps = ", fps, " must be > 0");
    require(finite_positive(seconds), "walk_cycle: seconds = ", seconds, " must be > 0");
    require(rest_joints.allFinite(), "walk_cycle: the rest joints are not finite");
    const long count = std::lround(seconds * fps) + 1;
    require(count <= 1000000, "walk_cycle: ", count, " frames is too many");
    const auto J = [&](Joint j) -> Eigen::Vector3d { return rest_joints.row(index(j)).transpose(); };
    const double leg = 0.5 * ((J(Joint::left_hip) - J(Joint::left_knee)).norm() +
                              (J(Joint::left_knee) - J(Joint::left_ankle)).norm() +
                              (J(Joint::right_hip) - J(Joint::right_knee)).norm() +
                              (J(Joint::right_knee) - J(Joint::right_ankle)).norm());
    // The stance foot, swung back through most of its half cycle at the profile's steady rate,
    // stays put: the body moves at the foot's speed relative to the hip there, L dtheta/dt.
    const double steady_rate = (swing_profile(1e-3) - swing_profile(-1e-3)) / 2e-3;  // dg/dpsi at 0
    const double speed =
        options.forward ? leg * options.hip_swing_rad * steady_rate * 2 * kPi / options.period_s : 0.0;
    Motion out;
    out.fps = fps;
    out.frames.reserve(std::size_t(count));
    for (long k = 0; k < count; ++k) {
        const double t = double(k) / fps;
        const double phi = 2 * kPi * t / options.period_s;
        Pose p;
        // Leg with phase psi: flexion forward (negative x at the hip), the knee bent in swing
        // (the leg moving forward: cos psi > 0) and a little in stance.
        const auto leg_pose = [&](Joint hip, Joint knee, Joint ankle, double psi) {
            p.rotations.row(index(hip)) << -options.hip_swing_rad * swing_profile(psi), 0, 0;
            const double swing = std::max(0.0, std::cos(psi));
            p.rotations.row(index(knee)) << 0.08 + options.knee_swing_rad * swing * swing, 0, 0;
            p.rotations.row(index(ankle)) << 0.14 * std::sin(psi), 0, 0;
        };
        leg_pose(Joint::right_hip, Joint::right_knee, Joint::right_ankle, phi);
        leg_pose(Joint::left_hip, Joint::left_knee, Joint::left_ankle, phi + kPi);
        // Arms swing opposite to the legs, lowered towards the sides, elbows a little bent.
        p.rotations.row(index(Joint::right_shoulder)) << options.arm_swing_rad * std::sin(phi), 0,
            options.arm_lowering_rad;
        p.rotations.row(index(Joint::left_shoulder)) << -options.arm_swing_rad * std::sin(phi), 0,
            -options.arm_lowering_rad;
        p.rotations.row(index(Joint::right_elbow)) << -0.25, 0, 0;
        p.rotations.row(index(Joint::left_elbow)) << -0.25, 0, 0;
        // The pelvis turns with the forward leg; the body bobs twice per cycle.
        p.rotations.row(index(Joint::pelvis)) << 0, 0.08 * std::sin(phi), 0;
        p.translation << 0, options.bob_m * (std::cos(2 * phi) - 1), speed * t;
        out.frames.push_back(p);
    }
    return out;
}

BvhJointMap BvhJointMap::standard() {
    BvhJointMap m;
    const auto set = [&](Joint j, std::vector<std::string> names, bool required) {
        m.candidates[std::size_t(index(j))] = std::move(names);
        m.required[std::size_t(index(j))] = required;
    };
    set(Joint::pelvis, {"Hips", "hip", "Hip", "pelvis", "Pelvis", "Root"}, true);
    set(Joint::spine, {"LowerBack", "Ab", "abdomen", "Spine", "spine"}, false);
    set(Joint::chest, {"Spine1", "Chest", "chest", "Spine2"}, false);
    set(Joint::neck, {"Neck", "neck"}, false);
    set(Joint::head, {"Head", "head"}, false);
    for (const char* side : {"Left", "Right"}) {
        const bool left = side[0] == 'L';
        const std::string s = side, c = left ? "L" : "R", l = left ? "l" : "r";
        set(left ? Joint::left_clavicle : Joint::right_clavicle, {s + "Collar", s + "Shoulder", l + "Collar"}, false);
        set(left ? Joint::left_shoulder : Joint::right_shoulder, {s + "Arm", s + "UpArm", s + "Shoulder", l + "Shldr"},
            true);
        set(left ? Joint::left_elbow : Joint::right_elbow, {s + "ForeArm", s + "Elbow", s + "LowArm", l + "ForeArm"},
            true);
        set(left ? Joint::left_wrist : Joint::right_wrist, {s + "Hand", s + "Wrist", l + "Hand"}, false);
        set(left ? Joint::left_hip : Joint::right_hip, {s + "UpLeg", s + "Hip", s + "Thigh", l + "Thigh"}, true);
        set(left ? Joint::left_knee : Joint::right_knee, {s + "Leg", s + "Knee", s + "Shin", s + "LowLeg", l + "Shin"},
            true);
        set(left ? Joint::left_ankle : Joint::right_ankle, {s + "Foot", s + "Ankle", l + "Foot"}, false);
        set(left ? Joint::left_toe : Joint::right_toe, {s + "ToeBase", s + "Toes", s + "Toe"}, false);
    }
    return m;
}

namespace {

/// The BVH hierarchy as flat arrays (parents before children), end sites excluded.
struct BvhSkeleton {
    std::vector<std::string> names;
    std::vector<int> parents;
    std::vector<const aiNodeAnim*> channels;  // null: no channel (the rest transform)
    std::vector<aiMatrix4x4> rest_local;
    std::vector<Eigen::Vector3d> rest_position;  // world, the file's units
};

void flatten(const aiNode* node, int parent, const std::map<std::string, const aiNodeAnim*>& channels,
             BvhSkeleton& out) {
    const std::string name = node->mName.C_Str();
    const auto it = channels.find(name);
    // End sites have no channel and no children; they are not joints.
    if (it == channels.end() && node->mNumChildren == 0 && parent >= 0) return;
    const int me = int(out.names.size());
    out.names.push_back(name);
    out.parents.push_back(parent);
    out.channels.push_back(it == channels.end() ? nullptr : it->second);
    out.rest_local.push_back(node->mTransformation);
    const aiMatrix4x4& T = node->mTransformation;
    const Eigen::Vector3d offset(T.a4, T.b4, T.c4);
    out.rest_position.push_back(parent < 0 ? offset : Eigen::Vector3d(out.rest_position[std::size_t(parent)] + offset));
    for (unsigned c = 0; c < node->mNumChildren; ++c) flatten(node->mChildren[c], me, channels, out);
}

std::string joined(const std::vector<std::string>& names, std::size_t limit) {
    std::ostringstream os;
    for (std::size_t i = 0; i < names.size() && i < limit; ++i) os << (i ? ", " : "") << names[i];
    if (names.size() > limit) os << ", ...";
    return os.str();
}


Motion retarget_bvh(const std::filesystem::path& path, const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                    const BvhJointMap& map, BvhRetargetSummary* summary) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read BVH file '" + path.string() + "': no such file");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    if (!scene || !scene->mRootNode)
        throw IoError("BVH file '" + path.string() + "' does not parse: " + importer.GetErrorString());
    require(scene->mNumAnimations >= 1 && scene->mAnimations[0]->mNumChannels >= 1, "BVH file '", path.string(),
            "' has no motion (no animation channel)");
    const aiAnimation& anim = *scene->mAnimations[0];
    std::map<std::string, const aiNodeAnim*> channels;
    for (unsigned c = 0; c < anim.mNumChannels; ++c) channels[anim.mChannels[c]->mNodeName.C_Str()] = anim.mChannels[c];
    BvhSkeleton bvh;
    flatten(scene->mRootNode, -1, channels, bvh);
    const std::size_t nb = bvh.names.size();
    std::map<std::string, int> by_name;
    for (std::size_t b = 0; b < nb; ++b) by_name.emplace(bvh.names[b], int(b));

    // The joint map.
    std::array<int, kJointCount> source{};
    source.fill(-1);
    for (int j = 0; j < kJointCount; ++j) {
        for (const std::string& name : map.candidates[std::size_t(j)]) {
            const auto it = by_name.find(name);
            if (it != by_name.end()) {
                source[std::size_t(j)] = it->second;
                break;
            }
        }
        require(source[std::size_t(j)] >= 0 || !map.required[std::size_t(j)], "the joint map does not fit BVH file '",
                path.string(), "': joint '", kJointNames[std::size_t(j)], "' needs one of [",
                joined(map.candidates[std::size_t(j)], 20), "], the file has [", joined(bvh.names, 60), "]");
    }
    // Every mapped joint's BVH joint must have a channel with one key per frame.
    std::size_t frames = 0;
    for (int j = 0; j < kJointCount; ++j) {
        const int b = source[std::size_t(j)];
        if (b < 0) continue;
        const aiNodeAnim* ch = bvh.channels[std::size_t(b)];
        require(ch && ch->mNumRotationKeys >= 1, "BVH file '", path.string(), "': joint '", bvh.names[std::size_t(b)],
                "' (for '", kJointNames[std::size_t(j)], "') has no rotation channel");
        frames = frames == 0 ? ch->mNumRotationKeys : std::min<std::size_t>(frames, ch->mNumRotationKeys);
    }
    const aiNodeAnim* root_channel = bvh.channels[std::size_t(source[0])];
    require(root_channel->mNumPositionKeys >= 1, "BVH file '", path.string(), "': the root joint '",
            bvh.names[std::size_t(source[0])], "' has no position channel");
    frames = std::min<std::size_t>(frames, root_channel->mNumPositionKeys);
    const double ticks = anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 0.0;
    const double fps = frames >= 2 && ticks > 0
                           ? ticks / std::max(1e-12, root_channel->mRotationKeys[1].mTime - root_channel->mRotationKeys[0].mTime)
                           : (ticks > 0 ? ticks : 30.0);
    require(finite_positive(fps), "BVH file '", path.string(), "': frame rate ", fps, " is not positive");

    // Facing: turn about +Y so that the file's left hip lies towards +X, as ours.
    const auto rest_of = [&](Joint j) { return bvh.rest_position[std::size_t(source[std::size_t(index(j))])]; };
    Eigen::Vector3d across = rest_of(Joint::left_hip) - rest_of(Joint::right_hip);
    across.y() = 0;
    require(across.norm() > 0, "BVH file '", path.string(), "': its left and right hips coincide at rest");
    const double yaw = std::atan2(-across.z(), across.x());  // rotation about +Y taking across to +X
    const Eigen::Matrix3d A = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();

    // Rest offsets: per joint of ours, the rotation taking our rest bone direction onto the
    // file's (in our axes). The bone of joint j runs to the first mapped joint of `towards`.
    const std::array<std::vector<Joint>, kJointCount> towards = {{
        {Joint::spine, Joint::chest, Joint::neck},  // pelvis
        {Joint::chest, Joint::neck},                // spine
        {Joint::neck, Joint::head},                 // chest
        {Joint::head},                              // neck
        {},                                         // head
        {},                                         // head_top
        {Joint::right_shoulder},
        {Joint::right_elbow},
        {Joint::right_wrist},
        {},
        {Joint::left_shoulder},
        {Joint::left_elbow},
        {Joint::left_wrist},
        {},
        {Joint::right_knee},
        {Joint::right_ankle},
        {Joint::right_toe},
        {},
        {Joint::left_knee},
        {Joint::left_ankle},
        {Joint::left_toe},
        {},
    }};
    std::array<Eigen::Matrix3d, kJointCount> offset;
    for (int j = 0; j < kJointCount; ++j) {
        const int p = kJointParents[std::size_t(j)];
        offset[std::size_t(j)] = p < 0 ? Eigen::Matrix3d::Identity() : offset[std::size_t(p)];
        if (source[std::size_t(j)] < 0) continue;
        for (Joint c : towards[std::size_t(j)]) {
            if (source[std::size_t(index(c))] < 0) continue;
            const Eigen::Vector3d ours = (rest_joints.row(index(c)) - rest_joints.row(j)).transpose();
            const Eigen::Vector3d theirs = A * (bvh.rest_position[std::size_t(source[std::size_t(index(c))])] -
                                                bvh.rest_position[std::size_t(source[std::size_t(j)])]);
            if (ours.norm() < 1e-9 || theirs.norm() < 1e-9) continue;
            offset[std::size_t(j)] = Eigen::Quaterniond::FromTwoVectors(ours, theirs).toRotationMatrix();
            break;
        }
    }
    // Root motion scale: our leg length over the file's.
    const auto leg_of = [&](auto position, Joint hip, Joint knee, Joint ankle) {
        return (position(hip) - position(knee)).norm() + (position(knee) - position(ankle)).norm();
    };
    const auto ours_at = [&](Joint j) -> Eigen::Vector3d { return rest_joints.row(index(j)).transpose(); };
    const bool ankles = source[std::size_t(index(Joint::left_ankle))] >= 0 &&
                        source[std::size_t(index(Joint::right_ankle))] >= 0;
    double scale = 0;
    if (ankles) {
        const double theirs = leg_of(rest_of, Joint::left_hip, Joint::left_knee, Joint::left_ankle) +
                              leg_of(rest_of, Joint::right_hip, Joint::right_knee, Joint::right_ankle);
        const double ours = leg_of(ours_at, Joint::left_hip, Joint::left_knee, Joint::left_ankle) +
                            leg_of(ours_at, Joint::right_hip, Joint::right_knee, Joint::right_ankle);
        scale = theirs > 0 ? ours / theirs : 0;
    } else {
        const double theirs = (rest_of(Joint::left_hip) - rest_of(Joint::left_knee)).norm();
        scale = theirs > 0 ? (ours_at(Joint::left_hip) - ours_at(Joint::left_knee)).norm() / theirs : 0;
    }
    require(finite_positive(scale), "BVH file '", path.string(), "': its legs have zero length at rest");

    // Per frame: the file's world orientations, then ours.
    Motion out;
    out.fps = fps;
    out.frames.reserve(frames);
    std::vector<Eigen::Matrix3d> global(nb);
    Eigen::Vector3d root0 = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < frames; ++k) {
        for (std::size_t b = 0; b < nb; ++b) {
            Eigen::Matrix3d local = Eigen::Matrix3d::Identity();
            if (bvh.channels[b] && bvh.channels[b]->mNumRotationKeys > 0) {
                const aiQuaternion& q =
                    bvh.channels[b]->mRotationKeys[std::min<std::size_t>(k, bvh.channels[b]->mNumRotationKeys - 1)].mValue;
                local = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
            }
            global[b] = bvh.parents[b] < 0 ? local : Eigen::Matrix3d(global[std::size_t(bvh.parents[b])] * local);
        }
        std::array<Eigen::Matrix3d, kJointCount> Q;
        Pose pose;
        for (int j = 0; j < kJointCount; ++j) {
            const int p = kJointParents[std::size_t(j)];
            const int b = source[std::size_t(j)];
            Q[std::size_t(j)] = b < 0 ? (p < 0 ? Eigen::Matrix3d::Identity() : Q[std::size_t(p)])
                                      : Eigen::Matrix3d(A * global[std::size_t(b)] * A.transpose() * offset[std::size_t(j)]);
            const Eigen::Matrix3d local = p < 0 ? Q[std::size_t(j)] : Eigen::Matrix3d(Q[std::size_t(p)].transpose() * Q[std::size_t(j)]);
            pose.rotations.row(j) = axis_angle(local).transpose();
        }
        const aiVector3D& r = root_channel->mPositionKeys[k].mValue;
        const Eigen::Vector3d root(r.x, r.y, r.z);
        if (k == 0) root0 = root;
        pose.translation = scale * (A * (root - root0));
        out.frames.push_back(pose);
    }
    require(!out.frames.empty(), "BVH file '", path.string(), "' has no frame");
    if (summary) {
        summary->file_joints = int(nb);
        summary->file_frames = int(frames);
        summary->file_fps = fps;
        summary->mapped_joints = 0;
        for (int j = 0; j < kJointCount; ++j) {
            const int b = source[std::size_t(j)];
            summary->source[std::size_t(j)] = b < 0 ? std::string() : bvh.names[std::size_t(b)];
            summary->mapped_joints += b >= 0;
        }
        summary->root_scale = scale;
    }
    return out;
}

// The isolated child's output: the motion and the summary as plain bytes.
std::string encode_bvh(const Motion& m, const BvhRetargetSummary& s) {
    core::ByteEncoder e;
    e.f64(m.fps);
    e.u64(m.frames.size());
    for (const Pose& p : m.frames) {
        e.matrix(p.translation);
        e.matrix(p.rotations);
    }
    e.i64(s.file_joints);
    e.i64(s.file_frames);
    e.f64(s.file_fps);
    e.i64(s.mapped_joints);
    for (const std::string& name : s.source) e.str(name);
    e.f64(s.root_scale);
    return e.take();
}

Motion decode_bvh(const std::string& bytes, const std::filesystem::path& path, BvhRetargetSummary& s) {
    constexpr std::uint64_t kMaxFrames = 10'000'000;
    core::ByteDecoder d(bytes, "cannot read BVH file '" + path.string() + "': the isolated reader's output is damaged",
                        kMaxFrames);
    Motion m;
    m.fps = d.f64();
    const std::uint64_t n = d.u64();
    if (n > kMaxFrames || n > bytes.size() / (8 * (3 + 3 * kJointCount))) d.fail();
    m.frames.resize(n);
    for (Pose& p : m.frames) {
        d.matrix(p.translation);
        d.matrix(p.rotations);
    }
    const auto small = [&](std::int64_t v) { return static_cast<int>(std::clamp<std::int64_t>(v, -1, 1'000'000'000)); };
    s.file_joints = small(d.i64());
    s.file_frames = small(d.i64());
    s.file_fps = d.f64();
    s.mapped_joints = small(d.i64());
    for (std::string& name : s.source) name = d.str();
    s.root_scale = d.f64();
    d.finish();
    return m;
}

}  // namespace

Motion load_bvh_motion(const std::filesystem::path& path, const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                       const BvhJointMap& map, BvhRetargetSummary* summary, const BvhLoadOptions& options) {
    require(rest_joints.allFinite(), "load_bvh_motion: the rest joints are not finite");
    require(options.isolation_timeout_s > 0 && std::isfinite(options.isolation_timeout_s),
            "load_bvh_motion: isolation_timeout_s = ", options.isolation_timeout_s, " (need > 0)");
    if (!options.isolate) return retarget_bvh(path, rest_joints, map, summary);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read BVH file '" + path.string() + "': no such file");
    const core::IsolatedOutcome o = core::run_isolated(
        [&] {
            BvhRetargetSummary s;
            const Motion m = retarget_bvh(path, rest_joints, map, &s);
            return encode_bvh(m, s);
        },
        options.isolation_timeout_s, std::size_t(1) << 31);
    const std::string p = path.string();
    core::throw_unless_finished(o, "cannot read BVH file '" + p + "'", "the BVH importer (assimp)",
                                options.isolation_timeout_s);
    BvhRetargetSummary s;
    Motion m = decode_bvh(o.output, path, s);
    std::string why;
    if (!m.is_valid(&why))
        throw IoError("cannot read BVH file '" + p + "': the isolated reader returned an invalid motion: " + why);
    if (summary) *summary = s;
    return m;
}

}  // namespace drape::body
