#include "sparse_solver.hpp"

#ifdef DRAPE_CLOTH_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif

namespace drape::cloth::internal {

struct SparseSpdSolver::Impl {
#ifdef DRAPE_CLOTH_HAVE_CHOLMOD
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
#else
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
#endif
    bool analysed = false;
};


SparseSpdSolver::SparseSpdSolver() { reset(); }
SparseSpdSolver::~SparseSpdSolver() = default;
SparseSpdSolver::SparseSpdSolver(SparseSpdSolver&&) noexcept = default;
SparseSpdSolver& SparseSpdSolver::operator=(SparseSpdSolver&&) noexcept = default;

void SparseSpdSolver::reset() {
    // A fresh solver object: CHOLMOD keeps its symbolic factor inside.
    impl_ = std::make_unique<Impl>();
#ifdef DRAPE_CLOTH_HAVE_CHOLMOD
    // An indefinite matrix is an expected outcome (the caller falls back): no printing.
    impl_->solver.cholmod().print = 0;
#endif
}

bool SparseSpdSolver::factorize(const Eigen::SparseMatrix<double>& m) {
    if (!impl_->analysed) {
        impl_->solver.analyzePattern(m);
        impl_->analysed = true;
    }
    impl_->solver.factorize(m);
    if (impl_->solver.info() != Eigen::Success) return false;
#ifndef DRAPE_CLOTH_HAVE_CHOLMOD
    // LDLᵀ succeeds on indefinite matrices too: require a positive D.
    if (!(impl_->solver.vectorD().array() > 0).all()) return false;
#endif
    return true;
}

Eigen::VectorXd SparseSpdSolver::solve(const Eigen::VectorXd& rhs) const {
    return impl_->solver.solve(rhs);
}

const char* SparseSpdSolver::backend() {
#ifdef DRAPE_CLOTH_HAVE_CHOLMOD
    return "cholmod-supernodal";
#else
    return "eigen-simplicial-ldlt";
#endif
}

}  // namespace drape::cloth::internal
