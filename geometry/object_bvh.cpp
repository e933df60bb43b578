#include <refract/geometry/object_bvh.h>

#include <algorithm>

namespace refract {

namespace {

Bounds padded(const Bounds& b) {
    const double pad = 1e-9 * ((b.hi - b.lo).cwiseAbs().maxCoeff() + b.lo.cwiseAbs().maxCoeff() +
                               b.hi.cwiseAbs().maxCoeff()) + 1e-300;
    return {b.lo.array() - pad, b.hi.array() + pad};
}

}  // namespace

ObjectBvh::ObjectBvh(const std::vector<std::optional<Bounds>>& boxes) {
    std::vector<Bounds> padded_boxes(boxes.size());
    for (size_t k = 0; k < boxes.size(); ++k) {
        if (!boxes[k]) {
            unbounded_.push_back(static_cast<int>(k));
            continue;
        }
        padded_boxes[k] = padded(*boxes[k]);
        order_.push_back(static_cast<int>(k));
    }
    if (!order_.empty()) build(0, static_cast<int>(order_.size()), padded_boxes);
}

int ObjectBvh::build(int begin, int end, const std::vector<Bounds>& boxes) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Vec3 lo = boxes[static_cast<size_t>(order_[static_cast<size_t>(begin)])].lo, hi = lo;
    Vec3 clo = 0.5 * (lo + boxes[static_cast<size_t>(order_[static_cast<size_t>(begin)])].hi), chi = clo;
    for (int i = begin; i < end; ++i) {
        const Bounds& b = boxes[static_cast<size_t>(order_[static_cast<size_t>(i)])];
        lo = lo.cwiseMin(b.lo);
        hi = hi.cwiseMax(b.hi);
        const Vec3 c = 0.5 * (b.lo + b.hi);
        clo = clo.cwiseMin(c);
        chi = chi.cwiseMax(c);
    }
    Node n;
    n.lo = lo;
    n.hi = hi;
    n.index = index;
    if (end - begin <= kLeafSize) {
        n.first = begin;
        n.count = end - begin;
        nodes_[static_cast<size_t>(index)] = n;
        return index;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    // Median by centre along the axis; ties by object index (a deterministic tree).
    const auto centre = [&](int k) {
        const Bounds& b = boxes[static_cast<size_t>(k)];
        return b.lo[axis] + b.hi[axis];
    };
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
        const double ca = centre(a), cb = centre(b);
        return ca < cb || (ca == cb && a < b);
    });
    n.axis = axis;
    build(begin, mid, boxes);  // first child: index + 1
    n.first = build(mid, end, boxes);
    nodes_[static_cast<size_t>(index)] = n;
    return index;
}

}  // namespace refract
