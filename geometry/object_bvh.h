#pragma once
// A bounding-volume hierarchy over a scene's objects, in double precision: the
// top-level structure of the tracer's nearest-hit search (each object then searched by
// its own shape: Embree's BVH for a mesh, the plane-set kernel for a polyhedron).
//
// Built once from the objects' boxes (median split of the box centres along the longest
// axis, at most kLeafSize objects per leaf; boxes padded by a relative 1e-9 so that a hit
// computed on an object's boundary is never culled by its box's own rounding). Unbounded
// objects (planes) are visited on every ray. The search calls `test(k)` for every object
// whose box the ray reaches before the caller's current best distance `t_cull`, which
// `test` may lower; the nearer child is visited first. Which objects are tested, and in
// what order, does not change the result when the caller keeps the linear search's rule
// (core/tracer.cpp): the nearest t, and on an exact tie the object first in order.
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <refract/geometry/shapes.h>

namespace refract {

class ObjectBvh {
public:
    static constexpr int kLeafSize = 2;

    // boxes[k]: object k's box; empty for an unbounded object.
    explicit ObjectBvh(const std::vector<std::optional<Bounds>>& boxes);

    int nodes() const { return static_cast<int>(nodes_.size()); }

    template <class Test>
    void search(const Ray& r, double t_min, const double& t_cull, Test&& test) const {
        for (int k : unbounded_) test(k);
        if (nodes_.empty()) return;
        const Vec3 inv(1.0 / r.dir.x(), 1.0 / r.dir.y(), 1.0 / r.dir.z());
        if (!std::isfinite(entry(nodes_[0], r, inv, t_min, t_cull))) return;
        std::array<int, 64> stack;
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[static_cast<size_t>(stack[--top])];
            if (n.count > 0) {
                for (int i = 0; i < n.count; ++i) test(order_[static_cast<size_t>(n.first + i)]);
                continue;
            }
            // Children (index + 1 and first): those the ray reaches before t_cull, the nearer
            // one visited first. (t_cull may have dropped since a node was pushed; its
            // objects then miss the window cheaply.)
            const int a = n.index + 1, b = n.first;
            const double ta = entry(nodes_[static_cast<size_t>(a)], r, inv, t_min, t_cull);
            const double tb = entry(nodes_[static_cast<size_t>(b)], r, inv, t_min, t_cull);
            const bool a_first = ta <= tb;
            const int near = a_first ? a : b, far = a_first ? b : a;
            if (std::isfinite(a_first ? tb : ta)) stack[top++] = far;
            if (std::isfinite(a_first ? ta : tb)) stack[top++] = near;
        }
    }

private:
    struct Node {
        Vec3 lo, hi;
        int first = 0;  // leaf: first entry in order_; inner: second child's node index
        int count = 0;  // leaf: objects (> 0); inner: 0
        int axis = 0;   // inner: split axis
        int index = 0;  // this node's own index (its first child is index + 1)
    };

    // Slab test of the ray against the node's box within [t_min, t_cull]: where the ray
    // enters it, +inf when it misses.
    static double entry(const Node& n, const Ray& r, const Vec3& inv, double t_min, double t_cull) {
        constexpr double kMiss = std::numeric_limits<double>::infinity();
        double t0 = t_min, t1 = t_cull;
        for (int a = 0; a < 3; ++a) {
            if (r.dir[a] == 0) {
                if (r.origin[a] < n.lo[a] || r.origin[a] > n.hi[a]) return kMiss;
                continue;
            }
            double ta = (n.lo[a] - r.origin[a]) * inv[a];
            double tb = (n.hi[a] - r.origin[a]) * inv[a];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::fmax(t0, ta);
            t1 = std::fmin(t1, tb);
            if (t0 > t1) return kMiss;
        }
        return t0;
    }

    int build(int begin, int end, const std::vector<Bounds>& boxes);

    std::vector<Node> nodes_;
    std::vector<int> order_;      // bounded objects, leaves' ranges index into it
    std::vector<int> unbounded_;  // objects tested on every ray
};

}  // namespace refract
