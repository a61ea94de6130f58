// A small RAII wrapper over the HDF5 C API, private to libbody (model_io_hdf5.cpp and the
// tests). No HDF5 type appears here, so includers need not see <hdf5.h>.
//
// Every call silences HDF5's automatic error-stack printing for the lifetime of the File
// (restored afterwards) and reports failures as exceptions instead:
//   - drape::IoError      the file cannot be created / opened / written / closed;
//   - drape::InvalidInput the file's content does not have the expected shape or type
//                         (the message names the file and the dataset).
// Datasets are addressed by absolute paths ("/mesh/faces"); writers create the
// intermediate groups. Matrices are stored row-major (C order), as h5py / numpy see them.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace drape::body::h5 {

enum class Mode {
    create,     ///< create or truncate
    read_only,  ///< must exist and be an HDF5 file
    read_write, ///< must exist and be an HDF5 file
};

/// Dimensions of a dataset (empty for a scalar).
using Dims = std::vector<std::size_t>;

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class File {
public:
    /// \throw drape::IoError naming `path` if it is missing, not HDF5, or cannot be created.
    File(const std::filesystem::path& path, Mode mode);
    /// Read-only, from the file's bytes in memory (HDF5's core driver): what is parsed is
    /// exactly `image`, whatever happens to the file meanwhile. `name` names it in messages.
    /// \throw drape::IoError naming `name` if `image` has no HDF5 signature or cannot be opened.
    File(const std::filesystem::path& name, const std::string& image);
    ~File();
    File(const File&) = delete;
    File& operator=(const File&) = delete;

    const std::filesystem::path& path() const { return path_; }

    /// Flushes and closes; reports a failure (the destructor would swallow it).
    /// \throw drape::IoError
    void close();

    /// True if every link along `object` ("/a/b/c") exists.
    bool exists(const std::string& object) const;
    bool has_attribute(const std::string& object, const std::string& name) const;
    /// Unlinks a dataset or group. \throw drape::IoError
    void remove(const std::string& object);
    /// Deletes an attribute of a group or dataset. \throw drape::IoError
    void remove_attribute(const std::string& object, const std::string& name);

    // ---- writing (throw drape::IoError) ----------------------------------------------
    /// rows x cols float64 (float32 with `single`, as converters from float32 sources do).
    void write_matrix(const std::string& dataset, const Eigen::MatrixXd& m, bool single = false);
    /// 1-D float64.
    void write_vector(const std::string& dataset, const Eigen::VectorXd& v);
    /// rows x cols int32.
    void write_int_matrix(const std::string& dataset, const Eigen::MatrixXi& m);
    /// 1-D int32 (or int64 with `wide`).
    void write_int_vector(const std::string& dataset, const std::vector<std::int64_t>& v,
                          bool wide = false);
    void write_double_scalar(const std::string& dataset, double value);
    void write_int_scalar(const std::string& dataset, int value);
    /// 1-D null-padded fixed-length UTF-8 strings of `fixed_size` bytes (numpy "S"
    /// arrays; 0 = the longest value's length, at least 1).
    void write_strings(const std::string& dataset, const std::vector<std::string>& values,
                       std::size_t fixed_size = 0);
    /// Fixed-length (or, with `variable_length`, h5py's default variable-length) UTF-8
    /// string attribute on a group or dataset ("/" for the file).
    void write_string_attribute(const std::string& object, const std::string& name,
                                const std::string& value, bool variable_length = false);
    void write_int_attribute(const std::string& object, const std::string& name, int value);

    // ---- reading (throw drape::InvalidInput naming the dataset) --------------------------
    /// Dimensions; \throw InvalidInput if the dataset is missing or not a dataset.
    Dims dims(const std::string& dataset) const;
    /// 2-D floating-point data (any float width), every value finite. `rows` / `cols` < 0
    /// accept any extent.
    Eigen::MatrixXd read_matrix(const std::string& dataset, long rows, long cols) const;
    /// 1-D floating-point data, finite. `size` < 0 accepts any length.
    Eigen::VectorXd read_vector(const std::string& dataset, long size) const;
    /// 2-D integer data (any integer width) fitting in int32.
    Eigen::MatrixXi read_int_matrix(const std::string& dataset, long rows, long cols) const;
    /// 1-D integer data (any width).
    std::vector<std::int64_t> read_int_vector(const std::string& dataset, long size) const;
    /// Scalar (or one-element 1-D) floating-point / integer data.
    double read_double_scalar(const std::string& dataset) const;
    std::int64_t read_int_scalar(const std::string& dataset) const;
    /// 1-D strings, fixed length (variable length only if allowed, below).
    std::vector<std::string> read_strings(const std::string& dataset, long size) const;
    /// Scalar string attribute, fixed length (variable length only if allowed, below).
    std::string read_string_attribute(const std::string& object, const std::string& name) const;
    /// Variable-length strings live in the file's global heap, which libhdf5 1.10 reads
    /// without checking: a damaged one crashes or hangs it (found by fuzzing,
    /// docs/hardening.md). Off by default: such strings are refused with an error naming
    /// the dataset, before libhdf5 reads them.
    void allow_variable_length_strings(bool allow) { allow_variable_ = allow; }
    std::int64_t read_int_attribute(const std::string& object, const std::string& name) const;

    /// Throws InvalidInput("file '<path>', dataset '<dataset>': <problem>").
    [[noreturn]] void fail(const std::string& dataset, const std::string& problem) const;

private:
    struct Impl;
    bool allow_variable_ = false;
    std::filesystem::path path_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace drape::body::h5
