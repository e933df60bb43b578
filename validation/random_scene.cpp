#include <refract/validation/random_scene.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <refract/core/camera.h>
#include <refract/geometry/error.h>
#include <refract/validation/random_geometry.h>

namespace refract::validation::random_detail {
namespace {

struct Mat {
    std::string name, desc;
    json j;
    bool transparent = false, dispersive = false;
};

// ---- the generator ----------------------------------------------------------------------

class Generator {
public:
    Generator(std::uint64_t seed, const RandomSceneOptions& opt)
        : rng_(seed), area_rng_(seed ^ 0x617265616c696768ULL), opt_(opt), seed_(seed) {}
    json run();

private:
    // materials
    std::string add_material(Mat m);
    std::string dielectric();
    std::string diffuse(bool checker_likely);
    std::string mirror();
    std::string emissive();
    // shapes
    void add_solid(int index);
    // the rest of the scene
    void camera();
    bool clear_of_camera(const Solid& s) const;
    bool outside_plane(const Vec3& n, double d) const;
    void planes();
    void lights();
    json area_light(const Vec3& p, const Vec3& colour);
    void highlights(int count);
    void enclosure();
    void render();
    Box solids_box() const;

    Rand rng_;
    Rand area_rng_;  // RandomSceneOptions::area_lights: a stream of its own ("arealigh")
    int area_lights_ = 0;
    RandomSceneOptions opt_;
    std::uint64_t seed_;
    json scene_ = json::object();
    json objects_ = json::array();
    std::map<std::string, Mat> materials_;
    std::vector<std::string> dielectrics_;
    std::vector<Solid> solids_;
    std::vector<std::string> parts_;  // description of each object
    std::vector<Vec3> light_positions_;
    int dispersive_ = 0, max_dispersive_ = 2;
    bool floor_ = false, room_ = false, cocoon_ = false;
    double region_ = 2;
    Camera cam_;
    std::string camera_desc_, render_desc_;
    Vec3 view_dir_{0, 0, 1};
    std::vector<std::pair<Vec3, double>> highlights_;
    std::vector<Half> planes_;  // the opaque planes, as the scene reader sees them
};

std::string Generator::add_material(Mat m) {
    m.name = m.name + " " + std::to_string(materials_.size());
    const std::string name = m.name;
    materials_[name] = std::move(m);
    return name;
}

std::string Generator::dielectric() {
    if (!dielectrics_.empty() && rng_.chance(0.15))
        return dielectrics_[static_cast<size_t>(rng_.integer(0, static_cast<int>(dielectrics_.size()) - 1))];
    Mat m;
    m.name = "glass";
    m.transparent = true;
    // n uniform on [0.3, 0.98] ∪ [1.02, 4]: never within 0.02 of 1.
    const double x = rng_.uniform(0, 3.66);
    const double n = sig(x < 0.68 ? 0.3 + x : 1.02 + (x - 0.68), 4);
    m.j = {{"type", "dielectric"}, {"ior", n}};
    std::string filter;
    switch (rng_.pick({35, 35, 10, 20})) {
        case 0: break;  // clear: the default [1, 1, 1]
        case 1:
            m.j["filter"] = arr(dec3(rng_.box(0.4, 1), 3));
            filter = " tinted";
            break;
        case 2:
            m.j["filter"] = arr(Vec3(0, 0, 0));
            filter = " filter 0";
            break;
        default:
            m.j["filter"] = arr(dec3(rng_.box(0, 1), 3));
            filter = " filtered";
    }
    std::string refl = "fresnel";
    if (rng_.chance(0.3)) {
        const int k = rng_.pick({10, 10, 80});
        const double u = rng_.uniform(0, 1);
        const double ks = k == 0 ? 0.0 : k == 1 ? 1.0 : dec(u, 3);
        m.j["reflectance"] = "constant";
        m.j["reflectivity"] = ks;
        refl = "constant ks=" + num(ks);
    }
    std::string kind = "dielectric n=" + num(n);
    if (opt_.dispersion && dispersive_ < max_dispersive_ && rng_.chance(0.35)) {
        const int k = rng_.pick({5, 20, 75});
        const double u = rng_.u();
        const double D = k == 0 ? 1.0 : k == 1 ? sig(0.75 + 0.25 * u, 4) : sig(1.0 + 0.3 * u, 4);
        const bool big = rng_.chance(0.4);
        const int S = big ? rng_.integer(13, 31) : rng_.integer(2, 12);
        m.j["dispersion"] = {{"model", "povray"}, {"ior", n}, {"dispersion", D}, {"samples", S}};
        m.dispersive = true;
        ++dispersive_;
        kind = "dispersive n=" + num(n) + " D=" + num(D) + " x" + std::to_string(S);
    }
    m.desc = kind + " " + refl + filter;
    const std::string name = add_material(std::move(m));
    dielectrics_.push_back(name);
    return name;
}

std::string Generator::diffuse(bool checker_likely) {
    Mat m;
    m.name = "diffuse";
    const Vec3 c = dec3(rng_.box(0.05, 0.95), 3);
    const double d = dec(rng_.uniform(0.3, 1), 3);
    const bool ambient = rng_.chance(0.7);
    const double a = ambient ? dec(rng_.uniform(0, 0.3), 3) : 0.0;
    m.j = {{"type", "diffuse"}, {"color", arr(c)}, {"diffuse", d}, {"ambient", a}};
    m.desc = "diffuse";
    if (rng_.chance(checker_likely ? 0.85 : 0.4)) {
        const Vec3 c2 = dec3(rng_.box(0, 0.95), 3);
        const double s = dec(rng_.uniform(0.2, 1.5), 3);
        m.j["checker"] = {{"color2", arr(c2)}, {"size", s}};
        m.desc = "checker";
    }
    return add_material(std::move(m));
}

std::string Generator::mirror() {
    Mat m;
    m.name = "mirror";
    Vec3 c;
    if (rng_.chance(0.3)) c = Vec3::Constant(dec(rng_.uniform(0.5, 1), 3));
    else c = dec3(rng_.box(0.2, 1), 3);
    m.j = {{"type", "mirror"}, {"color", arr(c)}};
    m.desc = "mirror";
    return add_material(std::move(m));
}

std::string Generator::emissive() {
    Mat m;
    m.name = "lamp";
    const double k = rng_.uniform(2, 20);
    m.j = {{"type", "emissive"}, {"color", arr(dec3(k * rng_.box(0.5, 1), 3))}};
    m.desc = "emissive";
    return add_material(std::move(m));
}

void Generator::add_solid(int index) {
    const int kind = rng_.pick({22, 12, 20, 19, 23, 4});
    const int m = kind == 1 ? 0 : rng_.pick({60, 22, 18});  // hollow spheres are glass
    const bool transparent = m == 0;
    for (int attempt = 0; attempt < 40; ++attempt) {
        const double size = rng_.uniform(0.3, 1.2) * (attempt >= 20 ? 0.5 : 1.0);
        Template t;
        switch (kind) {
            case 0: t = sphere_template(size); break;
            case 1: t = hollow_template(rng_, size); break;
            case 2: t = mesh_template(rng_, size); break;
            case 3: t = polyhedron_template(rng_, size); break;
            case 4: t = brilliant_like_template(rng_, size); break;
            default: t = brilliant_template(rng_, size); break;
        }
        const double x = rng_.uniform(-region_, region_), z = rng_.uniform(-region_, region_);
        const int rest = rng_.pick({10, 45, 45});  // touching, slightly sunk, lifted
        const double sunk = rng_.uniform(0, 0.05) * size, lift = rng_.uniform(0.02, 1.5);
        const double free_y = rng_.uniform(-1.5, 1.5);
        const double y = !floor_ ? free_y : -t.box.lo.y() + (rest == 0 ? 0.0 : rest == 1 ? -sunk : lift);
        const std::string name = "object " + std::to_string(index);
        auto s = place(t, Vec3(x, y, z), name, transparent);
        if (!s) continue;
        bool ok = true;
        for (const Solid& other : solids_) {
            if (!transparent || !other.transparent) continue;
            ok = ok && (s->sphere && other.sphere
                            ? (s->centre - other.centre).norm() >= s->radius + other.radius + 0.02
                            : apart(s->box, other.box, 0.02));
        }
        if (!ok) continue;
        const std::string material = m == 0 ? dielectric() : m == 1 ? diffuse(false) : mirror();
        for (json& o : s->objects) {
            o["material"] = material;
            objects_.push_back(o);
        }
        solids_.push_back(*s);
        parts_.push_back(s->desc + " (" + materials_.at(material).desc + ")");
        return;
    }
}

Box Generator::solids_box() const {
    Box b;
    for (const Solid& s : solids_) b.add(s.box);
    if (solids_.empty()) b = {Vec3::Constant(-1), Vec3::Constant(1)};
    return b;
}

void Generator::camera() {
    const Box all = solids_box();
    const Vec3 c = all.centre();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    const Vec3 jitter = rng_.box(-0.15, 0.15) * rs;
    cam_.look_at = sig3(c + jitter);
    cam_.width = opt_.width;
    cam_.height = opt_.height;
    const bool ortho = rng_.chance(0.2);
    cam_.type = ortho ? Camera::Type::Orthographic : Camera::Type::Perspective;
    if (rng_.chance(0.15)) {
        const double sx = rng_.uniform(-0.3, 0.3), sz = rng_.uniform(-0.3, 0.3);
        cam_.sky = Vec3(dec(sx, 3), 1, dec(sz, 3));
    }
    const bool far = !ortho && rng_.chance(0.12);
    for (int attempt = 0;; ++attempt) {
        const double az = rng_.uniform(0, 2 * kPi);
        const double el = rad(floor_ ? rng_.uniform(5, 65) : rng_.uniform(-50, 70));
        const Vec3 dir(dcos(el) * dsin(az), -dsin(el), dcos(el) * dcos(az));  // towards look_at
        const double grow = 1 + 0.05 * attempt;
        double dist;
        if (ortho) {
            const double h = rng_.uniform(0.8, 1.5);
            cam_.ortho_height = sig(2 * rs * h, 4);
            dist = (rs + rng_.uniform(0.5, 4)) * grow;
        } else {
            cam_.angle_deg = dec(far ? rng_.uniform(20, 32) : rng_.uniform(20, 90), 1);
            const double half = rad(cam_.angle_deg / 2);
            dist = rs * rng_.uniform(0.9, 1.6) * dcos(half) / dsin(half) * grow;
            if (far) dist *= rng_.uniform(2, 4);
        }
        cam_.location = sig3(cam_.look_at - dist * dir);
        const Vec3 d = (cam_.look_at - cam_.location).normalized();
        bool ok = std::abs(d.dot(cam_.sky.normalized())) < 0.98;
        // Perspective: outside every solid (after 40 tries, outside the transparent ones);
        // orthographic: the image rectangle clear of every solid (the exporter refuses one
        // crossing a surface) and above the floor.
        const bool strict = attempt < 40;
        if (floor_ && (strict || ortho)) ok = ok && outside_plane(Vec3::UnitY(), 0.0);
        for (const Solid& s : solids_) ok = ok && ((!s.transparent && !strict && !ortho) || clear_of_camera(s));
        if (!ok) continue;
        view_dir_ = d;
        break;
    }
    json j = {{"type", ortho ? "orthographic" : "perspective"}, {"location", arr(cam_.location)},
              {"look_at", arr(cam_.look_at)}, {"sky", arr(cam_.sky)}, {"width", opt_.width}, {"height", opt_.height}};
    if (ortho) j["ortho_height"] = cam_.ortho_height;
    else j["angle"] = cam_.angle_deg;
    scene_["camera"] = j;
    camera_desc_ = ortho ? "orthographic (height " + num(cam_.ortho_height) + ")"
                         : std::string(far ? "far " : "") + "perspective (angle " + num(cam_.angle_deg) + ")";
}

// The camera's rays start outside the solid: the location, or the orthographic image
// rectangle (spheres exactly, other solids by their boxes), with a margin.
bool Generator::clear_of_camera(const Solid& s) const {
    if (cam_.type == Camera::Type::Orthographic) return !rectangle_cuts(s, cam_, 0.02);
    return !reaches(s, cam_.location, 0.02);
}

// The camera's rays start on the outer side of the plane n·x = d (n unit).
bool Generator::outside_plane(const Vec3& n, double d) const {
    if (cam_.type == Camera::Type::Perspective) return n.dot(cam_.location) > d + 0.05;
    const Camera::Basis b = cam_.basis();
    for (double sy : {-0.5, 0.5})
        for (double sx : {-0.5, 0.5})
            if (n.dot(cam_.location + sx * b.R + sy * b.U) <= d + 0.05) return false;
    return true;
}

void Generator::planes() {
    // 0–2 opaque planes: a checker floor at y = 0, a back wall or a tilted plane behind or
    // below every object; the camera always on their outer side.
    std::vector<int> kinds;
    if (floor_) kinds.push_back(0);
    const int extra = rng_.pick({floor_ ? 65.0 : 40.0, 35, floor_ ? 0.0 : 25.0});
    const int first = rng_.chance(0.6) ? 1 : 2;
    if (extra >= 1) kinds.push_back(first);
    if (extra >= 2) kinds.push_back(3 - first);
    const Box all = solids_box();
    int index = 0;
    for (int kind : kinds) {
        Vec3 n = Vec3::UnitY();
        double gap = 0;
        if (kind == 1) {
            n = -Vec3(view_dir_.x(), 0, view_dir_.z());
            if (n.norm() < 0.2) continue;  // looking straight down: no wall
            n.normalize();
            gap = rng_.uniform(0.5, 3);
        } else if (kind == 2) {
            const double tilt = rad(rng_.uniform(15, 60)), az = rng_.uniform(0, 2 * kPi);
            n = Vec3(dsin(tilt) * dcos(az), dcos(tilt), dsin(tilt) * dsin(az));
            gap = rng_.uniform(0.2, 2);
        }
        n = sig3(n);
        double d = 0;
        if (kind != 0) {
            d = INFINITY;
            for (const Vec3& p : all.corners()) d = std::min(d, n.normalized().dot(p));
            d = sig(d - gap);
        }
        if (!outside_plane(n / n.norm(), d)) continue;  // the reader normalises the normal only
        const int m = rng_.pick({85, 5, 10});
        const std::string material = m == 0 ? diffuse(true) : m == 1 ? diffuse(false) : mirror();
        planes_.push_back({n / n.norm(), d});
        objects_.push_back({{"type", "plane"}, {"name", "plane " + std::to_string(index++)}, {"normal", arr(n)},
                            {"offset", d}, {"material", material}});
        const std::string what = kind == 0 ? "floor" : kind == 1 ? "back wall" : "tilted plane";
        parts_.push_back(materials_.at(material).desc + " " + what);
    }
}

void Generator::lights() {
    const int count = rng_.pick({10, 40, 30, 20});
    const Box all = solids_box();
    const Vec3 c = all.centre();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    json ls = json::array();
    for (int i = 0; i < count; ++i) {
        Vec3 p;
        for (int attempt = 0;; ++attempt) {
            Vec3 d = rng_.unit();
            if (floor_ || rng_.chance(0.7)) d.y() = std::abs(d.y()) + 0.3;
            const double dist = rng_.uniform(3, 12) * std::max(1.0, rs / 2);
            p = sig3(c + dist * d.normalized());
            bool ok = above(planes_, p);
            for (const Solid& s : solids_) ok = ok && !reaches(s, p, 0.05);
            if (ok || attempt > 50) break;
        }
        const bool dim = rng_.chance(0.2);
        const double k = dim ? rng_.uniform(0.05, 0.3) : rng_.uniform(0.4, 1);
        const Vec3 tint = rng_.chance(0.6) ? Vec3(1, 1, 1) : rng_.box(0.4, 1);
        const Vec3 colour = dec3(k * tint, 3).cwiseMax(0.001);
        json l = opt_.area_lights ? area_light(p, colour) : json();
        ls.push_back(l.is_null() ? json{{"type", "point"}, {"position", arr(p)}, {"color", arr(colour)}} : l);
        light_positions_.push_back(p);
    }
    scene_["lights"] = ls;
}

// A point light at p made, half of the time, a 2 × 2 rectangle or disk area light about p
// (POV-Ray's grid without jitter, which refract's POV-Ray mode matches exactly at 2 × 2),
// its extent shrunk until its grid's square clears every solid and plane; null: stays a point.
json Generator::area_light(const Vec3& p, const Vec3& colour) {
    if (!area_rng_.chance(0.5)) return json();
    const Mat3 R = area_rng_.rotation();
    const bool disk = area_rng_.chance(0.5);
    double extent = area_rng_.uniform(0.2, 1.5);
    for (int attempt = 0; attempt < 4; ++attempt, extent *= 0.5) {
        const double e = sig(extent, 3);
        const Vec3 u = sig3(e * R.col(0)), v = sig3(e * R.col(1));
        bool ok = true;
        for (const double a : {-0.5, 0.5})
            for (const double b : {-0.5, 0.5}) {
                const Vec3 q = p + a * u + b * v;
                ok = ok && above(planes_, q);
                for (const Solid& s : solids_) ok = ok && !reaches(s, q, 0.05);
            }
        if (!ok) continue;
        ++area_lights_;
        if (disk)
            return {{"type", "disk"}, {"position", arr(p)}, {"normal", arr(sig3(R.col(2)))}, {"radius", sig(0.5 * e, 3)},
                    {"size", {2, 2}}, {"color", arr(colour)}};
        return {{"type", "rectangle"}, {"position", arr(p)}, {"axis1", arr(u)}, {"axis2", arr(v)}, {"size", {2, 2}},
                {"color", arr(colour)}};
    }
    return json();
}

void Generator::highlights(int count) {
    // Small emissive spheres: at a light (the 1984 paper's highlight) or beside the objects.
    const Box all = solids_box();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    for (int i = 0; i < count; ++i) {
        const double r = sig(rng_.uniform(0.08, 0.35));
        Vec3 p;
        for (int attempt = 0;; ++attempt) {
            if (!light_positions_.empty() && rng_.chance(0.5)) {
                p = light_positions_[static_cast<size_t>(rng_.integer(0, static_cast<int>(light_positions_.size()) - 1))];
            } else {
                Vec3 d = rng_.unit();
                if (floor_) d.y() = std::abs(d.y()) + 0.2;
                const double dist = rs + rng_.uniform(0.5, 4);
                p = sig3(all.centre() + dist * d.normalized());
            }
            Solid lamp;
            lamp.sphere = true;
            lamp.centre = p;
            lamp.radius = r;
            if ((clear_of_camera(lamp) && above(planes_, p)) || attempt > 50) break;
        }
        const std::string material = emissive();
        objects_.push_back({{"type", "sphere"}, {"name", "highlight " + std::to_string(i)}, {"center", arr(p)},
                            {"radius", r}, {"material", material}});
        highlights_.push_back({p, r});
        parts_.push_back("highlight sphere (emissive)");
    }
}

void Generator::enclosure() {
    // The camera inside an opaque sphere: a room holding the whole scene, or a small
    // sphere around the camera alone.
    if (!room_ && !cocoon_) return;
    Vec3 c;
    double r;
    std::string what;
    if (cocoon_) {
        c = sig3(cam_.location + rng_.box(-0.05, 0.05));
        r = sig(rng_.uniform(0.2, 0.6));
        what = "sphere around the camera";
    } else {
        const Box all = solids_box();
        c = sig3(all.centre());
        r = 0;
        std::vector<Vec3> pts = light_positions_;
        for (const Solid& s : solids_)
            for (const Vec3& p : s.box.corners()) pts.push_back(p);
        const Camera::Basis b = cam_.basis();
        for (double sy : {-0.5, 0.5})
            for (double sx : {-0.5, 0.5})
                pts.push_back(cam_.location + (cam_.type == Camera::Type::Orthographic ? sx * b.R + sy * b.U : Vec3(0, 0, 0)));
        for (const Vec3& p : pts) r = std::max(r, (p - c).norm());
        for (const auto& [p, hr] : highlights_) r = std::max(r, (p - c).norm() + hr);
        r = sig(r + rng_.uniform(1, 3));
        what = "room sphere";
    }
    // A mirror cocoon with no light inside would render black: the cocoon is a checker
    // seen by its ambient light.
    const int m = cocoon_ ? 0 : rng_.pick({60, 15, 25});
    const std::string material = m == 2 ? mirror() : diffuse(m == 0);
    if (cocoon_) materials_.at(material).j["ambient"] = dec(rng_.uniform(0.1, 0.3), 3);
    objects_.push_back({{"type", "sphere"}, {"name", what}, {"center", arr(c)}, {"radius", r}, {"material", material}});
    parts_.push_back(materials_.at(material).desc + " " + what + " (camera inside)");
}

void Generator::render() {
    const bool whitted = rng_.chance(0.2);
    const int t = rng_.integer(0, 5);
    const double random_threshold = dec(rng_.uniform(0.0005, 0.1), 4);
    const double threshold = std::array<double, 6>{0.0, sig(1.0 / 255), 1e-3, 0.01, 0.05, random_threshold}[t];
    const bool deep = rng_.chance(0.55);
    const int deep_depth = rng_.integer(11, 24), shallow_depth = rng_.integer(1, 10);
    int depth = deep ? deep_depth : shallow_depth;
    // POV-Ray's cost: without pruning a tree can double at every level, and dispersion
    // multiplies the refracted subtree by the number of bands. With these limits the
    // costliest of 1700 seeds took POV-Ray 3.4 s at 80×60; one dispersive scene at depth
    // 16 instead of 10 took 41 s.
    const double pruning = whitted ? 0.0 : threshold;
    int specular = 0, max_samples = 0;
    for (const json& o : objects_) {
        const Mat& m = materials_.at(o["material"].get<std::string>());
        if (m.transparent || m.j["type"] == "mirror") ++specular;
        if (m.dispersive) max_samples = std::max(max_samples, m.j["dispersion"]["samples"].get<int>());
    }
    if (pruning < 1e-3 && specular >= 2) depth = std::min(depth, 12);
    if (max_samples > 0 && pruning < 1e-3) depth = std::min(depth, 10);
    scene_["render"] = {{"integrator", whitted ? "whitted" : "fresnel-tree"},
                        {"max_depth", depth},
                        {"threshold", threshold},
                        {"compat", "povray"}};
    render_desc_ = std::string(whitted ? "whitted" : "fresnel-tree") + ", max_depth " + std::to_string(depth) +
                   ", threshold " + num(threshold) + (whitted ? " (ignored)" : "");
}

json Generator::run() {
    floor_ = rng_.chance(0.7);
    const double enclosed = rng_.u();
    room_ = enclosed < 0.08;
    cocoon_ = !room_ && enclosed < 0.11;
    max_dispersive_ = rng_.chance(0.2) ? 3 : 2;
    region_ = rng_.uniform(1.5, 3.5);
    const int count = rng_.integer(1, room_ || cocoon_ ? 5 : 6);  // the enclosing sphere is the sixth
    int lamps = 0;
    for (int i = 0; i < count; ++i) {
        if (i > 0 && rng_.chance(0.12)) ++lamps;
        else add_solid(i);
    }
    if (solids_.empty()) add_solid(count);
    camera();
    if (cocoon_ && cam_.type == Camera::Type::Orthographic) {
        cocoon_ = false;
        room_ = true;
    }
    planes();
    lights();
    highlights(lamps);
    enclosure();

    // Background: a random colour, or the RTIOW gradient sky (its colours or random ones).
    std::string background;
    if (rng_.chance(0.35)) {
        const bool rtiow = rng_.chance(0.5);
        const Vec3 bottom = dec3(rng_.box(0, 1), 3), top = dec3(rng_.box(0, 1), 3);
        scene_["background"] = {{"type", "gradient"},
                                {"bottom", arr(rtiow ? Vec3(1, 1, 1) : bottom)},
                                {"top", arr(rtiow ? Vec3(0.5, 0.7, 1) : top)}};
        background = rtiow ? "RTIOW sky" : "gradient sky";
    } else {
        const Vec3 colour = dec3(rng_.box(0, 1), 3);
        const bool black = floor_ && rng_.chance(0.1);  // else glass and mirrors alone would be black
        scene_["background"] = arr(black ? Vec3(0, 0, 0) : colour);
        background = black ? "black background" : "solid background";
    }
    render();

    json mats = json::object();
    for (const auto& [name, m] : materials_) mats[name] = m.j;
    scene_["materials"] = mats;
    scene_["objects"] = objects_;
    std::string desc = "random seed " + std::to_string(seed_) + ": ";
    for (size_t i = 0; i < parts_.size(); ++i) desc += (i ? ", " : "") + parts_[i];
    const size_t nl = light_positions_.size();
    desc += "; " + std::to_string(nl) + (nl == 1 ? " light; " : " lights; ");
    if (area_lights_ > 0) desc += std::to_string(area_lights_) + " of them area lights; ";
    desc += camera_desc_ + "; " + background + "; " +
            render_desc_;
    scene_["description"] = desc;
    return scene_;
}

}  // namespace

}  // namespace refract::validation::random_detail

namespace refract::validation {

nlohmann::json random_scene(std::uint64_t seed, const RandomSceneOptions& opt) {
    if (opt.width < 1 || opt.height < 1) throw InputError("random_scene: the image size must be positive");
    nlohmann::json scene = random_detail::Generator(seed, opt).run();
    if (opt.transforms) random_detail::draw_transforms(scene, seed);
    return scene;
}

RandomSceneFiles random_scene_files(std::uint64_t seed, const RandomSceneOptions& opt) {
    RandomSceneFiles r;
    r.scene = random_scene(seed, opt);
    if (opt.mesh_files) r.files = random_detail::draw_mesh_files(r.scene, seed);
    return r;
}

}  // namespace refract::validation