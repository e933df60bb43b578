// Many rays at once (trace_rays): each ray's sums are what its own record (trace) sums to,
// to the last bit, whatever the thread count; bad rays are refused by index before any work.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/integrator.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_rays.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>

using namespace refract;

namespace {

struct Rays {
    std::vector<Vec3> o, d;
    std::vector<double> nm;
};

// The camera's rays through every `step`-th pixel, at 400-700 nm in turn, every fifth an
// RGB ray (0).
Rays camera_rays(const Scene& s, int step) {
    Rays r;
    for (int j = 0; j < s.camera.height; j += step)
        for (int i = 0; i < s.camera.width; i += step) {
            const Ray ray = s.camera.ray(i + 0.5, j + 0.5);
            r.o.push_back(ray.origin);
            r.d.push_back(ray.dir);
            r.nm.push_back(r.nm.size() % 5 == 4 ? 0.0 : 400.0 + 10.0 * static_cast<double>(r.nm.size() % 31));
        }
    return r;
}

Vec3 row(const std::vector<double>& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }
bool same(const Vec3& a, const Vec3& b) {  // NaN equal to NaN
    for (int k = 0; k < 3; ++k)
        if (!(a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k])))) return false;
    return true;
}

// Ray i of batch b against its record: the sums taken over the record's segments in order.
void check_against_record(const Scene& s, const RayBatch& b, size_t i, const TraceRecord& rec) {
    INFO("ray " << i);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    REQUIRE(b.segments[i] == static_cast<int>(rec.segments.size()));
    const TraceSegment& first = rec.segments.front();
    CHECK(same(row(b.point, i), first.hit ? first.point : Vec3(nan, nan, nan)));
    CHECK((b.object[i] >= 0 ? s.objects[static_cast<size_t>(b.object[i])].name : std::string()) == first.object);
    CHECK(b.facet[i] == first.facet);
    CHECK(row(b.radiance, i) == rec.radiance);
    Vec3 escaped(0, 0, 0), exit(nan, nan, nan);
    double strongest = -std::numeric_limits<double>::infinity(), Rs = 0, Rp = 0;
    for (const TraceSegment& seg : rec.segments) {
        Rs += seg.Rs;
        Rp += seg.Rp;
        if (seg.event != "background") continue;
        escaped += seg.weight;
        if (seg.weight.sum() > strongest) {
            strongest = seg.weight.sum();
            exit = seg.ray.dir;
        }
    }
    CHECK(row(b.escaped, i) == escaped);
    CHECK(same(row(b.exit_direction, i), exit));
    CHECK(b.Rs[i] == Rs);
    CHECK(b.Rp[i] == Rp);
}

}  // namespace

TEST_CASE("trace_rays: every ray's sums are its own record's to the last bit, on any thread count", "[trace]") {
    const auto diamond = std::make_shared<const Scene>(load_scene(REFRACT_SOURCE_DIR "/scenes/examples/ohtsuka1998-diamond.json"));
    auto exact = std::make_shared<Scene>(*diamond);
    exact->settings.requested_polarisation = PolarisationModel::Exact;
    for (const auto& scene : {diamond, std::shared_ptr<const Scene>(exact)}) {
        const TraceSession session(scene);
        const Rays r = camera_rays(*scene, 24);
        const size_t n = r.o.size();
        const RayBatch one = trace_rays(session, r.o.data(), r.d.data(), r.nm.data(), n, 1);
        const RayBatch two = trace_rays(session, r.o.data(), r.d.data(), r.nm.data(), n, 2);
        REQUIRE(one.n == n);
        int on_diamond = 0, escaping = 0;
        for (size_t i = 0; i < n; ++i) {
            check_against_record(*scene, one, i, session.ray(Ray{r.o[i], r.d[i]}, r.nm[i]));
            on_diamond += one.object[i] == 1;
            escaping += !std::isnan(one.exit_direction[3 * i]);
        }
        CHECK(on_diamond > 20);  // the rays meet the gem, the floor and the sky
        CHECK(escaping > 0);
        CHECK(one.radiance == two.radiance);
        CHECK(one.segments == two.segments);
        CHECK(one.Rs == two.Rs);
        // Without wavelengths: RGB rays, as the record at 0 nm.
        const RayBatch rgb = trace_rays(session, r.o.data(), r.d.data(), nullptr, 8, 1);
        for (size_t i = 0; i < 8; ++i) check_against_record(*scene, rgb, i, session.ray(Ray{r.o[i], r.d[i]}));
    }
}

TEST_CASE("trace_rays in packets: each lane's sums are its own record's, whatever its neighbours meet", "[trace]") {
    // Packets of eight rays (natural light): lanes at other materials than their neighbours'
    // (absorbing glass, a dispersive prism, mirrors, a checker floor, an emitter), a lone
    // sphere whose escaping lanes would end early, a last packet partly empty.
    const nlohmann::json lone = {
        {"camera", {{"location", {0, 0, -4}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 40}, {"height", 30}}},
        {"background", {0.3, 0.5, 0.9}},
        {"materials", {{"glass", {{"type", "dielectric"}, {"dispersion", "diamond"}}}}},
        {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
        {"render", {{"max_depth", 12}}}};
    for (Scene s : {parse_scene(lone, "lone.json"), load_scene(REFRACT_SOURCE_DIR "/scenes/validation/absorbing-glass.json"),
                    load_scene(REFRACT_SOURCE_DIR "/scenes/validation/dispersion-gem.json"),
                    load_scene(REFRACT_SOURCE_DIR "/scenes/examples/glass-sphere.json")}) {
        s.settings.requested_polarisation = PolarisationModel::Natural;  // packets carry natural light
        const auto scene = std::make_shared<const Scene>(std::move(s));
        INFO(scene->source);
        const TraceSession session(scene);
        REQUIRE(session.tracer().packets());
        const Rays r = camera_rays(*scene, scene->camera.width / 13);
        const size_t n = r.o.size() - 3;  // not a multiple of eight
        const RayBatch b = trace_rays(session, r.o.data(), r.d.data(), r.nm.data(), n, 1);
        int transparent = 0;
        for (size_t i = 0; i < n; ++i) {
            check_against_record(*scene, b, i, session.ray(Ray{r.o[i], r.d[i]}, r.nm[i]));
            transparent += b.Rs[i] > 0;
        }
        CHECK(transparent > 8);
    }
}

TEST_CASE("trace_rays: a non-finite ray or a wavelength out of range is refused by its index", "[trace]") {
    const auto s = std::make_shared<const Scene>(load_scene(REFRACT_SOURCE_DIR "/scenes/examples/ohtsuka1998-diamond.json"));
    const TraceSession session(s);
    std::vector<Vec3> o(3, Vec3(0, 3, -3.6)), d(3, Vec3(0, -0.6, 0.8));
    std::vector<double> nm{500, 550, 600};
    d[2] = Vec3(0, 0, 0);
    CHECK_THROWS_WITH(trace_rays(session, o.data(), d.data(), nm.data(), 3),
                      Catch::Contains("trace_rays: ray 2 needs a finite origin and a finite, non-zero direction") &&
                          Catch::Contains("ohtsuka1998-diamond.json"));
    d[2] = d[0];
    nm[1] = 1000;
    CHECK_THROWS_WITH(trace_rays(session, o.data(), d.data(), nm.data(), 3),
                      Catch::Contains("trace_rays: ray 1: wavelength 1000 nm is outside [360, 830] nm"));
    CHECK(trace_rays(session, o.data(), d.data(), nullptr, 0).n == 0);
}

TEST_CASE("Path record: a segment's parent is the node that pushed it, when two nodes end at one point", "[trace]") {
    // The calcite plate's o and e waves leave its top at the very same point (segments 4 and
    // 6 of pixel (15, 12)); each one's children are its own (they used to be found by the
    // point, and all given to the later node).
    const Scene s = load_scene(REFRACT_SOURCE_DIR "/scenes/examples/calcite-plate.json");
    const TraceRecord r = trace_pixel(s, 15, 12);
    REQUIRE(r.segments.size() > 11);
    REQUIRE(r.segments[4].point == r.segments[6].point);
    CHECK(r.segments[8].parent == 4);
    CHECK(r.segments[9].parent == 4);
    CHECK(r.segments[10].parent == 6);
    CHECK(r.segments[11].parent == 6);
    int children[64] = {};
    for (const TraceSegment& seg : r.segments)
        if (seg.parent >= 0) {
            CHECK(seg.ray.origin == r.segments[static_cast<size_t>(seg.parent)].point);
            ++children[seg.parent];
        }
    CHECK(children[4] == 2);
    CHECK(children[6] == 2);
}
