// drape_train_garment_types: prints libvision/src/garment_type_model_data.cpp, the learned
// garment-type decisions of the automatic segmentation (libvision/src/garment_type_model.hpp,
// docs/vision.md "Garment type from mask geometry").
//
//   drape_train_garment_types [--cache F.tsv] [--keep-rule dress|lower] DIR[:tune|:all] ... > libvision/src/garment_type_model_data.cpp
//
// Each DIR is a folder in the ../shared/data/photos layout; ":tune" keeps only the tuning
// part of the fixed split (names sorted ascending, 0-based even positions), ":all" (default)
// every photo. For each photo the automatic segmentation runs (its upper and lower regions,
// before typing), the features of garment_type_model.hpp are measured on them, and the
// hand labels give the truth: a dress when the labels hold a full garment, else the lower
// garment's class. --cache keeps the features per photo (re-runs skip the segmentation;
// delete the file after changing the segmentation or the features).
// Two multinomial logistic models (L2, standardised features) are fitted: dress vs two
// pieces and skirt/pants/shorts. Features are chosen among all subsets of up to three by
// 5-fold cross-validation (fold = sample index mod 5); the CV figures are printed to stderr
// and into the generated file's header.
#include "garment_type_model.hpp"
#include "photo_folder.hpp"

#include <drape/vision/classify_garment.hpp>
#include <drape/vision/garment_result.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/label_table.hpp>
#include <drape/vision/segmentation.hpp>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace drape::vision;
using drape::vision::detail::kDressFeatureCount;
using drape::vision::detail::kLowerFeatureCount;

namespace {

struct PhotoSample {
    std::string key;           // dir/name
    bool has_two_regions = false;
    bool true_dress = false;
    std::vector<double> dress;  // kDressFeatureCount
    bool has_lower = false;
    int true_lower = -1;        // GarmentType of the labelled lower garment, -1 none
    std::vector<double> lower;  // kLowerFeatureCount
    int rule_lower = -1;        // classify_lower on the automatic mask
};

/// The most frequent class id of a role (the lowest id on a tie); -1 if none.
int largest_class_of(const cv::Mat& labels, const LabelTable& t, LabelRole role) {
    std::map<int, long> count;
    for (size_t i = 0; i < labels.total(); ++i)
        if (t.role(labels.data[i]) == role) ++count[labels.data[i]];
    const auto best = std::max_element(count.begin(), count.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    return best == count.end() ? -1 : best->first;
}

cv::Mat role_mask_of(const cv::Mat& labels, const LabelTable& t, LabelRole role) {
    cv::Mat m = cv::Mat::zeros(labels.size(), CV_8UC1);
    for (size_t i = 0; i < labels.total(); ++i)
        if (t.role(labels.data[i]) == role) m.data[i] = 255;
    return m;
}

PhotoSample measure(const fs::path& dir, const std::string& name) {
    const LabelTable& table = LabelTable::fashionista();
    PhotoSample s;
    s.key = dir.filename().string() + "/" + name;
    const cv::Mat image = load_image(dir / "images" / (name + ".jpg"));
    const cv::Mat gt = load_label_map(dir / "labels" / (name + ".png"), "labels");
    const Joints j = drape::tools::read_joints(dir / "joints" / (name + ".json"));
    const double min_area = 0.002 * double(gt.total());
    // Truth (as eval-segment's parse of the hand labels).
    const cv::Mat gt_full = role_mask_of(gt, table, LabelRole::full_garment);
    const cv::Mat gt_lower = role_mask_of(gt, table, LabelRole::lower_garment);
    s.true_dress = cv::countNonZero(gt_full) >= min_area;
    if (!s.true_dress && cv::countNonZero(gt_lower) >= min_area)
        s.true_lower = int(garment_type_of_class(gt_lower, largest_class_of(gt, table, LabelRole::lower_garment),
                                                 table, j, sleeve_hiding_mask(gt, table)));
    // The automatic regions, typed as two pieces (the hint only forces the typing step).
    SegmentationOptions o;
    o.hint = GarmentType::t_shirt;
    Segmentation seg;
    segment_automatic(image, j, o, seg);
    const cv::Mat upper = seg.labels == label_id_of(GarmentType::t_shirt);
    const cv::Mat lower = (seg.labels == label_id_of(GarmentType::skirt)) |
                          (seg.labels == label_id_of(GarmentType::pants)) |
                          (seg.labels == label_id_of(GarmentType::shorts));
    const cv::Mat hair = seg.labels == (table.hair_id() >= 0 ? table.hair_id() : 19);
    const bool has_upper = cv::countNonZero(upper) >= min_area;
    s.has_lower = cv::countNonZero(lower) >= min_area;
    s.has_two_regions = has_upper && s.has_lower;
    if (s.has_two_regions) {
        const auto f = detail::dress_features(image, upper, lower, j);
        s.dress.assign(f.begin(), f.end());
    }
    if (s.has_lower) {
        const auto f = detail::lower_features(image, lower, j, hair);
        s.lower.assign(f.begin(), f.end());
        s.rule_lower = int(classify_lower(measure_shape_cues(lower, j, hair)));
    }
    return s;
}

void write_cache_line(std::ostream& out, const PhotoSample& s) {
    out << s.key << '\t' << s.has_two_regions << '\t' << s.true_dress << '\t' << s.has_lower << '\t'
        << s.true_lower << '\t' << s.rule_lower;
    out << std::setprecision(17);
    for (int k = 0; k < kDressFeatureCount; ++k) out << '\t' << (s.has_two_regions ? s.dress[size_t(k)] : 0.0);
    for (int k = 0; k < kLowerFeatureCount; ++k) out << '\t' << (s.has_lower ? s.lower[size_t(k)] : 0.0);
    out << '\n';
}

bool read_cache_line(const std::string& line, PhotoSample& s) {
    std::stringstream ss(line);
    if (!std::getline(ss, s.key, '\t')) return false;
    ss >> s.has_two_regions >> s.true_dress >> s.has_lower >> s.true_lower >> s.rule_lower;
    s.dress.assign(kDressFeatureCount, 0.0);
    s.lower.assign(kLowerFeatureCount, 0.0);
    for (auto& v : s.dress) ss >> v;
    for (auto& v : s.lower) ss >> v;
    return bool(ss);
}

// --- multinomial logistic regression ---------------------------------------------------

struct Fit {
    std::vector<int> features;
    Eigen::VectorXd mean, scale;
    Eigen::MatrixXd w;  // classes x features
    Eigen::VectorXd b;
    double l2 = 0;
};

/// L2 weights (on the mean log-loss, standardised features) tried by the selection.
constexpr double kL2Choices[] = {0.003, 0.03, 0.3};

Fit fit(const std::vector<std::vector<double>>& x, const std::vector<int>& y, int classes,
        const std::vector<int>& features, const std::vector<size_t>& rows, double l2) {
    Fit m;
    m.l2 = l2;
    m.features = features;
    const int d = int(features.size());
    const double n = double(rows.size());
    m.mean = Eigen::VectorXd::Zero(d);
    m.scale = Eigen::VectorXd::Ones(d);
    Eigen::MatrixXd X(rows.size(), d);
    for (size_t r = 0; r < rows.size(); ++r)
        for (int k = 0; k < d; ++k) X(long(r), k) = x[rows[r]][size_t(features[size_t(k)])];
    for (int k = 0; k < d; ++k) {
        m.mean(k) = X.col(k).mean();
        const double var = (X.col(k).array() - m.mean(k)).square().mean();
        m.scale(k) = var > 1e-12 ? std::sqrt(var) : 1.0;
        X.col(k) = (X.col(k).array() - m.mean(k)) / m.scale(k);
    }
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(long(rows.size()), classes);
    for (size_t r = 0; r < rows.size(); ++r) Y(long(r), y[rows[r]]) = 1;
    m.w = Eigen::MatrixXd::Zero(classes, d);
    m.b = Eigen::VectorXd::Zero(classes);
    for (int it = 0; it < 2000; ++it) {
        Eigen::MatrixXd S = (X * m.w.transpose()).rowwise() + m.b.transpose();
        for (long r = 0; r < S.rows(); ++r) {
            const double top = S.row(r).maxCoeff();
            S.row(r) = (S.row(r).array() - top).exp();
            S.row(r) /= S.row(r).sum();
        }
        const Eigen::MatrixXd G = S - Y;
        m.w -= 0.5 * ((G.transpose() * X) / n + l2 * m.w);
        m.b -= 0.5 * (G.colwise().sum().transpose() / n);
    }
    return m;
}

Eigen::VectorXd predict(const Fit& m, const std::vector<double>& x) {
    Eigen::VectorXd z(m.features.size());
    for (size_t k = 0; k < m.features.size(); ++k)
        z(long(k)) = (x[size_t(m.features[k])] - m.mean(long(k))) / m.scale(long(k));
    Eigen::VectorXd s = m.w * z + m.b;
    s = (s.array() - s.maxCoeff()).exp();
    return s / s.sum();
}

/// Cost of a prediction as eval-segment counts it. Dress model: class 0 = dress; a
/// two-piece read as a dress costs 2 garments, a dress read as two pieces 1.
using Cost = double (*)(int truth, const Eigen::VectorXd& p);
double dress_cost(int truth, const Eigen::VectorXd& p) {
    const bool dress = p(0) > detail::kDressDecision;
    return truth == 0 ? (dress ? 0 : 1) : (dress ? 2 : 0);
}
double lower_cost(int truth, const Eigen::VectorXd& p) {
    long best;
    p.maxCoeff(&best);
    return best == truth ? 0 : 1;
}

double cv_cost(const std::vector<std::vector<double>>& x, const std::vector<int>& y, int classes,
               const std::vector<int>& features, double l2, Cost cost,
               std::vector<double>* per_sample = nullptr) {
    if (per_sample) per_sample->assign(x.size(), 0.0);
    constexpr size_t kFolds = 5;
    double total = 0;
    for (size_t fold = 0; fold < kFolds; ++fold) {
        std::vector<size_t> train;
        for (size_t r = 0; r < x.size(); ++r)
            if (r % kFolds != fold) train.push_back(r);
        const Fit m = fit(x, y, classes, features, train, l2);
        for (size_t r = fold; r < x.size(); r += kFolds) {
            const double c = cost(y[r], predict(m, x[r]));
            total += c;
            if (per_sample) (*per_sample)[r] = c;
        }
    }
    return total;
}

/// The subset of at most kMaxFeatures features with the lowest CV cost (ties: fewer
/// features, then the earlier subset); each subset size's best is logged.
constexpr int kMaxFeatures = 3;
std::vector<int> select_features(const std::vector<std::vector<double>>& x, const std::vector<int>& y,
                                 int classes, int candidates, Cost cost, const char* const* names,
                                 double& best_cost, double& best_l2, std::ostringstream& log) {
    std::vector<int> best;
    best_cost = 1e300;
    std::vector<std::vector<int>> subsets;
    for (int a = 0; a < candidates; ++a) {
        subsets.push_back({a});
        for (int b = a + 1; b < candidates; ++b) {
            subsets.push_back({a, b});
            if (kMaxFeatures >= 3)
                for (int c = b + 1; c < candidates; ++c) subsets.push_back({a, b, c});
        }
    }
    std::stable_sort(subsets.begin(), subsets.end(),
                     [](const auto& p, const auto& q) { return p.size() < q.size(); });
    size_t size = 0;
    double size_best = 1e300;
    std::vector<int> size_arg;
    double size_l2 = 0;
    auto flush = [&] {
        if (size_arg.empty()) return;
        log << "//   best of " << size << ":";
        for (int k : size_arg) log << " " << names[k];
        log << ", L2 " << size_l2 << " (CV cost " << size_best << ")\n";
    };
    for (const auto& sub : subsets) {
        if (sub.size() != size) {
            flush();
            size = sub.size();
            size_best = 1e300;
            size_arg.clear();
        }
        for (double l2 : kL2Choices) {
            const double c = cv_cost(x, y, classes, sub, l2, cost);
            if (c < size_best - 1e-9) {
                size_best = c;
                size_arg = sub;
                size_l2 = l2;
            }
            if (c < best_cost - 1e-9) {
                best_cost = c;
                best = sub;
                best_l2 = l2;
            }
        }
    }
    flush();
    return best;
}

void print_model(std::ostream& out, const char* name, const Fit& m, const std::vector<GarmentType>& classes) {
    out << std::setprecision(10);
    out << "const LinearTypeModel " << name << "{\n    {";
    for (size_t c = 0; c < classes.size(); ++c)
        out << "GarmentType::" << (classes[c] == GarmentType::dress ? "dress"
                                   : classes[c] == GarmentType::t_shirt ? "t_shirt"
                                   : classes[c] == GarmentType::skirt ? "skirt"
                                   : classes[c] == GarmentType::pants ? "pants" : "shorts")
            << (c + 1 < classes.size() ? ", " : "");
    out << "},\n    {";
    for (size_t k = 0; k < m.features.size(); ++k) out << m.features[k] << (k + 1 < m.features.size() ? ", " : "");
    out << "},\n    {";
    for (long k = 0; k < m.mean.size(); ++k) out << m.mean(k) << (k + 1 < m.mean.size() ? ", " : "");
    out << "},\n    {";
    for (long k = 0; k < m.scale.size(); ++k) out << m.scale(k) << (k + 1 < m.scale.size() ? ", " : "");
    out << "},\n    {";
    for (long c = 0; c < m.w.rows(); ++c) {
        out << "{";
        for (long k = 0; k < m.w.cols(); ++k) out << m.w(c, k) << (k + 1 < m.w.cols() ? ", " : "");
        out << "}" << (c + 1 < m.w.rows() ? ", " : "");
    }
    out << "},\n    {";
    for (long c = 0; c < m.b.size(); ++c) out << m.b(c) << (c + 1 < m.b.size() ? ", " : "");
    out << "}};\n";
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string cache_path;
        bool keep_dress = false, keep_lower = false;
        std::vector<std::string> sources;
        std::vector<std::pair<fs::path, std::string>> photos;
        for (int a = 1; a < argc; ++a) {
            std::string arg = argv[a];
            if (arg == "--keep-rule" && a + 1 < argc) {
                const std::string what = argv[++a];
                if (what == "dress") keep_dress = true;
                else if (what == "lower") keep_lower = true;
                else throw std::runtime_error("--keep-rule takes dress or lower, not '" + what + "'");
                continue;
            }
            if (arg == "--cache" && a + 1 < argc) {
                cache_path = argv[++a];
                continue;
            }
            std::string part = "all";
            if (const auto colon = arg.rfind(':'); colon != std::string::npos && colon > 1) {
                part = arg.substr(colon + 1);
                arg = arg.substr(0, colon);
            }
            if (part != "tune" && part != "all") throw std::runtime_error("part must be tune or all: " + part);
            const auto names = drape::tools::photo_names(arg, part == "tune");
            for (const auto& n : names) photos.emplace_back(fs::path(arg), n);
            sources.push_back(fs::path(arg).filename().string() + " (" + part + ": " +
                              std::to_string(names.size()) + " photos)");
        }
        if (photos.empty()) {
            std::cerr << "usage: drape_train_garment_types [--cache F.tsv] [--keep-rule dress|lower] DIR[:tune|:all] ... > garment_type_model_data.cpp\n";
            return 2;
        }
        std::map<std::string, PhotoSample> cached;
        if (!cache_path.empty()) {
            std::ifstream in(cache_path);
            std::string line;
            while (std::getline(in, line)) {
                PhotoSample s;
                if (read_cache_line(line, s)) cached[s.key] = s;
            }
        }
        std::vector<PhotoSample> samples;
        for (const auto& [dir, name] : photos) {
            const std::string key = dir.filename().string() + "/" + name;
            if (auto it = cached.find(key); it != cached.end()) {
                samples.push_back(it->second);
                continue;
            }
            std::cerr << "segmenting " << key << "\n";
            samples.push_back(measure(dir, name));
            if (!cache_path.empty()) {
                std::ofstream out(cache_path, std::ios::app);
                write_cache_line(out, samples.back());
            }
        }
        // Dress vs two pieces: class 0 dress, 1 two pieces.
        std::vector<std::vector<double>> xd, xl;
        std::vector<int> yd, yl;
        std::vector<int> rule_lower;
        for (const auto& s : samples) {
            if (s.has_two_regions) {
                xd.push_back(s.dress);
                yd.push_back(s.true_dress ? 0 : 1);
            }
            if (s.has_lower && s.true_lower >= 0) {
                xl.push_back(s.lower);
                yl.push_back(s.true_lower == int(GarmentType::skirt) ? 0 : s.true_lower == int(GarmentType::pants) ? 1 : 2);
                rule_lower.push_back(s.rule_lower == int(GarmentType::skirt) ? 0 : s.rule_lower == int(GarmentType::pants) ? 1 : 2);
            }
        }
        std::ostringstream log;
        double dress_cv = 0, lower_cv = 0, dress_l2 = 0, lower_l2 = 0;
        log << "// Dress vs two pieces: " << xd.size() << " photos with both regions ("
            << std::count(yd.begin(), yd.end(), 0) << " dresses); subsets of <= 3 features x L2,\n"
            << "// 5-fold CV cost (garments wrong as eval-segment counts them: 2 per two-piece read as a dress):\n";
        const auto dress_features = select_features(xd, yd, 2, kDressFeatureCount, dress_cost,
                                                   detail::kDressFeatureNames.data(), dress_cv, dress_l2, log);
        std::vector<double> dress_each, lower_each;
        cv_cost(xd, yd, 2, dress_features, dress_l2, dress_cost, &dress_each);
        std::vector<double> dress_rule(xd.size());
        for (size_t r = 0; r < xd.size(); ++r)
            dress_rule[r] = yd[r] == 0 ? (xd[r][0] > 0.75 ? 0 : 1) : (xd[r][0] > 0.75 ? 2 : 0);
        log << "// Skirt / pants / shorts: " << xl.size() << " labelled lower garments with an automatic lower region:\n";
        const auto lower_features = select_features(xl, yl, 3, kLowerFeatureCount, lower_cost,
                                                   detail::kLowerFeatureNames.data(), lower_cv, lower_l2, log);
        cv_cost(xl, yl, 3, lower_features, lower_l2, lower_cost, &lower_each);
        std::vector<double> lower_rule(xl.size());
        for (size_t r = 0; r < xl.size(); ++r) lower_rule[r] = rule_lower[r] == yl[r] ? 0 : 1;
        // The CV wins and losses against the rule on the same samples, and a paired sign test
        // (significant when fixed - broken > 2 sqrt(fixed + broken), ~95 %); --keep-rule
        // PART writes no model for that part (the rule decides).
        auto compare = [&](const char* what, const std::vector<double>& model, const std::vector<double>& rule,
                           bool keep_rule) {
            double fixed = 0, broken = 0, m = 0, r = 0;
            for (size_t i = 0; i < model.size(); ++i) {
                fixed += std::max(0.0, rule[i] - model[i]);
                broken += std::max(0.0, model[i] - rule[i]);
                m += model[i];
                r += rule[i];
            }
            const bool significant = fixed - broken > 2.0 * std::sqrt(fixed + broken);
            log << "// " << what << ": CV cost " << m << " vs the rule's " << r << " (fixed " << fixed << ", broken "
                << broken << (significant ? ", significant" : ", not significant") << ") -> "
                << (keep_rule ? "rule kept (--keep-rule)" : "model") << "\n";
            return !keep_rule;
        };
        const bool use_dress = compare("dress decision (rule: similarity_all > 0.75)", dress_each, dress_rule, keep_dress);
        const bool use_lower = compare("lower type (rule: classify_lower)", lower_each, lower_rule, keep_lower);
        std::vector<size_t> all_d(xd.size()), all_l(xl.size());
        for (size_t r = 0; r < all_d.size(); ++r) all_d[r] = r;
        for (size_t r = 0; r < all_l.size(); ++r) all_l[r] = r;
        const Fit md = fit(xd, yd, 2, dress_features, all_d, dress_l2);
        const Fit ml = fit(xl, yl, 3, lower_features, all_l, lower_l2);
        std::cerr << log.str();
        std::ostringstream prov;
        for (size_t i = 0; i < sources.size(); ++i) prov << (i ? ", " : "") << sources[i];
        std::cout << "// Generated by tools/train_garment_types.cpp (drape_train_garment_types); do not edit.\n"
                     "// Trained on the automatic segmentation's regions and the hand labels of:\n//   "
                  << prov.str() << "\n" << log.str()
                  << "// Regenerate: docs/vision.md, \"Garment type from mask geometry\".\n"
                     "#include \"garment_type_model.hpp\"\n\n"
                     "namespace drape::vision::detail {\n\n"
                     "const char* const kTypeModelProvenance = \"drape_train_garment_types: "
                  << prov.str() << "\";\n";
        if (use_dress) print_model(std::cout, "kDressModel", md, {GarmentType::dress, GarmentType::t_shirt});
        else std::cout << "const LinearTypeModel kDressModel{};  // rule kept\n";
        if (use_lower) print_model(std::cout, "kLowerModel", ml, {GarmentType::skirt, GarmentType::pants, GarmentType::shorts});
        else std::cout << "const LinearTypeModel kLowerModel{};  // rule kept\n";
        std::cout << "\n}  // namespace drape::vision::detail\n";
    } catch (const std::exception& e) {
        std::cerr << "drape_train_garment_types: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
