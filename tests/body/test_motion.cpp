// Motion: BVH retargeting (a small file with known rotations, and the Debian assimp test
// files when installed), the walk cycle's periodicity, resampling, and bad input.
#include <drape/body/body_model.hpp>
#include <drape/body/motion.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/body/shape_prior.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace drape;
using namespace drape::body;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct TempFile {
    fs::path path;
    TempFile(const std::string& name, const std::string& text)
        : path(fs::temp_directory_path() / ("drape_motion_" + std::to_string(::getpid()) + "_" + name)) {
        std::ofstream(path) << text;
    }
    ~TempFile() { fs::remove(path); }
};

// A T-pose figure (Y up, facing +Z, its left at +X), lengths in cm: 13 joints, 42 channels.
// Frame 0: rest. Frame 1: root moved by (0, 10, 20), left knee flexed 30 degrees.
const char* kHierarchy = R"(HIERARCHY
ROOT Hips
{
  OFFSET 0 90 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT LeftUpLeg
  {
    OFFSET 10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT LeftLeg
    {
      OFFSET 0 -40 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT LeftFoot
      {
        OFFSET 0 -40 0
        CHANNELS 3 Zrotation Xrotation Yrotation
        End Site
        {
          OFFSET 0 -5 12
        }
      }
    }
  }
  JOINT RightUpLeg
  {
    OFFSET -10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT RightLeg
    {
      OFFSET 0 -40 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT RightFoot
      {
        OFFSET 0 -40 0
        CHANNELS 3 Zrotation Xrotation Yrotation
        End Site
        {
          OFFSET 0 -5 12
        }
      }
    }
  }
  JOINT Spine
  {
    OFFSET 0 10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT Neck
    {
      OFFSET 0 40 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT LeftArm
      {
        OFFSET 18 0 0
        CHANNELS 3 Zrotation Xrotation Yrotation
        JOINT LeftForeArm
        {
          OFFSET 28 0 0
          CHANNELS 3 Zrotation Xrotation Yrotation
          End Site
          {
            OFFSET 25 0 0
          }
        }
      }
      JOINT RightArm
      {
        OFFSET -18 0 0
        CHANNELS 3 Zrotation Xrotation Yrotation
        JOINT RightForeArm
        {
          OFFSET -28 0 0
          CHANNELS 3 Zrotation Xrotation Yrotation
          End Site
          {
            OFFSET -25 0 0
          }
        }
      }
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0333333
)";

std::string frame_line(double root_y, double root_z, double left_knee_x_deg) {
    std::string s = "0 " + std::to_string(root_y) + " " + std::to_string(root_z) + " 0 0 0";  // Hips
    s += " 0 0 0";                                                                              // LeftUpLeg
    s += " 0 " + std::to_string(left_knee_x_deg) + " 0";                                        // LeftLeg
    for (int j = 0; j < 10; ++j) s += " 0 0 0";
    return s + "\n";
}

std::string small_bvh() { return std::string(kHierarchy) + frame_line(90, 0, 0) + frame_line(100, 20, 30); }

Eigen::Matrix<double, kJointCount, 3> rest_joints() { return BodyModel::default_model().template_joints; }

double angle_of(const Pose& p, Joint j) { return p.rotations.row(index(j)).norm(); }

fs::path debian_bvh(const std::string& name) {
    const fs::path p = fs::path("/usr/share/assimp/models/BVH") / name;
    return fs::exists(p) ? p : fs::path();
}

}  // namespace

TEST_CASE("bvh: a small file is retargeted with its knee angle, T-pose arms and scaled root motion",
          "[body][motion]") {
    const TempFile file("small.bvh", small_bvh());
    BvhRetargetSummary s;
    const Motion m = load_bvh_motion(file.path, rest_joints(), BvhJointMap::standard(), &s);
    REQUIRE(m.frames.size() == 2);
    CHECK(s.file_joints == 13);
    CHECK(s.file_frames == 2);
    CHECK(m.fps == Approx(30.0).epsilon(1e-4));
    CHECK(s.source[std::size_t(index(Joint::left_knee))] == "LeftLeg");
    CHECK(s.source[std::size_t(index(Joint::left_shoulder))] == "LeftArm");
    CHECK(s.source[std::size_t(index(Joint::chest))].empty());  // no such joint in the file
    // The knee: the file's leg is straight at rest and flexed 30 degrees in frame 1; ours
    // (slightly bent at rest) follows: straight, then 30 degrees between thigh and shin, the
    // shin swung backwards (-Z).
    const auto knee_angle = [&](const Pose& p) {
        const PosedSkeleton k = forward_kinematics(rest_joints(), p);
        const Eigen::Vector3d thigh = (k.joints.row(index(Joint::left_knee)) - k.joints.row(index(Joint::left_hip))).transpose();
        const Eigen::Vector3d shin = (k.joints.row(index(Joint::left_ankle)) - k.joints.row(index(Joint::left_knee))).transpose();
        return std::make_pair(std::acos(std::clamp(thigh.normalized().dot(shin.normalized()), -1.0, 1.0)), shin);
    };
    CHECK(knee_angle(m.frames[0]).first < 0.5 * kDeg);
    CHECK(knee_angle(m.frames[1]).first == Approx(30 * kDeg).margin(0.5 * kDeg));
    CHECK(knee_angle(m.frames[1]).second.z() < 0);
    CHECK(m.frames[1].rotations(index(Joint::left_knee), 0) > 0.4);  // flexion is positive x, as ours
    CHECK(angle_of(m.frames[1], Joint::right_knee) == Approx(angle_of(m.frames[0], Joint::right_knee)).margin(1e-9));
    // Frame 0 is the file's T-pose: our A-pose arms are raised to horizontal.
    const PosedSkeleton sk = forward_kinematics(rest_joints(), m.frames[0]);
    const Eigen::Vector3d upper_arm =
        (sk.joints.row(index(Joint::left_elbow)) - sk.joints.row(index(Joint::left_shoulder))).transpose().normalized();
    CHECK(upper_arm.x() > 0.99);
    const Eigen::Vector3d right_arm =
        (sk.joints.row(index(Joint::right_elbow)) - sk.joints.row(index(Joint::right_shoulder))).transpose().normalized();
    CHECK(right_arm.x() < -0.99);
    // Root motion relative to frame 0, scaled by the leg length ratio (ours / 80 cm).
    const auto J = [&](Joint j) -> Eigen::Vector3d { return rest_joints().row(index(j)).transpose(); };
    const double our_legs = (J(Joint::left_hip) - J(Joint::left_knee)).norm() +
                            (J(Joint::left_knee) - J(Joint::left_ankle)).norm() +
                            (J(Joint::right_hip) - J(Joint::right_knee)).norm() +
                            (J(Joint::right_knee) - J(Joint::right_ankle)).norm();
    CHECK(s.root_scale == Approx(our_legs / 160.0).epsilon(1e-9));
    CHECK(m.frames[0].translation.norm() == Approx(0).margin(1e-12));
    CHECK((m.frames[1].translation - s.root_scale * Eigen::Vector3d(0, 10, 20)).norm() < 1e-5);
}

TEST_CASE("bvh: a figure facing -Z is turned to face +Z", "[body][motion]") {
    // The same figure turned 180 degrees: its left at -X.
    std::string text = small_bvh();
    auto flip = [&](const std::string& from, const std::string& to) {
        for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
            text.replace(at, from.size(), to);
    };
    flip("OFFSET 10 0 0", "OFFSET -10 0 0#");
    flip("OFFSET -10 0 0\n", "OFFSET 10 0 0\n");
    flip("OFFSET -10 0 0#", "OFFSET -10 0 0");
    const TempFile file("turned.bvh", text), straight("straight.bvh", small_bvh());
    const Motion m = load_bvh_motion(file.path, rest_joints());
    const Motion reference = load_bvh_motion(straight.path, rest_joints());
    // Its left hip at -X: the file's world is turned by 180 degrees about Y, so its forward
    // root motion (+Z in the file, backwards for it) becomes -Z and its pelvis stays upright.
    CHECK(m.frames[1].translation.z() < 0);
    CHECK(m.frames[1].translation.y() > 0);
    CHECK((m.frames[0].rotations.row(index(Joint::pelvis)) - reference.frames[0].rotations.row(index(Joint::pelvis)))
              .norm() < 1e-6);
}

TEST_CASE("bvh: the Debian assimp test captures retarget every joint but the head top", "[body][motion]") {
    const fs::path cmu = debian_bvh("01_01.bvh"), boxing = debian_bvh("Boxing_Toes.bvh");
    if (cmu.empty() || boxing.empty()) {
        WARN("skipped: /usr/share/assimp/models/BVH is absent (Debian package assimp-testmodels)");
        return;
    }
    BvhRetargetSummary s;
    const Motion m = load_bvh_motion(cmu, rest_joints(), BvhJointMap::standard(), &s);
    CHECK(s.file_joints == 31);
    CHECK(s.file_frames == 2752);
    CHECK(m.fps == Approx(120).epsilon(1e-3));
    CHECK(s.mapped_joints == 21);
    CHECK(s.source[std::size_t(index(Joint::left_clavicle))] == "LeftShoulder");
    CHECK(s.source[std::size_t(index(Joint::left_shoulder))] == "LeftArm");
    std::string why;
    CHECK(m.is_valid(&why));
    BvhRetargetSummary b;
    load_bvh_motion(boxing, rest_joints(), BvhJointMap::standard(), &b);
    CHECK(b.file_joints == 21);
    CHECK(b.source[std::size_t(index(Joint::left_clavicle))] == "LeftCollar");
    CHECK(b.source[std::size_t(index(Joint::left_shoulder))] == "LeftShoulder");
    CHECK(b.source[std::size_t(index(Joint::spine))] == "Ab");
    CHECK(b.mapped_joints == 21);
}

TEST_CASE("bvh: bad files and a joint map that does not fit get clear errors", "[body][motion]") {
    CHECK_THROWS_AS(load_bvh_motion("/no/such/motion.bvh", rest_joints()), IoError);
    const TempFile garbage("garbage.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
    CHECK_THROWS_AS(load_bvh_motion(garbage.path, rest_joints()), IoError);
    const TempFile file("map.bvh", small_bvh());
    BvhJointMap map = BvhJointMap::standard();
    map.candidates[std::size_t(index(Joint::left_knee))] = {"LeftShin"};
    try {
        load_bvh_motion(file.path, rest_joints(), map);
        FAIL("no error");
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        CHECK_THAT(what, Catch::Contains("does not fit"));
        CHECK_THAT(what, Catch::Contains("left_knee"));
        CHECK_THAT(what, Catch::Contains("LeftShin"));
        CHECK_THAT(what, Catch::Contains("LeftLeg"));  // the file's joints are listed
    }
}

TEST_CASE("walk cycle: periodic joint rotations, steady forward speed, valid poses", "[body][motion]") {
    WalkOptions o;
    o.period_s = 1.0;
    const Motion m = walk_cycle(rest_joints(), 2.5, 30, o);
    REQUIRE(m.frames.size() == 76);
    std::string why;
    REQUIRE(m.is_valid(&why));
    const Eigen::Vector3d stride = m.frames[30].translation - m.frames[0].translation;
    CHECK(stride.z() > 0.8);  // about 1.2 m per cycle for a 0.8 m leg at 22 degrees of swing
    CHECK(stride.z() < 2.0);
    for (std::size_t k = 0; k + 30 < m.frames.size(); ++k) {
        CHECK((m.frames[k + 30].rotations - m.frames[k].rotations).cwiseAbs().maxCoeff() < 1e-9);
        CHECK((m.frames[k + 30].translation - m.frames[k].translation - stride).norm() < 1e-9);
    }
    // Half a period later the legs have swapped: the right hip as the left was.
    CHECK(m.frames[15].rotations(index(Joint::right_hip), 0) ==
          Approx(m.frames[0].rotations(index(Joint::left_hip), 0)).margin(1e-9));
    CHECK(std::abs(m.frames[7].rotations(index(Joint::right_hip), 0)) > 0.3);  // it does swing
    o.forward = false;
    const Motion in_place = walk_cycle(rest_joints(), 1.0, 30, o);
    CHECK(in_place.frames.back().translation.z() == Approx(0).margin(1e-12));
}

// Cloth cannot fit between body surfaces closer than its layers and their contact layers
// (a sleeve and a side panel at the armpit need about 15 mm): the walk keeps the arms clear of
// the trunk. Measured on the median body (ANSUR II prior, shaped as eval-animate does) over one
// period: the closest arm (shoulder, elbow) and trunk (pelvis, spine, chest) vertices that are
// at least 3 cm apart at rest.
TEST_CASE("walk cycle: the swinging arms keep the armpit open on the median body", "[body][motion]") {
    const BodyModel& model = BodyModel::default_model();
    ShapedBody shaped;
    REQUIRE(shape_body(model, model.prior.complete(SemanticRequest{}), ShapeOptions{}, shaped).usable());
    const std::vector<int> dominant = dominant_joints(model);
    std::vector<int> arm, trunk;
    for (int v = 0; v < static_cast<int>(dominant.size()); ++v) {
        const int j = dominant[static_cast<std::size_t>(v)];
        if (j == index(Joint::left_shoulder) || j == index(Joint::left_elbow) || j == index(Joint::right_shoulder) ||
            j == index(Joint::right_elbow))
            arm.push_back(v);
        if (j == index(Joint::pelvis) || j == index(Joint::spine) || j == index(Joint::chest)) trunk.push_back(v);
    }
    REQUIRE(arm.size() > 50);
    REQUIRE(trunk.size() > 50);
    const Eigen::MatrixXd rest = pose_body(model, shaped, named_pose(NamedPose::a_pose)).vertices;
    auto clearance = [&](const Pose& pose) {
        const Eigen::MatrixXd x = pose_body(model, shaped, pose).vertices;
        double best = std::numeric_limits<double>::infinity();
        for (int a : arm)
            for (int t : trunk)
                if ((rest.row(a) - rest.row(t)).squaredNorm() >= 0.03 * 0.03)
                    best = std::min(best, (x.row(a) - x.row(t)).norm());
        return best;
    };
    auto worst_over_period = [&](const WalkOptions& options) {
        double worst = std::numeric_limits<double>::infinity();
        for (const Pose& p : walk_cycle(shaped.joints, 1.1, 10, options).frames) worst = std::min(worst, clearance(p));
        return worst;
    };
    CHECK(worst_over_period(WalkOptions{}) > 0.014);
    // The old lowering (0.42 rad, as arms_down) closed it: the measure can fail.
    WalkOptions lowered;
    lowered.arm_lowering_rad = 0.42;
    CHECK(worst_over_period(lowered) < 0.010);
}

TEST_CASE("motion: resampling interpolates between frames and holds the last pose", "[body][motion]") {
    Motion m;
    m.fps = 10;
    m.frames.resize(3);
    m.frames[1].rotations(index(Joint::left_knee), 0) = 0.4;
    m.frames[2].translation = Eigen::Vector3d(0, 0, 1);
    const Motion r = resample_motion(m, 20, 0.3);
    REQUIRE(r.frames.size() == 7);
    CHECK(r.fps == 20);
    CHECK(r.frames[1].rotations(index(Joint::left_knee), 0) == Approx(0.2));
    CHECK(r.frames[2].rotations(index(Joint::left_knee), 0) == Approx(0.4));
    CHECK(r.frames[3].translation.z() == Approx(0.5));  // t = 0.15 s: halfway from frame 1 to 2
    CHECK(r.frames[6].translation.z() == Approx(1.0));  // past the end: the last pose
    CHECK(resample_motion(m, 5).frames.size() == 2);  // the whole 0.2 s
    CHECK_THROWS_AS(resample_motion(m, -30), InvalidInput);
    CHECK_THROWS_AS(resample_motion(m, 0), InvalidInput);
    CHECK_THROWS_AS(walk_cycle(rest_joints(), 1, -30), InvalidInput);
    CHECK_THROWS_AS(walk_cycle(rest_joints(), -1, 30), InvalidInput);
    Motion empty;
    CHECK_THROWS_AS(resample_motion(empty, 30), InvalidInput);
}

// load_bvh_motion parses in a forked child by default (assimp 5.2 leaks on malformed files:
// docs/hardening.md): the motion that comes back is bit for bit the in-process one, and the
// child's errors arrive with their messages.
TEST_CASE("bvh: the isolated reader gives the in-process motion and errors", "[body][motion]") {
    const TempFile file("iso.bvh", small_bvh());
    BvhLoadOptions here;
    here.isolate = false;
    BvhRetargetSummary si, sh;
    const Motion isolated = load_bvh_motion(file.path, rest_joints(), BvhJointMap::standard(), &si);
    const Motion in_process = load_bvh_motion(file.path, rest_joints(), BvhJointMap::standard(), &sh, here);
    REQUIRE(isolated.frames.size() == in_process.frames.size());
    CHECK(isolated.fps == in_process.fps);
    for (std::size_t k = 0; k < isolated.frames.size(); ++k) {
        CHECK(isolated.frames[k].translation == in_process.frames[k].translation);
        CHECK(isolated.frames[k].rotations == in_process.frames[k].rotations);
    }
    CHECK(si.source == sh.source);
    CHECK(si.file_joints == sh.file_joints);
    CHECK(si.file_frames == sh.file_frames);
    CHECK(si.root_scale == sh.root_scale);
    const TempFile garbage("garbage_iso.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
    CHECK_THROWS_WITH(load_bvh_motion(garbage.path, rest_joints()),
                      Catch::Contains("garbage_iso.bvh") && Catch::Contains("does not parse"));
    BvhJointMap map = BvhJointMap::standard();
    map.candidates[std::size_t(index(Joint::left_knee))] = {"LeftShin"};
    CHECK_THROWS_AS(load_bvh_motion(file.path, rest_joints(), map), InvalidInput);
    BvhLoadOptions bad;
    bad.isolation_timeout_s = 0;
    CHECK_THROWS_WITH(load_bvh_motion(file.path, rest_joints(), BvhJointMap::standard(), nullptr, bad),
                      Catch::Contains("isolation_timeout_s"));
}
