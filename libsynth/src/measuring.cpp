#include <drape/synth/measuring.hpp>

#include <drape/body/body_model.hpp>
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/local_curvature.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/core/errors.hpp>

#include <opencv2/core.hpp>

namespace drape::synth {

std::vector<double> mean_curvatures(const garment::DressedOutfit& outfit) {
    std::vector<double> out;
    for (std::size_t i = 0; i < outfit.meshes.size(); ++i) {
        const std::vector<cloth::Hinge> hinges = cloth::build_hinges(outfit.meshes[i].cloth);
        out.push_back(cloth::vertex_local_curvature(outfit.meshes[i].cloth, hinges, outfit.positions[i]).mean());
    }
    return out;
}

std::vector<DeepestInside> deepest_inside(const Eigen::MatrixXd& body_vertices,
                                          const garment::DressedOutfit& outfit) {
    const body::BodyModel& model = body::BodyModel::default_model();
    const Eigen::MatrixX3i& body_F = model.faces;
    const Eigen::MatrixX3d body_V = body_vertices;
    const cloth::Obstacle body_obstacle(body_V, body_F);
    const std::vector<int> joint_of = body::dominant_joints(model);
    std::vector<DeepestInside> out;
    for (std::size_t i = 0; i < outfit.positions.size(); ++i) {
        const Eigen::MatrixX3d& draped = outfit.positions[i];
        DeepestInside d;
        for (Eigen::Index v = 0; v < draped.rows(); ++v) {
            const cloth::ObstacleQuery q = body_obstacle.closest(draped.row(v).transpose(), 0.1);
            if (!q.found || -q.signed_distance_m <= d.depth_m) continue;
            const int joint = joint_of[size_t(body_F(q.face, 0))];
            d.found = true;
            d.depth_m = -q.signed_distance_m;
            d.panel = outfit.patterns[i].panels[size_t(outfit.meshes[i].panel_of_vertex(v))].name;
            d.position_m = draped.row(v).transpose();
            d.body_joint = joint >= 0 ? std::string(body::kJointNames[size_t(joint)]) : std::string();
        }
        out.push_back(d);
    }
    return out;
}

vision::Joints project_joints(const SynthScene& scene, const body::PosedBody& posed) {
    vision::Joints joints;
    joints.marks = vision::JointMarks::model;  // the model's own joints, projected
    for (int k = 0; k < body::kImageJointCount; ++k) {
        const Eigen::Vector3d X =
            posed.joints.row(body::index(body::kImageJoints[std::size_t(k)])).transpose() + scene.placement;
        joints.px[std::size_t(k)] = scene.camera.project(X);
    }
    return joints;
}

std::vector<GarmentWrinkles> measure_wrinkles(const SynthScene& scene, const cv::Mat& colour, const cv::Mat& labels,
                                              const vision::Joints& joints, const vision::WrinkleOptions& detector) {
    std::vector<GarmentWrinkles> out;
    for (const SynthGarment& g : scene.garments) {
        cv::Mat mask;
        cv::compare(labels, g.label, mask, cv::CMP_EQ);
        vision::WrinkleOptions wo = detector;
        wo.person_height_m = scene.shape[body::Semantic::height_m];
        GarmentWrinkles w;
        w.summary.message = "garment not visible";
        w.visible_pixels = cv::countNonZero(mask);
        if (w.visible_pixels > 0) {
            try {
                w.summary = vision::detect_wrinkles(colour, mask, cv::Mat(), joints, wo, nullptr);
            } catch (const InvalidInput& e) {  // e.g. a joint outside the frame: P stays 0
                w.summary.message = e.what();
            }
        }
        out.push_back(w);
    }
    return out;
}

}  // namespace drape::synth
