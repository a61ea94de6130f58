#include <drape/cloth/energies.hpp>

#include <drape/core/errors.hpp>

namespace drape::cloth {

Eigen::VectorXd vertex_masses(const ClothMesh& mesh, const Material& material) {
    std::string why;
    require(material.is_valid(&why), "vertex_masses: material is invalid: ", why);
    mesh.validate();
    Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh.vertex_count());
    for (int f = 0; f < mesh.face_count(); ++f) {
        const Eigen::Vector2d p0 = mesh.pattern.row(mesh.pattern_faces(f, 0)).transpose();
        const Eigen::Vector2d d1 = mesh.pattern.row(mesh.pattern_faces(f, 1)).transpose() - p0;
        const Eigen::Vector2d d2 = mesh.pattern.row(mesh.pattern_faces(f, 2)).transpose() - p0;
        const double area = 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
        for (int k = 0; k < 3; ++k) m(mesh.faces(f, k)) += material.density_kg_per_m2 * area / 3;
    }
    return m;
}

double gravity_energy(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses,
                      const Eigen::Vector3d& gravity, Eigen::MatrixX3d* gradient) {
    require(masses.size() == positions.rows(), "gravity_energy: masses has ", masses.size(),
            " entries, positions has ", positions.rows(), " rows");
    if (gradient) *gradient = -masses * gravity.transpose();
    return -(masses.transpose() * (positions * gravity)).value();
}

}  // namespace drape::cloth
