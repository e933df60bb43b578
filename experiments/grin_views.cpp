// grin, part 6: rendered views through gradient-index media (experiments/grin.h): the
// scenes built here, rendered by the renderer's one walker (docs/grin.md, "GRIN objects in
// scenes"), their images and counters kept in the result.
#include <chrono>
#include <cmath>

#include <refract/core/grin/atmosphere.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>
#include <refract/experiments/grin.h>
#include <refract/geometry/constants.h>

namespace refract::experiments::grin_media {

namespace {

using nlohmann::json;

// A Luneburg lens (R = 1) over a checker floor: it images the scene behind the camera
// upside down on its far surface.
json luneburg_scene(int w, int h) {
    return json{
        {"camera", {{"location", {0, 1, -6}}, {"look_at", {0, 1, 0}}, {"angle", 40}, {"width", w}, {"height", h}}},
        {"background", {0.4, 0.5, 0.8}},
        {"materials",
         {{"lens", {{"type", "grin"}, {"profile", {{"kind", "luneburg"}, {"centre", {0, 1, 0}}, {"radius", 1}}}}},
          {"floor",
           {{"type", "diffuse"}, {"color", {0.9, 0.9, 0.9}}, {"checker", {{"color2", {0.1, 0.1, 0.1}}, {"size", 0.5}}}}}}},
        {"objects", json::array({{{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 1}, {"material", "lens"}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}})},
        {"lights", json::array({{{"position", {5, 10, -5}}}})},
        {"render", {{"max_depth", 12}}}};
}

// An inferior mirage: air 400 m long over a road, 2 % of n − 1 hotter at the ground
// (n = 1 − 2e-5·exp(−h / 0.25 m) relative to the air above), a red ball 500 m away.
json road_scene(int w, int h) {
    const json air_box = json::array({{1, 0, 0, 400}, {-1, 0, 0, 10}, {0, 1, 0, 20}, {0, -1, 0, -0.001},
                                      {0, 0, 1, 100}, {0, 0, -1, 100}});
    return json{
        {"camera", {{"location", {0, 1.5, 0}}, {"look_at", {100, 1.45, 0}}, {"angle", 5}, {"width", w}, {"height", h}}},
        {"background", {{"type", "gradient"}, {"bottom", {0.9, 0.93, 1.0}}, {"top", {0.35, 0.55, 0.95}}}},
        {"materials",
         {{"air",
           {{"type", "grin"},
            {"tolerance", 1e-7},
            {"shadows", false},
            {"profile",
             {{"kind", "exponential-height"}, {"n0", 0.99998}, {"scale_height", 0.25}, {"h0", 0}, {"up", {0, 1, 0}}}}}},
          {"road",
           {{"type", "diffuse"}, {"color", {0.25, 0.25, 0.27}}, {"checker", {{"color2", {0.35, 0.35, 0.37}}, {"size", 2}}}}},
          {"car", {{"type", "diffuse"}, {"color", {0.8, 0.1, 0.1}}}}}},
        {"objects", json::array({{{"type", "polyhedron"}, {"material", "air"}, {"planes", air_box}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "road"}},
                                 {{"type", "sphere"}, {"center", {500, 1.5, 0}}, {"radius", 1.5}, {"material", "car"}}})},
        {"lights", json::array({{{"type", "directional"}, {"direction", {1, -0.25, 0.3}}}})},
        {"render", {{"max_depth", 6}}}};
}

ViewStudy render_view(const std::string& name, const std::string& title, const json& scene, int threads) {
    return grin_media::render_view(name, title, scene, parse_scene(scene, name + ".json"), threads);
}

// A superior mirage: a ship 25 km away over the cold sea of the superior-mirage study (an
// inversion 10 K warmer above 20 m: a tabulated radial profile over the Earth, 0–500 m),
// seen from 3 m. The Earth is a dark diffuse sphere inside the air; the ship a red hull
// (80 m wide, 12 m high) with a white superstructure (16 m wide, up to 35 m) on top, both
// inside the air. The camera looks along +x at apparent altitude `look_deg`, 0.6° across.
json sea_scene(int w, int h, double look_deg) {
    const SeaAir air = sea_air(0.55);
    const double R = grin::kEarthRadius_m, th = air.distance / R, look = look_deg * kPi / 180;
    const Vec3 up(std::sin(th), std::cos(th), 0), ahead(std::cos(th), -std::sin(th), 0), side(0, 0, 1);
    const Vec3 base = air.centre + R * up;
    const auto box = [&](double half_side, double half_ahead, double bottom, double top) {
        const Vec3 c = base + 0.5 * (bottom + top) * up;
        json planes = json::array();
        for (const auto& [n, half] : {std::pair{up, 0.5 * (top - bottom)}, std::pair{ahead, half_ahead}, std::pair{side, half_side}})
            for (const double sg : {1.0, -1.0})
                planes.push_back({sg * n.x(), sg * n.y(), sg * n.z(), sg * n.dot(c) + half});
        return planes;
    };
    return json{
        {"camera",
         {{"location", {0, air.eye_height, 0}},
          {"look_at", {1000 * std::cos(look), air.eye_height + 1000 * std::sin(look), 0}},
          {"angle", 0.6},
          {"width", w},
          {"height", h}}},
        {"background", {{"type", "gradient"}, {"bottom", {0.85, 0.9, 0.95}}, {"top", {0.45, 0.62, 0.9}}}},
        {"materials",
         {{"air",
           {{"type", "grin"},
            {"tolerance", 1e-7},
            {"shadows", false},
            {"profile", {{"kind", "tabulated-radial"}, {"centre", {air.centre.x(), air.centre.y(), air.centre.z()}},
                         {"r", air.r}, {"n", air.n}}}}},
          {"sea", {{"type", "diffuse"}, {"color", {0.1, 0.16, 0.22}}, {"ambient", 0.6}}},
          {"hull", {{"type", "diffuse"}, {"color", {0.8, 0.1, 0.08}}, {"ambient", 0.3}}},
          {"deck", {{"type", "diffuse"}, {"color", {0.95, 0.95, 0.95}}, {"ambient", 0.3}}}}},
        {"objects",
         json::array({{{"type", "sphere"}, {"center", {air.centre.x(), air.centre.y(), air.centre.z()}},
                       {"radius", air.r.back()}, {"material", "air"}},
                      {{"type", "sphere"}, {"center", {air.centre.x(), air.centre.y(), air.centre.z()}}, {"radius", R},
                       {"material", "sea"}},
                      {{"type", "polyhedron"}, {"material", "hull"}, {"planes", box(40, 8, -1, 12)}},
                      {{"type", "polyhedron"}, {"material", "deck"}, {"planes", box(8, 5, 12, 35)}}})},
        {"lights", json::array({{{"type", "directional"}, {"direction", {1, -0.4, 0.3}}}})},
        {"render", {{"max_depth", 4}}}};
}

// The setting sun from 10 m over the sea (the scene in metres): the Earth a dark diffuse
// sphere inside the 1976 standard air (the "earth-atmosphere" profile, dispersing by
// Ciddor's index, to 100 km), the sun an emitter of the true angular radius (0.2666°) at
// 1 au with its centre kSunTrueAltitude below the true horizon; the camera looks along +x at
// apparent altitude `look_deg` with a horizontal field of `fov_deg`. Rendered by the
// spectral eye pass (31 wavelengths): the root ray splits at the camera, inside the air.
constexpr double kSunTrueAltitude = -0.3, kEyeHeight = 10.0;
json sunset_scene(int w, int h, double look_deg, double fov_deg) {
    const double au = 1.495978707e11, a = kSunTrueAltitude * kPi / 180, look = look_deg * kPi / 180;
    return json{
        {"camera",
         {{"location", {0, kEyeHeight, 0}},
          {"look_at", {1000 * std::cos(look), kEyeHeight + 1000 * std::sin(look), 0}},
          {"angle", fov_deg},
          {"width", w},
          {"height", h}}},
        {"background", {0.0, 0.0, 0.0}},
        {"materials",
         {{"air", {{"type", "grin"}, {"tolerance", 1e-9}, {"shadows", false}, {"profile", {{"kind", "earth-atmosphere"}}}}},
          {"sea", {{"type", "diffuse"}, {"color", {0.05, 0.08, 0.12}}, {"ambient", 1.0}}},
          {"sun", {{"type", "emissive"}, {"color", {0.8, 0.8, 0.8}}}}}},
        {"objects",
         json::array({{{"type", "sphere"}, {"center", {0, -grin::kEarthRadius_m, 0}}, {"radius", grin::kEarthRadius_m + 1e5},
                       {"material", "air"}},
                      {{"type", "sphere"}, {"center", {0, -grin::kEarthRadius_m, 0}}, {"radius", grin::kEarthRadius_m},
                       {"material", "sea"}},
                      {{"type", "sphere"},
                       {"center", {au * std::cos(a), kEyeHeight + au * std::sin(a), 0}},
                       {"radius", au * std::tan(0.2666 * kPi / 180)},
                       {"material", "sun"}}})},
        {"lights", json::array()}};
}

// The apparent altitude (degrees) of the sun's upper limb at `nm` straight ahead: the
// highest ray from the eye whose tree ends on the sun (bisection to 1e-6°).
double upper_limb_deg(const Scene& scene, double nm) {
    const auto meets_sun = [&](double deg) {
        const double e = deg * kPi / 180;
        const TraceRecord rec = trace_ray(scene, Ray{Vec3(0, kEyeHeight, 0), Vec3(std::cos(e), std::sin(e), 0)}, nm);
        for (const TraceSegment& seg : rec.segments)
            if (seg.event == "emissive") return true;
        return false;
    };
    double lo = 0.0, hi = 1.0;  // the sun's centre lies below 0.5°: its upper limb between
    if (!meets_sun(lo) || meets_sun(hi)) return std::nan("");
    while (hi - lo > 1e-6) {
        const double mid = 0.5 * (lo + hi);
        (meets_sun(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

ViewStudy render_view(const std::string& name, const std::string& title, const json& scene, const Scene& parsed,
                      int threads) {
    ViewStudy v;
    v.name = name;
    v.title = title;
    v.scene = scene;
    RenderOptions o;
    o.threads = threads;
    const auto t0 = std::chrono::steady_clock::now();
    RenderResult r = render(parsed, o);
    v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    v.image = std::move(r.image);
    v.grin_segments = r.stats.grin_segments;
    v.grin_evaluations = r.stats.grin_evaluations;
    v.grin_exhausted = r.stats.grin_exhausted;
    v.finite = true;
    for (double x : v.image.rgb) v.finite = v.finite && std::isfinite(x);
    return v;
}

std::vector<ViewStudy> view_study(bool quick, int threads) {
    const int w = quick ? 160 : 640, h = quick ? 120 : 480;
    std::vector<ViewStudy> v{
            render_view("luneburg_view", "A Luneburg lens over a checker floor", luneburg_scene(w, h), threads),
            render_view("road_view", "An inferior mirage over a hot road", road_scene(w, h), threads)};
    v.push_back(render_view("sea_view", "A superior mirage: a ship 25 km away over a cold sea, 0.6° across",
                            sea_scene(quick ? 48 : 160, quick ? 36 : 120, 0.05), threads));
    for (ViewStudy& s : sunset_views(quick, threads)) v.push_back(std::move(s));
    return v;
}

std::vector<ViewStudy> sunset_views(bool quick, int threads) {
    std::vector<ViewStudy> v;
    // The setting sun, whole (1° across), and its upper limb (0.03° across, centred on the
    // limb found at 550 nm): the spectral passes split its image, the violet and blue limb
    // above, the red below.
    const int sw = quick ? 48 : 96, sh = quick ? 36 : 72, lw = quick ? 32 : 64, lh = quick ? 24 : 48;
    v.push_back(render_view("sunset_view", "The setting sun from 10 m over the sea, 1° across",
                            sunset_scene(sw, sh, 0.2, 1.0), threads));
    const double limb = upper_limb_deg(parse_scene(sunset_scene(4, 4, 0.2, 1.0), "sunset_view.json"), 550.0);
    v.push_back(render_view("sunset_limb_view", "The setting sun's upper limb, 0.03° across (108″)",
                            sunset_scene(lw, lh, std::isfinite(limb) ? limb : 0.42, 0.03), threads));
    return v;
}

ShipImage ship_image(const ViewStudy& v) {
    ShipImage s;
    const Image& img = v.image;
    const int x = img.width / 2;
    for (int y = 0; y < img.height; ++y) {
        const Vec3 c = img.at(x, y);
        if (c.x() > 0.3 && c.x() > 2.5 * c.y()) {  // the hull's red
            if (s.red_top < 0) s.red_top = y;
            s.red_bottom = y;
        } else if (c.minCoeff() > 0.6) {  // the superstructure's white
            if (s.white_top < 0) s.white_top = y;
            s.white_bottom = y;
        }
    }
    s.seen = s.red_top >= 0 && s.white_top >= 0;
    s.inverted = s.seen && s.white_top > s.red_bottom;
    return s;
}

SunsetLimb sunset_limb(const ViewStudy& v) {
    SunsetLimb l;
    const Image& img = v.image;
    const int x = img.width / 2;
    const double pixel_arcsec = v.scene["camera"]["angle"].get<double>() * 3600.0 / img.width;
    int first = -1, white = -1;
    for (int y = 0; y < img.height; ++y) {
        const Vec3 c = img.at(x, y);
        if (first < 0 && c.sum() > 1e-3) {
            first = y;
            l.top_rgb = c;
        }
        if (first >= 0 && white < 0 && c.x() > 0.5 * c.maxCoeff()) white = y;
    }
    if (first < 0 || white < 0) return l;
    l.found = true;
    l.rim_arcsec = (white - first) * pixel_arcsec;
    l.blue_on_top = l.top_rgb.z() > l.top_rgb.x() && l.top_rgb.z() > l.top_rgb.y();
    return l;
}

}  // namespace refract::experiments::grin_media
