#include "ansur_records.hpp"

#include <drape/core/errors.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

namespace drape::test {
namespace {

using drape::body::Gender;
using drape::body::Semantic;

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        if (comma == std::string_view::npos) {
            fields.push_back(line.substr(start));
            return fields;
        }
        fields.push_back(line.substr(start, comma - start));
        start = comma + 1;
    }
}

// The columns read, in this order: the id, the ten semantic sources, the two proxy inputs.
// Semantic sources are in Semantic order, with muscle (no column) as an empty name.
constexpr std::array<std::string_view, 13> kColumns = {
    "subjectid",          "stature",
    "weightkg",           "",
    "chestcircumference", "waistcircumference",
    "buttockcircumference", "thighcircumference",
    "calfcircumference",  "acromialheight",
    "crotchheight",       "bicepscircumferenceflexed",
    "forearmcircumferenceflexed",
};

// Reads one gender's CSV. The files are CRLF, comma-separated, unquoted; the male file is
// Latin-1 with one non-ASCII byte in a column we do not read, so bytes are taken as they are.
std::vector<AnsurRecord> read_csv(const std::filesystem::path& path, Gender gender) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw drape::IoError("cannot open ANSUR II file '" + path.string() + "'");

    std::string line;
    if (!std::getline(in, line)) throw drape::IoError("empty ANSUR II file '" + path.string() + "'");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string_view> header = split(line);

    std::array<std::size_t, kColumns.size()> index{};
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
        if (kColumns[c].empty()) continue;
        const auto it = std::find_if(header.begin(), header.end(), [&](std::string_view h) {
            return lower(h) == kColumns[c];
        });
        drape::require(it != header.end(), "ANSUR II file '", path.string(), "' has no column '",
                       kColumns[c], "'");
        index[c] = static_cast<std::size_t>(it - header.begin());
    }

    std::vector<AnsurRecord> records;
    int line_number = 1;
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        const std::vector<std::string_view> fields = split(line);
        drape::require(fields.size() == header.size(), "ANSUR II file '", path.string(), "' line ",
                       line_number, " has ", fields.size(), " fields, expected ", header.size());
        std::array<long, kColumns.size()> v{};
        for (std::size_t c = 0; c < kColumns.size(); ++c) {
            if (kColumns[c].empty()) continue;
            const std::string_view f = fields[index[c]];
            const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v[c]);
            drape::require(ec == std::errc() && end == f.data() + f.size(), "ANSUR II file '",
                           path.string(), "' line ", line_number, " column '", kColumns[c],
                           "' = '", f, "' is not an integer");
        }
        AnsurRecord r;
        r.subject_id = static_cast<int>(v[0]);
        r.gender = gender;
        for (int s = 0; s < drape::body::kSemanticCount; ++s) {
            const double raw = static_cast<double>(v[static_cast<std::size_t>(s) + 1]);
            r.values[s] = s == static_cast<int>(Semantic::weight_kg) ? raw / 10.0 : raw / 1000.0;
        }
        r.values[static_cast<int>(Semantic::muscle)] = 0.5;  // set once the proxy is fitted
        r.flexed_arm_girth_m = static_cast<double>(v[11] + v[12]) / 1000.0;
        records.push_back(r);
    }
    std::sort(records.begin(), records.end(),
              [](const AnsurRecord& a, const AnsurRecord& b) { return a.subject_id < b.subject_id; });
    return records;
}

}  // namespace

double AnsurMuscleProxy::muscle(double flexed_arm_girth_m, double height_m, double weight_kg,
                                double waist_girth_m) const {
    const double predicted = coefficients[0] + coefficients[1] * height_m +
                             coefficients[2] * weight_kg + coefficients[3] * waist_girth_m;
    const double z = (flexed_arm_girth_m - predicted) / residual_sd_m;
    return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

AnsurMuscleProxy fit_muscle_proxy(const std::vector<AnsurRecord>& records) {
    const auto n = static_cast<Eigen::Index>(records.size());
    drape::require(n >= 10, "fit_muscle_proxy: records.size() = ", n, " (need at least 10)");
    Eigen::MatrixXd X(n, 4);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const AnsurRecord& r = records[static_cast<std::size_t>(i)];
        X(i, 0) = 1.0;
        X(i, 1) = r.values[static_cast<int>(Semantic::height_m)];
        X(i, 2) = r.values[static_cast<int>(Semantic::weight_kg)];
        X(i, 3) = r.values[static_cast<int>(Semantic::waist_girth_m)];
        y[i] = r.flexed_arm_girth_m;
    }
    AnsurMuscleProxy proxy;
    proxy.coefficients = X.colPivHouseholderQr().solve(y);
    const double rss = (y - X * proxy.coefficients).squaredNorm();
    proxy.residual_sd_m = std::sqrt(rss / static_cast<double>(n - 4));
    proxy.sample_count = static_cast<int>(n);
    return proxy;
}

std::filesystem::path ansur_csv_path(const std::filesystem::path& anthropometry_dir,
                                     drape::body::Gender gender) {
    return anthropometry_dir / (gender == Gender::female ? "ANSUR_II_FEMALE_Public.csv"
                                                         : "ANSUR_II_MALE_Public.csv");
}

std::vector<AnsurRecord> load_ansur_all(const std::filesystem::path& anthropometry_dir,
                                        std::vector<AnsurMuscleProxy>* proxies) {
    std::vector<AnsurRecord> all;
    if (proxies) proxies->clear();
    for (const Gender g : {Gender::female, Gender::male}) {
        std::vector<AnsurRecord> records = read_csv(ansur_csv_path(anthropometry_dir, g), g);
        const AnsurMuscleProxy proxy = fit_muscle_proxy(records);
        for (AnsurRecord& r : records) {
            r.values[static_cast<int>(Semantic::muscle)] =
                proxy.muscle(r.flexed_arm_girth_m, r.values[static_cast<int>(Semantic::height_m)],
                             r.values[static_cast<int>(Semantic::weight_kg)],
                             r.values[static_cast<int>(Semantic::waist_girth_m)]);
        }
        if (proxies) proxies->push_back(proxy);
        all.insert(all.end(), records.begin(), records.end());
    }
    return all;
}

std::vector<AnsurRecord> load_ansur_sample(const std::filesystem::path& anthropometry_dir,
                                           int per_gender) {
    const std::vector<AnsurRecord> all = load_ansur_all(anthropometry_dir);
    std::vector<AnsurRecord> sample;
    for (const Gender g : {Gender::female, Gender::male}) {
        std::vector<AnsurRecord> of_gender;
        for (const AnsurRecord& r : all)
            if (r.gender == g) of_gender.push_back(r);
        const auto n = static_cast<long long>(of_gender.size());
        drape::require(per_gender >= 1 && per_gender <= n, "load_ansur_sample: per_gender = ",
                       per_gender, " is not in [1, ", n, "] for ",
                       g == Gender::female ? "female" : "male");
        for (long long i = 0; i < per_gender; ++i)
            sample.push_back(of_gender[static_cast<std::size_t>(i * n / per_gender)]);
    }
    return sample;
}

}  // namespace drape::test
