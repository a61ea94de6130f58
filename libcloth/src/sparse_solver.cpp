#include "sparse_solver.hpp"

#include <mutex>

#ifdef DRAPE_CLOTH_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif
#ifdef DRAPE_CLOTH_HAVE_OPENMP
#include <omp.h>
#endif

namespace drape::cloth::internal {

namespace {

// CHOLMOD (SuiteSparse 5) opens OpenMP regions with a compiled-in num_threads(4) inside its
// supernodal factorisation. On a 2-core machine that already runs TBB workers, those extra
// threads spin and preempt each other (≈ 30 % of the time in profiles). While CHOLMOD runs
// on this thread, dynamic adjustment with one thread caps every region at one thread; the
// previous settings (per-thread ICVs, so other threads are unaffected) come back after.
class SingleThreadedOpenMp {
public:
#ifdef DRAPE_CLOTH_HAVE_OPENMP
    SingleThreadedOpenMp() : dynamic_(omp_get_dynamic()), threads_(omp_get_max_threads()) {
        omp_set_dynamic(1);
        omp_set_num_threads(1);
    }
    ~SingleThreadedOpenMp() {
        omp_set_num_threads(threads_);
        omp_set_dynamic(dynamic_);
    }

private:
    int dynamic_;
    int threads_;
#endif
};

// CHOLMOD's symbolic analysis runs METIS, whose random generator is global state in GKlib,
// and its supernodal factorisation and solve run the system's BLAS. Debian's serial OpenBLAS
// (0.3.21, the one scripts/setup.sh installs) is not safe for concurrent callers: two
// simulators factorising on two threads at once corrupted each other's factors, so garment
// recovery's parallel re-drapes differed from the same re-drapes in turn by up to 22 mm and
// took other Newton paths (measured 2026-11-27: identical with the reference BLAS, or with
// this lock). Every call into CHOLMOD therefore runs one at a time in the process. It costs
// no measured speed: two threads re-draping a skirt took 1.82 s with the lock, 2.27 s without
// (the unlocked calls contend for the same 2 cores); assembly and contact, the rest of a
// step, stay parallel. tests/cloth/test_sparse_solver.cpp checks the bit-identical results.
std::mutex& library_calls() {
    static std::mutex m;
    return m;
}

}  // namespace

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
    // Nested dissection (METIS) alone, not CHOLMOD's default (AMD, METIS only if AMD's fill
    // is poor): a cloth mesh is a surface grid, where nested dissection gives less fill and
    // fewer flops. Anchor scene N = 64: 66 -> 38 ms per factorisation (docs/cloth.md).
    cholmod_common& c = impl_->solver.cholmod();
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
    c.postorder = 1;
#endif
}

bool SparseSpdSolver::factorize(const Eigen::SparseMatrix<double>& m) {
    [[maybe_unused]] const SingleThreadedOpenMp single_threaded;
    {
        const std::lock_guard<std::mutex> lock(library_calls());
        if (!impl_->analysed) {
            impl_->solver.analyzePattern(m);
            impl_->analysed = true;
        }
        impl_->solver.factorize(m);
    }
    if (impl_->solver.info() != Eigen::Success) return false;
#ifndef DRAPE_CLOTH_HAVE_CHOLMOD
    // LDLᵀ succeeds on indefinite matrices too: require a positive D.
    if (!(impl_->solver.vectorD().array() > 0).all()) return false;
#endif
    return true;
}

Eigen::VectorXd SparseSpdSolver::solve(const Eigen::VectorXd& rhs) const {
    [[maybe_unused]] const SingleThreadedOpenMp single_threaded;
    const std::lock_guard<std::mutex> lock(library_calls());
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
