// Plain bytes for one process to hand data to another of the same build (run_isolated's
// output): host byte order, sizes as u64, matrices column by column. The decoder treats its
// input as untrusted: every read is bounded by what is left, every extent by a limit, and
// damage is an IoError with the caller's message. What the bytes mean is the caller's to
// check after decoding.
#pragma once

#include <drape/core/errors.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace drape::core {

class ByteEncoder {
public:
    void u64(std::uint64_t v) { raw(&v, sizeof v); }
    void i64(std::int64_t v) { raw(&v, sizeof v); }
    void f64(double v) { raw(&v, sizeof v); }
    void str(const std::string& v) {
        u64(v.size());
        raw(v.data(), v.size());
    }
    template <class M>
    void matrix(const M& m) {
        u64(static_cast<std::uint64_t>(m.rows()));
        u64(static_cast<std::uint64_t>(m.cols()));
        for (Eigen::Index c = 0; c < m.cols(); ++c)
            for (Eigen::Index r = 0; r < m.rows(); ++r) {
                if constexpr (std::is_integral_v<typename M::Scalar>) i64(m(r, c));
                else f64(m(r, c));
            }
    }
    void sparse(const Eigen::SparseMatrix<double>& m) {
        u64(static_cast<std::uint64_t>(m.rows()));
        u64(static_cast<std::uint64_t>(m.cols()));
        u64(static_cast<std::uint64_t>(m.nonZeros()));
        for (int k = 0; k < m.outerSize(); ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it) {
                i64(it.row());
                i64(it.col());
                f64(it.value());
            }
    }
    std::string take() { return std::move(out_); }

private:
    void raw(const void* p, std::size_t n) { out_.append(static_cast<const char*>(p), n); }
    std::string out_;
};

class ByteDecoder {
public:
    /// `in` must outlive the decoder; `error` is the IoError's message on damaged input;
    /// no matrix or sparse matrix may have more than `max_elements` entries.
    ByteDecoder(const std::string& in, std::string error, std::uint64_t max_elements)
        : in_(in), error_(std::move(error)), max_(max_elements) {}
    std::uint64_t u64() { return pod<std::uint64_t>(); }
    std::int64_t i64() { return pod<std::int64_t>(); }
    double f64() { return pod<double>(); }
    std::string str() {
        const std::uint64_t n = count(1);
        std::string v = in_.substr(at_, n);
        at_ += n;
        return v;
    }
    template <class M>
    void matrix(M& m) {
        const std::uint64_t rows = u64(), cols = u64();
        if (rows > max_ || cols > max_ ||
            rows * cols > max_ ||
            rows * cols * 8 > in_.size() - at_ ||
            (M::RowsAtCompileTime != Eigen::Dynamic && rows != std::uint64_t(M::RowsAtCompileTime)) ||
            (M::ColsAtCompileTime != Eigen::Dynamic && cols != std::uint64_t(M::ColsAtCompileTime)))
            fail();
        m.resize(Eigen::Index(rows), Eigen::Index(cols));
        for (Eigen::Index c = 0; c < m.cols(); ++c)
            for (Eigen::Index r = 0; r < m.rows(); ++r) {
                if constexpr (std::is_integral_v<typename M::Scalar>) {
                    const std::int64_t v = i64();
                    if (v < std::numeric_limits<typename M::Scalar>::min() || v > std::numeric_limits<typename M::Scalar>::max()) fail();
                    m(r, c) = static_cast<typename M::Scalar>(v);
                } else {
                    m(r, c) = f64();
                }
            }
    }
    Eigen::SparseMatrix<double> sparse() {
        const std::uint64_t rows = u64(), cols = u64(), nnz = u64();
        if (rows > max_ || cols > max_ ||
            nnz > max_ || nnz * 24 > in_.size() - at_)
            fail();
        std::vector<Eigen::Triplet<double>> t;
        t.reserve(nnz);
        for (std::uint64_t k = 0; k < nnz; ++k) {
            const std::int64_t r = i64(), c = i64();
            const double v = f64();
            if (r < 0 || c < 0 || std::uint64_t(r) >= rows || std::uint64_t(c) >= cols) fail();
            t.emplace_back(int(r), int(c), v);
        }
        Eigen::SparseMatrix<double> m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
        m.setFromTriplets(t.begin(), t.end());
        return m;
    }
    /// Throws unless every byte was read.
    void finish() const {
        if (at_ != in_.size()) fail();
    }
    /// Throws the damaged-input IoError.
    [[noreturn]] void fail() const { throw IoError(error_); }

private:
    template <class T>
    T pod() {
        if (in_.size() - at_ < sizeof(T)) fail();
        T v;
        std::memcpy(&v, in_.data() + at_, sizeof v);
        at_ += sizeof v;
        return v;
    }
    std::uint64_t count(std::uint64_t size_of) {
        const std::uint64_t n = u64();
        if (n > (in_.size() - at_) / size_of) fail();
        return n;
    }
    const std::string& in_;
    std::string error_;
    std::uint64_t max_;
    std::size_t at_ = 0;
};

}  // namespace drape::core
