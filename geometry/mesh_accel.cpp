#include <refract/geometry/mesh_accel.h>

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <refract/geometry/error.h>

namespace refract {

namespace {

// The bytes Embree holds, all its scenes together (its memory monitor's running sum).
std::atomic<long long> embree_bytes{0};

bool monitor(void*, ssize_t bytes, bool) {
    embree_bytes += static_cast<long long>(bytes);
    return true;  // never refuse an allocation
}

// The process's one Embree device (thread-safe static initialisation; kept to the end of
// the process, as Embree's own examples do).
RTCDevice device() {
    static const RTCDevice d = [] {
        RTCDevice dev = rtcNewDevice("verbose=0");
        if (!dev) throw InputError("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
        rtcSetDeviceMemoryMonitorFunction(dev, monitor, nullptr);
        return dev;
    }();
    return d;
}

// A triangle as the refinement reads it: corner and edges in double, in one place (one or
// two cache lines instead of an index and three vertex lookups).
struct TriangleD {
    Vec3 a, e1, e2;
};

// A float bound no nearer than the double one (the refinement decides exactly).
float float_above(double t) {
    if (!(t < std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
    return std::nextafter(static_cast<float>(t), std::numeric_limits<float>::infinity());
}

RTCRayHit embree_ray(const Ray& r, float t_near, float t_far) {
    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(r.origin.x());
    rh.ray.org_y = static_cast<float>(r.origin.y());
    rh.ray.org_z = static_cast<float>(r.origin.z());
    rh.ray.dir_x = static_cast<float>(r.dir.x());
    rh.ray.dir_y = static_cast<float>(r.dir.y());
    rh.ray.dir_z = static_cast<float>(r.dir.z());
    rh.ray.tnear = t_near;
    rh.ray.tfar = t_far;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.time = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace

struct MeshAccel::Impl {
    const TriangleMesh* mesh = nullptr;
    Mode mode = Mode::refined;
    RTCScene scene = nullptr;
    std::vector<TriangleD> triangles;
    long long embree_bytes = 0;  // Embree's allocations over the build (other builds at the same time included)

    // Triangle k as the refinement reads it: from the copy when there is one, else from
    // the mesh (the same subtractions, so the same bits).
    TriangleD triangle(size_t k) const {
        if (!triangles.empty()) return triangles[k];
        const auto& t = mesh->triangles[k];
        const Vec3& a = mesh->vertices[static_cast<size_t>(t[0])];
        return {a, mesh->vertices[static_cast<size_t>(t[1])] - a, mesh->vertices[static_cast<size_t>(t[2])] - a};
    }
};

// Meshes up to this many triangles keep the refinement's own copy of each triangle
// (72 bytes: one cache line read instead of an index and three vertices, docs/performance.md);
// larger ones read the mesh, to hold within 120 bytes per triangle.
constexpr size_t kCopiedTriangles = size_t{1} << 19;

MeshAccel::MeshAccel(const TriangleMesh& mesh, Mode mode) : impl_(std::make_unique<Impl>()) {
    impl_->mesh = &mesh;
    impl_->mode = mode;
    const RTCDevice dev = device();
    const long long embree_before = embree_bytes.load();
    RTCScene scene = rtcNewScene(dev);
    if (mode == Mode::refined) {
        // Robust traversal (no optimisation that can miss an edge) and the best BVH Embree builds.
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    }
    RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangles.size()));
    if (!vb || !ib) {
        rtcReleaseGeometry(geom);
        rtcReleaseScene(scene);
        throw InputError("Embree: cannot allocate a mesh of " + std::to_string(mesh.triangles.size()) + " triangles");
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        for (int c = 0; c < 3; ++c) vb[3 * i + c] = static_cast<float>(mesh.vertices[i][c]);
    for (size_t k = 0; k < mesh.triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) ib[3 * k + c] = static_cast<unsigned>(mesh.triangles[k][c]);
    if (mode == Mode::refined && mesh.triangles.size() <= kCopiedTriangles) {
        impl_->triangles.reserve(mesh.triangles.size());
        for (const auto& t : mesh.triangles) {
            const Vec3& a = mesh.vertices[static_cast<size_t>(t[0])];
            impl_->triangles.push_back({a, mesh.vertices[static_cast<size_t>(t[1])] - a, mesh.vertices[static_cast<size_t>(t[2])] - a});
        }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    impl_->scene = scene;
    impl_->embree_bytes = embree_bytes.load() - embree_before;
}

std::size_t MeshAccel::bytes() const {
    return static_cast<std::size_t>(std::max(0LL, impl_->embree_bytes)) + impl_->triangles.capacity() * sizeof(TriangleD);
}

MeshAccel::~MeshAccel() { rtcReleaseScene(impl_->scene); }

std::optional<Hit> MeshAccel::intersect(const Ray& r, double t_min, double t_max) const {
    if (impl_->mode != Mode::refined) throw std::logic_error("MeshAccel::intersect on a plain Embree mesh");
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    // The near end at half of t_min: a self-hit Embree reports is the refinement's to reject.
    float t_near = static_cast<float>(std::fmax(0.0, 0.5 * t_min));
    const float t_far = float_above(t_max);
    for (;;) {
        RTCRayHit rh = embree_ray(r, t_near, t_far);
        rtcIntersect1(impl_->scene, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        const auto k = static_cast<size_t>(rh.hit.primID);
        const TriangleD tri = impl_->triangle(k);
        const auto h = triangle_t(tri.a, tri.e1, tri.e2, r);
        const double t = h ? h->t : rh.ray.tfar;  // parallel in double: Embree's t
        if (t > t_min && t < t_max)
            return Hit{t, r.at(t), tri.e1.cross(tri.e2).normalized(), static_cast<int>(k)};  // = triangle_normal
        // At or before t_min (the surface the ray starts on): look again beyond it. Past
        // t_max: nothing nearer.
        if (!(t <= t_min) || !(rh.ray.tfar < t_far)) return std::nullopt;
        t_near = std::nextafter(rh.ray.tfar, std::numeric_limits<float>::infinity());
    }
}

MeshAccel::FloatHit MeshAccel::intersect_float(const Ray& r, double t_min, double t_max) const {
    if (impl_->mode != Mode::plain) throw std::logic_error("MeshAccel::intersect_float on a refined mesh");
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = embree_ray(r, static_cast<float>(t_min), float_above(t_max));
    rtcIntersect1(impl_->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {-1, 0.0f};
    return {static_cast<int>(rh.hit.primID), rh.ray.tfar};
}

}  // namespace refract
