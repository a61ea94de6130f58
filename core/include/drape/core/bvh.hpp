// The one spatial index of Drape: a bounding-volume hierarchy over axis-aligned boxes
// (triangles, edges, points, or any item with a box).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <vector>

namespace drape::core {

using Box3 = Eigen::AlignedBox3d;

/// Squared distance from `p` to the closed box `b` (0 inside), computed per axis as
/// max(lo − p, p − hi, 0).
double squared_distance(const Box3& b, const Eigen::Vector3d& p);

/// A bounding-volume hierarchy over n items, each with a box: built top-down by a median
/// split (std::nth_element, ties by item id) along the longest axis of the items' split
/// points, leaves of at most `leaf_size` items. The tree's shape depends only on the split
/// points, so refit() keeps it while the boxes move (a deforming body between time steps).
///
/// Node layout: a node's first child follows it, so traversals are depth-first over a flat
/// array. All queries are const and may run from several threads at once.
class Bvh {
public:
    Bvh() = default;

    /// \param boxes one box per item (item id = index), any frame and unit.
    /// \param leaf_size the maximum number of items per leaf, >= 1.
    /// The split points are the box centres.
    /// \throw drape::InvalidInput if leaf_size < 1.
    explicit Bvh(std::vector<Box3> boxes, int leaf_size = 4);

    /// As above with explicit split points (#items, one per item), e.g. triangle centroids.
    /// \throw drape::InvalidInput if leaf_size < 1 or the counts differ.
    Bvh(std::vector<Box3> boxes, const std::vector<Eigen::Vector3d>& split_points,
        int leaf_size);

    /// Boxes of the triangles of a mesh, grown by `inflate` on every side.
    /// \param V #V x 3; \param F #F x 3 rows of V. \pre indices in range (not checked).
    static std::vector<Box3> triangle_boxes(const Eigen::Ref<const Eigen::MatrixXd>& V,
                                            const Eigen::Ref<const Eigen::MatrixXi>& F,
                                            double inflate = 0);

    /// New boxes for the same items (same count), same tree; node boxes recomputed bottom-up.
    /// \throw drape::InvalidInput if the count differs.
    void refit(std::vector<Box3> boxes);

    int size() const { return static_cast<int>(boxes_.size()); }
    const Box3& box(int id) const { return boxes_[static_cast<std::size_t>(id)]; }

    /// Calls visit(id) for every item whose box satisfies overlaps(box), testing node boxes
    /// first to prune. Visiting order: depth-first, second child first. Callers that need an
    /// order sort what they collect.
    template <class Overlaps, class Visit>
    void traverse(Overlaps&& overlaps, Visit&& visit) const;

    /// The ids of the items whose box intersects `query` (closed boxes), increasing.
    std::vector<int> overlapping(const Box3& query) const;

    /// Nearest-item search from `p`: visits leaves nearer child first and calls
    /// leaf(id, best_squared_distance) for every item of a leaf whose box is closer than the
    /// current best; `leaf` lowers best_squared_distance (a double&) when it finds a closer
    /// point. Start best_squared_distance at the search radius squared (or infinity).
    template <class Leaf>
    void nearest(const Eigen::Vector3d& p, double& best_squared_distance, Leaf&& leaf) const;

private:
    // The depth-first traversal stack, starting at the root (unless the tree is empty). The
    // tree's depth is below 64 for any item count an int can hold, so two pushes per level
    // always fit; a push that would not is dropped rather than overflow.
    class Stack {
    public:
        explicit Stack(bool empty_tree) : top_(empty_tree ? 0 : 1) {}
        bool empty() const { return top_ == 0; }
        int pop() { return items_[static_cast<std::size_t>(--top_)]; }
        void push_two(int first, int second) {
            if (top_ + 2 > static_cast<int>(items_.size())) return;
            items_[static_cast<std::size_t>(top_++)] = first;
            items_[static_cast<std::size_t>(top_++)] = second;
        }

    private:
        std::array<int, 128> items_{};  // items_[0] = 0: the root
        int top_;
    };

    struct Node {
        Box3 box;
        int second = -1;  ///< the second child; -1 for a leaf (the first child is index + 1)
        int begin = 0, end = 0;  ///< leaf: items order_[begin, end)
    };
    int build(const std::vector<Eigen::Vector3d>& split, int begin, int end);

    std::vector<Box3> boxes_;
    std::vector<int> order_;
    std::vector<Node> nodes_;
    int leaf_size_ = 4;
};

// ---- templates -------------------------------------------------------------------------

template <class Overlaps, class Visit>
void Bvh::traverse(Overlaps&& overlaps, Visit&& visit) const {
    Stack stack(nodes_.empty());
    while (!stack.empty()) {
        const int index = stack.pop();
        const Node& node = nodes_[static_cast<std::size_t>(index)];
        if (!overlaps(node.box)) continue;
        if (node.second < 0) {
            for (int i = node.begin; i < node.end; ++i) {
                const int id = order_[static_cast<std::size_t>(i)];
                if (overlaps(boxes_[static_cast<std::size_t>(id)])) visit(id);
            }
        } else {
            stack.push_two(index + 1, node.second);
        }
    }
}

template <class Leaf>
void Bvh::nearest(const Eigen::Vector3d& p, double& best, Leaf&& leaf) const {
    Stack stack(nodes_.empty());
    while (!stack.empty()) {
        const int index = stack.pop();
        const Node& node = nodes_[static_cast<std::size_t>(index)];
        if (squared_distance(node.box, p) >= best) continue;
        if (node.second < 0) {
            for (int i = node.begin; i < node.end; ++i) {
                const int id = order_[static_cast<std::size_t>(i)];
                if (node.end - node.begin == 1 ||
                    squared_distance(boxes_[static_cast<std::size_t>(id)], p) < best)
                    leaf(id, best);
            }
            continue;
        }
        const int first = index + 1;
        const double d_first = squared_distance(nodes_[static_cast<std::size_t>(first)].box, p);
        const double d_second = squared_distance(nodes_[static_cast<std::size_t>(node.second)].box, p);
        if (d_first < d_second)  // the nearer child is popped first
            stack.push_two(node.second, first);
        else
            stack.push_two(first, node.second);
    }
}

}  // namespace drape::core
