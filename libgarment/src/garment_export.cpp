// write_garment_obj / write_garment_glb. glTF is written by drape::gltf (write_glb, as
// body::export_glb) from the scene built here; OBJ is written directly.
#include <drape/garment/garment_export.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/gltf/glb_writer.hpp>

#include <sstream>

namespace drape::garment {

Eigen::MatrixX3d flat_layout(const GarmentMesh& mesh) {
    const auto n = mesh.cloth.vertex_count();
    Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(n, 3);
    flat.leftCols<2>() = mesh.cloth.pattern.topRows(n);
    return flat;
}

namespace {

void check_positions(const char* who, const GarmentMesh& mesh, const Eigen::MatrixX3d& positions) {
    require(positions.rows() == mesh.cloth.vertex_count(), who, ": positions have ", positions.rows(),
            " rows, the mesh has ", mesh.cloth.vertex_count(), " vertices");
    require(mesh.uv.rows() >= positions.rows(), who, ": the mesh has ", mesh.uv.rows(), " uv rows for ",
            positions.rows(), " vertices");
    require(positions.allFinite(), who, ": positions are not finite");
}

// One mesh "garment" with the pattern uv and a default material, held by the root node.
gltf::GlbScene garment_scene(const GarmentMesh& m, const Eigen::MatrixX3d& X) {
    gltf::GlbScene scene;
    scene.root_name = "garment";
    gltf::GlbMesh mesh;
    mesh.mesh_name = "garment";
    mesh.material_name = "garment";
    mesh.V = X;
    mesh.F = m.cloth.faces;
    mesh.UV = m.uv.topRows(X.rows());
    scene.meshes.push_back(std::move(mesh));
    return scene;
}

}  // namespace

void write_garment_obj(const std::filesystem::path& path, const Pattern& pattern, const GarmentMesh& m,
                       const Eigen::MatrixX3d& positions, const std::string& what) {
    check_positions("write_garment_obj", m, positions);
    std::ostringstream os;
    os << "# drape '" << pattern.name << "': " << what << ", metres; vt = pattern uv\n";
    for (Eigen::Index v = 0; v < positions.rows(); ++v)
        os << "v " << positions(v, 0) << " " << positions(v, 1) << " " << positions(v, 2) << "\n";
    for (int v = 0; v < m.cloth.vertex_count(); ++v) os << "vt " << m.uv(v, 0) << " " << m.uv(v, 1) << "\n";
    int group = -1;
    for (int f = 0; f < m.cloth.face_count(); ++f) {
        const int p = m.panel_of_vertex(m.cloth.faces(f, 0));
        if (p != group) os << "g " << pattern.panels[static_cast<std::size_t>(group = p)].name << "\n";
        os << "f";
        for (int k = 0; k < 3; ++k) os << " " << m.cloth.faces(f, k) + 1 << "/" << m.cloth.faces(f, k) + 1;
        os << "\n";
    }
    write_text_atomically(path, os.str());
}

void write_garment_glb(const std::filesystem::path& path, const GarmentMesh& m, const Eigen::MatrixX3d& positions) {
    check_positions("write_garment_glb", m, positions);
    gltf::write_glb(path, garment_scene(m, positions));
}

}  // namespace drape::garment
