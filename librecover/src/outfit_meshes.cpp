#include <drape/recover/outfit_meshes.hpp>

#include <drape/core/errors.hpp>

namespace drape::recover {

namespace {

void check_mesh(const std::string& who, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int class_id) {
    require(V.rows() >= 3 && V.cols() == 3, who, ": V is ", V.rows(), " x ", V.cols(),
            ", expected #V x 3 with #V >= 3");
    require(V.allFinite(), who, ": V has non-finite positions");
    require(F.rows() >= 1 && F.cols() == 3, who, ": F is ", F.rows(), " x ", F.cols(),
            ", expected #F x 3 with #F >= 1");
    require(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), who, ": F indexes vertices in [", F.minCoeff(), ", ",
            F.maxCoeff(), "], outside [0, ", V.rows(), ")");
    require(class_id >= 1 && class_id <= 255, who, ": class id ", class_id, " is outside 1..255");
}

}  // namespace

std::string outfit_mesh_name(const OutfitMeshes& outfit, std::size_t index) {
    if (index == 0) return "body";
    std::string s = "garment " + std::to_string(index - 1);
    if (index - 1 < outfit.garments.size() && !outfit.garments[index - 1].name.empty())
        s += " '" + outfit.garments[index - 1].name + "'";
    return s;
}

void OutfitMeshes::validate() const {
    check_mesh("outfit body", body_V, body_F, body_class_id);
    for (std::size_t k = 0; k < garments.size(); ++k) {
        const OutfitGarment& g = garments[k];
        const std::string who = "outfit " + outfit_mesh_name(*this, k + 1);
        check_mesh(who, g.V, g.F, g.class_id);
        require(g.UV.size() == 0 || (g.UV.rows() == g.V.rows() && g.UV.cols() == 2), who, ": UV is ",
                g.UV.rows(), " x ", g.UV.cols(), ", expected ", g.V.rows(), " x 2 or empty");
        require(g.UV.allFinite(), who, ": UV has non-finite values");
    }
}

}  // namespace drape::recover
