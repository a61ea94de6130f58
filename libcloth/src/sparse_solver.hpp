// Private: the sparse symmetric positive-definite solver behind the Newton steps. CHOLMOD's
// supernodal Cholesky when libcloth was built with it (DRAPE_CLOTH_HAVE_CHOLMOD), else
// Eigen's SimplicialLDLT. The symbolic analysis is kept until reset() (pattern change).
#pragma once

#include <Eigen/SparseCore>

#include <memory>

namespace drape::cloth::internal {

class SparseSpdSolver {
public:
    SparseSpdSolver();
    ~SparseSpdSolver();
    SparseSpdSolver(SparseSpdSolver&&) noexcept;
    SparseSpdSolver& operator=(SparseSpdSolver&&) noexcept;

    /// Forgets the symbolic analysis (call when the sparsity pattern changes).
    void reset();
    /// Factors `m` (lower triangle used); analyses its pattern on first use after reset().
    /// \return false if `m` is not numerically positive definite.
    bool factorize(const Eigen::SparseMatrix<double>& m);
    /// Solves with the last successful factorisation.
    Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
    /// "cholmod-supernodal" or "eigen-simplicial-ldlt".
    static const char* backend();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace drape::cloth::internal
