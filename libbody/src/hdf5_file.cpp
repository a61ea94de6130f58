#include "hdf5_file.hpp"

#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <system_error>
#include <utility>

namespace drape::body::h5 {

namespace {

/// Owns one hid_t and closes it with the matching H5*close.
class Handle {
public:
    using Closer = herr_t (*)(hid_t);
    Handle() = default;
    Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, H5I_INVALID_HID);
            closer_ = o.closer_;
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    hid_t get() const { return id_; }
    bool valid() const { return id_ >= 0; }
    /// Closes now and reports whether closing succeeded.
    bool reset() {
        bool ok = true;
        if (id_ >= 0 && closer_) ok = closer_(id_) >= 0;
        id_ = H5I_INVALID_HID;
        return ok;
    }

private:
    hid_t id_ = H5I_INVALID_HID;
    Closer closer_ = nullptr;
};

Handle dataset_handle(hid_t id) { return Handle(id, H5Dclose); }
Handle space_handle(hid_t id) { return Handle(id, H5Sclose); }
Handle type_handle(hid_t id) { return Handle(id, H5Tclose); }
Handle attr_handle(hid_t id) { return Handle(id, H5Aclose); }
Handle plist_handle(hid_t id) { return Handle(id, H5Pclose); }

/// Turns HDF5's automatic error printing off for this thread, restoring it on destruction.
class ErrorSilencer {
public:
    ErrorSilencer() {
        saved_ok_ = H5Eget_auto2(H5E_DEFAULT, &func_, &data_) >= 0;
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    }
    ~ErrorSilencer() {
        if (saved_ok_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
    }
    ErrorSilencer(const ErrorSilencer&) = delete;
    ErrorSilencer& operator=(const ErrorSilencer&) = delete;

private:
    H5E_auto2_t func_ = nullptr;
    void* data_ = nullptr;
    bool saved_ok_ = false;
};

std::string dims_text(const Dims& d) {
    if (d.empty()) return "scalar";
    std::string s;
    for (std::size_t i = 0; i < d.size(); ++i) s += (i ? " x " : "") + std::to_string(d[i]);
    return s;
}

std::vector<std::string> split_path(const std::string& object) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : object) {
        if (c == '/') {
            if (!cur.empty()) parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty()) parts.push_back(cur);
    return parts;
}

std::string string_from_fixed(const char* p, std::size_t n, H5T_str_t pad) {
    std::size_t len = 0;
    while (len < n && p[len] != '\0') ++len;
    std::string s(p, len);
    if (pad == H5T_STR_SPACEPAD) {
        while (!s.empty() && s.back() == ' ') s.pop_back();
    }
    return s;
}

}  // namespace

struct File::Impl {
    ErrorSilencer silencer;  // first member: outlives the file handle
    Handle file;
};

File::File(const std::filesystem::path& path, Mode mode) : path_(path), impl_(std::make_unique<Impl>()) {
    const std::string p = path.string();
    if (mode == Mode::create) {
        hid_t id = H5Fcreate(p.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
        if (id < 0) throw IoError("cannot create HDF5 file '" + p + "'");
        impl_->file = Handle(id, H5Fclose);
        return;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read '" + p + "': no such file");
    const htri_t is_hdf5 = H5Fis_hdf5(p.c_str());
    if (is_hdf5 < 0) throw IoError("cannot read '" + p + "': the file cannot be opened");
    if (is_hdf5 == 0) throw IoError("cannot read '" + p + "': not an HDF5 file");
    const hid_t id = H5Fopen(p.c_str(), mode == Mode::read_only ? H5F_ACC_RDONLY : H5F_ACC_RDWR,
                             H5P_DEFAULT);
    if (id < 0) throw IoError("cannot open HDF5 file '" + p + "'");
    impl_->file = Handle(id, H5Fclose);
}

File::File(const std::filesystem::path& name, const std::string& image) : path_(name), impl_(std::make_unique<Impl>()) {
    const std::string p = name.string();
    // The superblock's signature, at offset 0 or after a user block of 512, 1024, 2048, ...
    // bytes (the HDF5 file format specification, "Format Signature").
    static const char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
    bool signed_image = false;
    for (std::size_t at = 0; at + sizeof kSignature <= image.size() && !signed_image; at = at == 0 ? 512 : 2 * at)
        signed_image = std::memcmp(image.data() + at, kSignature, sizeof kSignature) == 0;
    if (!signed_image) throw IoError("cannot read '" + p + "': not an HDF5 file");
    const Handle fapl = plist_handle(H5Pcreate(H5P_FILE_ACCESS));
    // Core driver without a backing store: the image is read, the file never opened.
    if (!fapl.valid() || H5Pset_fapl_core(fapl.get(), 1 << 20, 0) < 0 ||
        H5Pset_file_image(fapl.get(), const_cast<char*>(image.data()), image.size()) < 0)
        throw IoError("cannot read '" + p + "': the HDF5 library refused its bytes");
    // The core driver refuses an image whose name exists on disk ("file already exists"):
    // HDF5 gets a name that cannot exist; messages name `name`.
    const hid_t id = H5Fopen("/nonexistent/drape-file-image.h5", H5F_ACC_RDONLY, fapl.get());
    if (id < 0) throw IoError("cannot open HDF5 file '" + p + "'");
    impl_->file = Handle(id, H5Fclose);
}

File::~File() = default;

void File::close() {
    if (!impl_->file.valid()) return;
    const bool flushed = H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) >= 0;
    const bool closed = impl_->file.reset();
    if (!flushed || !closed) throw IoError("failed while writing '" + path_.string() + "' (disk full?)");
}

void File::fail(const std::string& dataset, const std::string& problem) const {
    throw InvalidInput("file '" + path_.string() + "', dataset '" + dataset + "': " + problem);
}

bool File::exists(const std::string& object) const {
    std::string prefix;
    for (const std::string& part : split_path(object)) {
        prefix += "/" + part;
        if (H5Lexists(impl_->file.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    return true;
}

bool File::has_attribute(const std::string& object, const std::string& name) const {
    if (!exists(object)) return false;
    return H5Aexists_by_name(impl_->file.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

void File::remove(const std::string& object) {
    if (H5Ldelete(impl_->file.get(), object.c_str(), H5P_DEFAULT) < 0)
        throw IoError("cannot remove '" + object + "' from '" + path_.string() + "'");
}

void File::remove_attribute(const std::string& object, const std::string& name) {
    if (H5Adelete_by_name(impl_->file.get(), object.c_str(), name.c_str(), H5P_DEFAULT) < 0)
        throw IoError("cannot remove attribute '" + name + "' of '" + object + "' in '" +
                      path_.string() + "'");
}

// ---- writing ------------------------------------------------------------------------------

namespace {

void write_raw(hid_t file, const std::filesystem::path& path, const std::string& dataset,
               hid_t file_type, hid_t mem_type, const Dims& dims, const void* data) {
    std::vector<hsize_t> hd(dims.begin(), dims.end());
    Handle space = space_handle(dims.empty() ? H5Screate(H5S_SCALAR)
                                             : H5Screate_simple(static_cast<int>(hd.size()),
                                                                hd.data(), nullptr));
    Handle lcpl = plist_handle(H5Pcreate(H5P_LINK_CREATE));
    if (!space.valid() || !lcpl.valid() || H5Pset_create_intermediate_group(lcpl.get(), 1) < 0)
        throw IoError("cannot prepare dataset '" + dataset + "' in '" + path.string() + "'");
    Handle ds = dataset_handle(H5Dcreate2(file, dataset.c_str(), file_type, space.get(),
                                          lcpl.get(), H5P_DEFAULT, H5P_DEFAULT));
    if (!ds.valid())
        throw IoError("cannot create dataset '" + dataset + "' in '" + path.string() + "'");
    std::size_t count = 1;
    for (std::size_t d : dims) count *= d;
    if (count > 0 && H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
        throw IoError("cannot write dataset '" + dataset + "' in '" + path.string() + "'");
    if (!ds.reset())
        throw IoError("cannot finish dataset '" + dataset + "' in '" + path.string() + "'");
}

Handle utf8_string_type(std::size_t size) {
    Handle t = type_handle(H5Tcopy(H5T_C_S1));
    if (!t.valid()) return t;
    if (size == 0) {
        H5Tset_size(t.get(), H5T_VARIABLE);
    } else {
        H5Tset_size(t.get(), size);
        H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
    }
    H5Tset_cset(t.get(), H5T_CSET_UTF8);
    return t;
}

}  // namespace

void File::write_matrix(const std::string& dataset, const Eigen::MatrixXd& m, bool single) {
    const RowMatrixXd r = m;
    write_raw(impl_->file.get(), path_, dataset, single ? H5T_IEEE_F32LE : H5T_IEEE_F64LE,
              H5T_NATIVE_DOUBLE,
              {static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols())}, r.data());
}

void File::write_vector(const std::string& dataset, const Eigen::VectorXd& v) {
    write_raw(impl_->file.get(), path_, dataset, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
              {static_cast<std::size_t>(v.size())}, v.data());
}

void File::write_int_matrix(const std::string& dataset, const Eigen::MatrixXi& m) {
    const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> r = m;
    write_raw(impl_->file.get(), path_, dataset, H5T_STD_I32LE, H5T_NATIVE_INT,
              {static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols())}, r.data());
}

void File::write_int_vector(const std::string& dataset, const std::vector<std::int64_t>& v,
                            bool wide) {
    static_assert(sizeof(long long) == sizeof(std::int64_t));
    write_raw(impl_->file.get(), path_, dataset, wide ? H5T_STD_I64LE : H5T_STD_I32LE,
              H5T_NATIVE_LLONG, {v.size()}, v.data());
}

void File::write_double_scalar(const std::string& dataset, double value) {
    write_raw(impl_->file.get(), path_, dataset, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value);
}

void File::write_int_scalar(const std::string& dataset, int value) {
    write_raw(impl_->file.get(), path_, dataset, H5T_STD_I32LE, H5T_NATIVE_INT, {}, &value);
}

void File::write_strings(const std::string& dataset, const std::vector<std::string>& values,
                         std::size_t fixed_size) {
    if (fixed_size == 0) {
        fixed_size = 1;
        for (const std::string& v : values) fixed_size = std::max(fixed_size, v.size());
    }
    Handle t = utf8_string_type(fixed_size);
    if (!t.valid()) throw IoError("cannot create a string type for '" + dataset + "'");
    std::vector<char> buffer(values.size() * fixed_size, '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i].copy(buffer.data() + i * fixed_size, std::min(fixed_size, values[i].size()));
    write_raw(impl_->file.get(), path_, dataset, t.get(), t.get(), {values.size()}, buffer.data());
}

void File::write_string_attribute(const std::string& object, const std::string& name,
                                  const std::string& value, bool variable_length) {
    Handle t = utf8_string_type(variable_length ? 0 : value.empty() ? 1 : value.size());
    Handle space = space_handle(H5Screate(H5S_SCALAR));
    if (!t.valid() || !space.valid())
        throw IoError("cannot prepare attribute '" + name + "' in '" + path_.string() + "'");
    Handle a = attr_handle(H5Acreate_by_name(impl_->file.get(), object.c_str(), name.c_str(),
                                             t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                             H5P_DEFAULT));
    std::string padded = value;
    if (padded.empty()) padded.push_back('\0');
    const char* vlen = value.c_str();
    const void* data = variable_length ? static_cast<const void*>(&vlen) : padded.data();
    if (!a.valid() || H5Awrite(a.get(), t.get(), data) < 0)
        throw IoError("cannot write attribute '" + name + "' in '" + path_.string() + "'");
}

void File::write_int_attribute(const std::string& object, const std::string& name, int value) {
    Handle space = space_handle(H5Screate(H5S_SCALAR));
    Handle a = attr_handle(H5Acreate_by_name(impl_->file.get(), object.c_str(), name.c_str(),
                                             H5T_STD_I32LE, space.get(), H5P_DEFAULT,
                                             H5P_DEFAULT, H5P_DEFAULT));
    if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_INT, &value) < 0)
        throw IoError("cannot write attribute '" + name + "' in '" + path_.string() + "'");
}

// ---- reading ------------------------------------------------------------------------------

namespace {

struct OpenDataset {
    Handle ds;
    Handle type;
    H5T_class_t cls = H5T_NO_CLASS;
    Dims dims;
};

OpenDataset open_dataset(const File& f, hid_t file, const std::string& dataset) {
    if (!f.exists(dataset)) f.fail(dataset, "missing");
    OpenDataset o;
    o.ds = dataset_handle(H5Dopen2(file, dataset.c_str(), H5P_DEFAULT));
    if (!o.ds.valid()) f.fail(dataset, "is not a dataset");
    o.type = type_handle(H5Dget_type(o.ds.get()));
    Handle space = space_handle(H5Dget_space(o.ds.get()));
    if (!o.type.valid() || !space.valid()) f.fail(dataset, "unreadable type or dataspace");
    o.cls = H5Tget_class(o.type.get());
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) f.fail(dataset, "unreadable dataspace");
    std::vector<hsize_t> hd(static_cast<std::size_t>(rank));
    if (rank > 0) H5Sget_simple_extent_dims(space.get(), hd.data(), nullptr);
    o.dims.assign(hd.begin(), hd.end());
    // A header may declare any extent (unwritten chunks cost no bytes): refuse before the
    // caller allocates for it (docs/hardening.md, "Resource limits").
    std::uint64_t count = 1;
    for (hsize_t d : hd) {
        if (d != 0 && count > static_cast<std::uint64_t>(limits::kMaxModelDatasetElements) / d)
            f.fail(dataset, "has shape " + dims_text(o.dims) + ", more than the limit of " +
                                std::to_string(limits::kMaxModelDatasetElements) + " elements");
        count *= d;
    }
    if (count > static_cast<std::uint64_t>(limits::kMaxModelDatasetElements))
        f.fail(dataset, "has shape " + dims_text(o.dims) + ", more than the limit of " +
                            std::to_string(limits::kMaxModelDatasetElements) + " elements");
    return o;
}

void expect_extent(const File& f, const std::string& dataset, const Dims& found,
                   std::vector<long> expected) {
    bool ok = found.size() == expected.size();
    for (std::size_t i = 0; ok && i < expected.size(); ++i)
        ok = expected[i] < 0 || found[i] == static_cast<std::size_t>(expected[i]);
    if (ok) return;
    std::string want;
    for (std::size_t i = 0; i < expected.size(); ++i)
        want += (i ? " x " : "") + (expected[i] < 0 ? std::string("any") : std::to_string(expected[i]));
    if (expected.empty()) want = "scalar";
    f.fail(dataset, "has shape " + dims_text(found) + ", expected " + want);
}

std::size_t element_count(const Dims& d) {
    std::size_t n = 1;
    for (std::size_t x : d) n *= x;
    return n;
}

void read_doubles(const File& f, const OpenDataset& o, const std::string& dataset, double* out) {
    if (o.cls != H5T_FLOAT) f.fail(dataset, "expected floating-point numbers");
    if (element_count(o.dims) == 0) return;
    if (H5Dread(o.ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
        f.fail(dataset, "cannot be read");
    const std::size_t n = element_count(o.dims);
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(out[i])) {
            const std::size_t cols = o.dims.size() == 2 ? o.dims[1] : 1;
            f.fail(dataset, o.dims.size() == 2
                                ? "non-finite value at row " + std::to_string(i / cols) +
                                      ", column " + std::to_string(i % cols)
                                : "non-finite value at index " + std::to_string(i));
        }
    }
}

void read_int64s(const File& f, const OpenDataset& o, const std::string& dataset,
                 std::int64_t* out) {
    if (o.cls != H5T_INTEGER) f.fail(dataset, "expected integers");
    if (element_count(o.dims) == 0) return;
    if (H5Dread(o.ds.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
        f.fail(dataset, "cannot be read");
}

bool is_scalar_like(const Dims& d) { return d.empty() || (d.size() == 1 && d[0] == 1); }

/// Reads n strings of `type` via `read(memtype, buffer)` (H5Dread or H5Aread).
template <class ReadFn>
std::vector<std::string> read_string_data(hid_t type, std::size_t n, ReadFn read,
                                          const std::function<void(const std::string&)>& fail,
                                          bool allow_variable) {
    if (H5Tget_class(type) != H5T_STRING) fail("expected strings");
    std::vector<std::string> out;
    if (n == 0) return out;
    const H5T_cset_t cset = H5Tget_cset(type);
    const htri_t variable = H5Tis_variable_str(type);
    if (variable < 0) fail("unreadable string type");
    if (variable > 0 && !allow_variable)
        fail("holds variable-length strings, which are not read from untrusted files (libhdf5 crashes on a "
             "damaged global heap); store fixed-length strings (numpy \"S\" arrays; drape's save_model does), "
             "or load with ModelLoadOptions::allow_variable_length_strings");
    if (variable > 0) {
        Handle mem = type_handle(H5Tcopy(H5T_C_S1));
        H5Tset_size(mem.get(), H5T_VARIABLE);
        H5Tset_cset(mem.get(), cset);
        std::vector<char*> ptrs(n, nullptr);
        // HDF5 allocates each string; a read that fails part way (a damaged file) leaves the
        // ones it made, and a throw below must not leak them either (found by fuzz_body_model).
        struct FreeStrings {
            std::vector<char*>& p;
            ~FreeStrings() {
                for (char* q : p)
                    if (q) H5free_memory(q);
            }
        } free_strings{ptrs};
        if (!read(mem.get(), ptrs.data())) fail("cannot be read");
        for (char* p : ptrs) out.emplace_back(p ? p : "");
    } else {
        const std::size_t size = H5Tget_size(type);
        if (size == 0) fail("unreadable string type");
        Handle mem = type_handle(H5Tcopy(H5T_C_S1));
        H5Tset_size(mem.get(), size);
        H5Tset_cset(mem.get(), cset);
        const H5T_str_t pad = H5Tget_strpad(type);
        H5Tset_strpad(mem.get(), pad);
        std::vector<char> buffer(n * size);
        if (!read(mem.get(), buffer.data())) fail("cannot be read");
        for (std::size_t i = 0; i < n; ++i)
            out.push_back(string_from_fixed(buffer.data() + i * size, size, pad));
    }
    return out;
}

}  // namespace

Dims File::dims(const std::string& dataset) const {
    return open_dataset(*this, impl_->file.get(), dataset).dims;
}

Eigen::MatrixXd File::read_matrix(const std::string& dataset, long rows, long cols) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    expect_extent(*this, dataset, o.dims, {rows, cols});
    RowMatrixXd r(static_cast<Eigen::Index>(o.dims[0]), static_cast<Eigen::Index>(o.dims[1]));
    read_doubles(*this, o, dataset, r.data());
    return r;
}

Eigen::VectorXd File::read_vector(const std::string& dataset, long size) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    expect_extent(*this, dataset, o.dims, {size});
    Eigen::VectorXd v(static_cast<Eigen::Index>(o.dims[0]));
    read_doubles(*this, o, dataset, v.data());
    return v;
}

Eigen::MatrixXi File::read_int_matrix(const std::string& dataset, long rows, long cols) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    expect_extent(*this, dataset, o.dims, {rows, cols});
    Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> r(
        static_cast<Eigen::Index>(o.dims[0]), static_cast<Eigen::Index>(o.dims[1]));
    read_int64s(*this, o, dataset, r.data());
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const std::int64_t x = r.data()[i];
        if (x < INT32_MIN || x > INT32_MAX)
            fail(dataset, "value " + std::to_string(x) + " does not fit in int32");
    }
    return r.cast<int>();
}

std::vector<std::int64_t> File::read_int_vector(const std::string& dataset, long size) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    expect_extent(*this, dataset, o.dims, {size});
    std::vector<std::int64_t> v(o.dims[0]);
    read_int64s(*this, o, dataset, v.data());
    return v;
}

double File::read_double_scalar(const std::string& dataset) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    if (!is_scalar_like(o.dims)) fail(dataset, "has shape " + dims_text(o.dims) + ", expected scalar");
    double x = 0;
    read_doubles(*this, o, dataset, &x);
    return x;
}

std::int64_t File::read_int_scalar(const std::string& dataset) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    if (!is_scalar_like(o.dims)) fail(dataset, "has shape " + dims_text(o.dims) + ", expected scalar");
    std::int64_t x = 0;
    read_int64s(*this, o, dataset, &x);
    return x;
}

std::vector<std::string> File::read_strings(const std::string& dataset, long size) const {
    const OpenDataset o = open_dataset(*this, impl_->file.get(), dataset);
    expect_extent(*this, dataset, o.dims, {size});
    const hid_t ds = o.ds.get();
    return read_string_data(
        o.type.get(), o.dims[0],
        [ds](hid_t mem, void* buf) { return H5Dread(ds, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0; },
        [&](const std::string& problem) { fail(dataset, problem); }, allow_variable_);
}

namespace {

struct OpenAttribute {
    Handle attr;
    Handle type;
    Dims dims;
};

OpenAttribute open_attribute(const File& f, hid_t file, const std::string& object,
                             const std::string& name) {
    const std::string label = object == "/" ? "/@" + name : object + "@" + name;
    if (!f.has_attribute(object, name)) f.fail(label, "missing attribute");
    OpenAttribute o;
    o.attr = attr_handle(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
    if (!o.attr.valid()) f.fail(label, "cannot open attribute");
    o.type = type_handle(H5Aget_type(o.attr.get()));
    Handle space = space_handle(H5Aget_space(o.attr.get()));
    if (!o.type.valid() || !space.valid()) f.fail(label, "unreadable attribute");
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) f.fail(label, "unreadable attribute");
    std::vector<hsize_t> hd(static_cast<std::size_t>(rank));
    if (rank > 0) H5Sget_simple_extent_dims(space.get(), hd.data(), nullptr);
    o.dims.assign(hd.begin(), hd.end());
    if (!is_scalar_like(o.dims)) f.fail(label, "has shape " + dims_text(o.dims) + ", expected scalar");
    return o;
}

}  // namespace

std::string File::read_string_attribute(const std::string& object, const std::string& name) const {
    const OpenAttribute o = open_attribute(*this, impl_->file.get(), object, name);
    const hid_t a = o.attr.get();
    const std::string label = object == "/" ? "/@" + name : object + "@" + name;
    return read_string_data(
        o.type.get(), 1, [a](hid_t mem, void* buf) { return H5Aread(a, mem, buf) >= 0; },
        [&](const std::string& problem) { fail(label, problem); }, allow_variable_)[0];
}

std::int64_t File::read_int_attribute(const std::string& object, const std::string& name) const {
    const OpenAttribute o = open_attribute(*this, impl_->file.get(), object, name);
    const std::string label = object == "/" ? "/@" + name : object + "@" + name;
    if (H5Tget_class(o.type.get()) != H5T_INTEGER) fail(label, "expected an integer");
    long long x = 0;
    if (H5Aread(o.attr.get(), H5T_NATIVE_LLONG, &x) < 0) fail(label, "cannot be read");
    return x;
}

}  // namespace drape::body::h5
