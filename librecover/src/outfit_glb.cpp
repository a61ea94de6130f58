#include <drape/recover/outfit_glb.hpp>

#include <drape/core/vertex_normals.hpp>
#include <drape/gltf/glb_writer.hpp>
#include <drape/render/material.hpp>
#include <drape/render/preview.hpp>

#include <string>
#include <utility>
#include <vector>

namespace drape::recover {

void write_outfit_glb(const std::filesystem::path& path, const OutfitMeshes& outfit) {
    outfit.validate();
    // The colours of the overlay: preview_scene's meshes are the body, then the garments.
    std::vector<render::PreviewGarment> preview;
    for (const OutfitGarment& g : outfit.garments) preview.push_back({g.V, g.F, Eigen::MatrixXd()});
    const render::Scene look = render::preview_scene(outfit.body_V, outfit.body_F, preview);

    gltf::GlbScene scene;
    scene.root_name = "outfit";
    auto add = [&](const std::string& node, const std::string& mesh_name, const Eigen::MatrixXd& V,
                   const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV, std::size_t look_index) {
        gltf::GlbMesh m;
        m.node_name = node;
        m.mesh_name = mesh_name;
        m.material_name = node;
        m.V = V;
        m.F = F;
        core::VertexNormalOptions normals;
        normals.isolated = Eigen::Vector3d::UnitY();
        m.N = core::vertex_normals(V, F, normals);
        m.UV = UV;
        m.base_colour_linear = render::srgb_to_linear(look.meshes[look_index].material.colour_srgb);
        scene.meshes.push_back(std::move(m));
    };
    add("body", "body", outfit.body_V, outfit.body_F, Eigen::MatrixXd(), 0);
    for (std::size_t k = 0; k < outfit.garments.size(); ++k) {
        const OutfitGarment& g = outfit.garments[k];
        const std::string node = "garment_" + std::to_string(k);
        add(node, g.name.empty() ? node : g.name, g.V, g.F, g.UV, k + 1);
    }
    gltf::write_glb(path, scene);
}

}  // namespace drape::recover
