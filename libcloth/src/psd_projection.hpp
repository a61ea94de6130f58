// Private: projection of a small symmetric matrix onto the positive semi-definite cone.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace drape::cloth::internal {

/// Replaces `m` by V max(Λ, 0) Vᵀ (its nearest PSD matrix in the Frobenius norm).
template <int N>
void project_psd(Eigen::Matrix<double, N, N>& m) {
    // Fast path: most elements under tension are already positive definite.
    if (Eigen::LLT<Eigen::Matrix<double, N, N>>(m).info() == Eigen::Success) return;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(m);
    Eigen::Matrix<double, N, 1> lambda = eig.eigenvalues();
    if (lambda.minCoeff() >= 0) return;
    lambda = lambda.cwiseMax(0.0);
    m = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace drape::cloth::internal
