#include <drape/core/bvh.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>

namespace drape::core {

double squared_distance(const Box3& b, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = (b.min() - p).cwiseMax(p - b.max()).cwiseMax(0.0);
    return d.squaredNorm();
}

Bvh::Bvh(std::vector<Box3> boxes, int leaf_size) : boxes_(std::move(boxes)), leaf_size_(leaf_size) {
    require(leaf_size >= 1, "Bvh: leaf_size = ", leaf_size, " must be >= 1");
    std::vector<Eigen::Vector3d> split(boxes_.size());
    for (std::size_t i = 0; i < boxes_.size(); ++i) split[i] = boxes_[i].center();
    order_.resize(boxes_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
    nodes_.reserve(2 * boxes_.size());
    if (!boxes_.empty()) build(split, 0, static_cast<int>(order_.size()));
}

Bvh::Bvh(std::vector<Box3> boxes, const std::vector<Eigen::Vector3d>& split_points, int leaf_size)
    : boxes_(std::move(boxes)), leaf_size_(leaf_size) {
    require(leaf_size >= 1, "Bvh: leaf_size = ", leaf_size, " must be >= 1");
    require(split_points.size() == boxes_.size(), "Bvh: ", split_points.size(),
            " split points for ", boxes_.size(), " boxes");
    order_.resize(boxes_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
    nodes_.reserve(2 * boxes_.size());
    if (!boxes_.empty()) build(split_points, 0, static_cast<int>(order_.size()));
}

std::vector<Box3> Bvh::triangle_boxes(const Eigen::Ref<const Eigen::MatrixXd>& V,
                                      const Eigen::Ref<const Eigen::MatrixXi>& F, double inflate) {
    std::vector<Box3> boxes(static_cast<std::size_t>(F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        Box3 b(Eigen::Vector3d(V.row(F(f, 0)).transpose()));
        b.extend(Eigen::Vector3d(V.row(F(f, 1)).transpose()));
        b.extend(Eigen::Vector3d(V.row(F(f, 2)).transpose()));
        if (inflate > 0) {
            b.min().array() -= inflate;
            b.max().array() += inflate;
        }
        boxes[static_cast<std::size_t>(f)] = b;
    }
    return boxes;
}

int Bvh::build(const std::vector<Eigen::Vector3d>& split, int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box3 box, centroids;
    for (int i = begin; i < end; ++i) {
        const auto id = static_cast<std::size_t>(order_[static_cast<std::size_t>(i)]);
        box.extend(boxes_[id]);
        centroids.extend(split[id]);
    }
    Node& node = nodes_[static_cast<std::size_t>(index)];
    node.box = box;
    node.begin = begin;
    node.end = end;
    if (end - begin <= leaf_size_) return index;
    int axis = 0;
    centroids.sizes().maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) {
                         const double ca = split[static_cast<std::size_t>(a)](axis),
                                      cb = split[static_cast<std::size_t>(b)](axis);
                         return ca < cb || (ca == cb && a < b);
                     });
    build(split, begin, mid);
    const int second = build(split, mid, end);
    nodes_[static_cast<std::size_t>(index)].second = second;
    return index;
}

void Bvh::refit(std::vector<Box3> boxes) {
    require(boxes.size() == boxes_.size(), "Bvh::refit: ", boxes.size(), " boxes, expected ",
            boxes_.size());
    boxes_ = std::move(boxes);
    // Children follow their parent in nodes_, so a backward sweep sees children first.
    for (std::size_t i = nodes_.size(); i-- > 0;) {
        Node& n = nodes_[i];
        if (n.second < 0) {
            Box3 b;
            for (int k = n.begin; k < n.end; ++k)
                b.extend(boxes_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
            n.box = b;
        } else {
            n.box = nodes_[i + 1].box;
            n.box.extend(nodes_[static_cast<std::size_t>(n.second)].box);
        }
    }
}

std::vector<int> Bvh::overlapping(const Box3& query) const {
    std::vector<int> hits;
    traverse([&](const Box3& b) { return b.intersects(query); }, [&](int id) { hits.push_back(id); });
    std::sort(hits.begin(), hits.end());
    return hits;
}

}  // namespace drape::core
