// Caustics against POV-Ray photons (validation/caustics.h): the opt-in photon export and
// the statistical comparison of a glass sphere's caustic; [povray] runs POV-Ray itself.
#include <catch2/catch.hpp>

#include <string>

#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/validation/caustics.h>
#include <refract/validation/pov_export.h>

using namespace refract;
using namespace refract::validation;
using Catch::Matchers::Contains;

namespace {

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("Photon export is opt-in: a light pass is refused without it, targets and count with it", "[validation]") {
    CausticOptions o;
    o.photons = 123456;
    const Scene s = caustic_scene(o);
    REQUIRE(s.settings.light_pass.enabled);
    CHECK_THROWS_AS(export_pov(s), InputError);  // photons are statistical: never the exact export
    const std::string pov = export_pov(s, ExportOptions{true, 0});
    CHECK(count(pov, "photons { count 123456 }") == 1);  // the scene's light-pass photons
    CHECK(count(pov, "photons { target refraction on reflection on }") == 1);  // the one glass sphere
    CHECK_THAT(export_pov(s, ExportOptions{true, 5000}), Contains("photons { count 5000 }"));
}

TEST_CASE("Photon export off is byte-identical to the exact export", "[validation]") {
    CausticOptions o;
    Scene s = caustic_scene(o);
    s.settings.light_pass.enabled = false;
    const std::string exact = export_pov(s);
    CHECK(export_pov(s, ExportOptions{}) == exact);
    CHECK(exact.find("photons") == std::string::npos);
    // Photons on, light pass off: the same file plus the three photon statements only.
    const std::string with = export_pov(s, ExportOptions{true, 1000});
    CHECK(with.size() == exact.size() + std::string("\n  photons { count 1000 }").size() +
                             std::string(" photons { target refraction on reflection on }").size());
}

TEST_CASE("Glass sphere caustic: refract's light pass matches POV-Ray photons in region means and profile",
          "[povray]") {
    CausticOptions o;
    o.threads = 2;
    const CaseResult r = run_caustics(o);
    INFO("refract " << r.refract_seconds << " s, POV-Ray " << r.povray_seconds << " s");
    int checked = 0;
    for (const Metric& m : r.metrics) {
        INFO(m.name << " = " << m.value);
        if (m.tolerance) {
            ++checked;
            CHECK(m.value <= *m.tolerance);
        }
    }
    CHECK(checked == 6);  // four region means, the profile's worst bin and mean
    CHECK(r.status == Status::Pass);
    // The caustic core (bilinear maps, the default) is held to 3 % (measured: 1.1 % at
    // seed 7, at most 1.7 % over seeds 7-9 and 1e5-8e5 photons).
    REQUIRE(r.metrics.front().name.rfind("caustic core", 0) == 0);
    CHECK(*r.metrics.front().tolerance == 0.03);
    CHECK(r.metrics.front().value < 0.02);
    // The caustic is there: the core is brighter than the lit floor, the shadow edge darker.
    const auto mean_of = [&](const std::string& region) {
        for (const Metric& m : r.metrics)
            if (m.name.rfind(region, 0) == 0) {
                const auto a = m.name.find("refract ") + 8;
                return std::stod(m.name.substr(a));
            }
        FAIL("no metric " << region);
        return 0.0;
    };
    CHECK(mean_of("caustic core") > 1.2 * mean_of("lit floor"));
    CHECK(mean_of("shadow edge") < 0.5 * mean_of("lit floor"));
}
