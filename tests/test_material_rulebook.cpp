// The rulebook of material kinds (core/material_rules.h): a kind is complete only with
// every rule, the production kinds all are, and a test-only kind with every rule renders
// through the one walker like the built-in ones. (compile_fail/incomplete_material_kind.cpp
// shows the compiler naming a missing rule.)
#include <catch2/catch.hpp>

#include <variant>

#include <refract/core/material.h>
#include <refract/core/tracer.h>

using namespace refract;

namespace rulebook_test {

// A test-only kind: a glowing surface, a leaf that shines `color` and blocks shadows.
struct Glow {
    Vec3 color{2, 3, 4};
    static constexpr const char* kType = "glow";
    static Glow read(const JsonReader&, const std::string&) { return Glow{}; }
};
inline Interaction interact(const Glow&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf_interaction();
}
inline LeafLight leaf_light(const Glow& g) { return {LeafLight::Kind::Emits, nullptr, 0, 0, g.color}; }
inline StochasticRole stochastic_role(const Glow&) { return StochasticRole::Leaf; }
inline std::optional<Scatter> sample(const Glow&, const SurfaceHit&, const Ray&, const InteractionContext&, Rng&) {
    return std::nullopt;
}
inline const Vec3* shadow_filter(const Glow&) { return nullptr; }
inline bool casts_shadow(const Glow&) { return true; }
inline bool dispersive(const Glow&) { return false; }
inline double band_index(const Glow&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Glow&) { return nullptr; }
inline bool in_packets(const Glow&) { return true; }
inline bool carries_stokes(const Glow&) { return true; }
inline const char* povray_lacks(const Glow&) { return nullptr; }
inline NodeRecord describe(const Glow&, const Interaction&, const SurfaceHit&, const Ray&, double) {
    return NodeRecord{"glow"};
}
inline void validate(const Glow&, const MaterialCheck&) {}

// The same kind without a shadow filter.
struct Incomplete {
    static constexpr const char* kType = "incomplete";
    static Incomplete read(const JsonReader&, const std::string&) { return Incomplete{}; }
};
inline Interaction interact(const Incomplete&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf_interaction();
}
inline LeafLight leaf_light(const Incomplete&) { return {}; }

}  // namespace rulebook_test

TEST_CASE("Material rulebook: every built-in kind has every rule, a test-only kind with all of them is complete, one "
          "lacking rules is not",
          "[materials]") {
    using namespace material;
    STATIC_REQUIRE(check_kinds(static_cast<const Material::Kind*>(nullptr)));
    STATIC_REQUIRE(is_complete_kind<rulebook_test::Glow>);
    STATIC_REQUIRE(check_kind<rulebook_test::Glow>());
    STATIC_REQUIRE(!is_complete_kind<rulebook_test::Incomplete>);
    STATIC_REQUIRE(has_interact<rulebook_test::Incomplete>::value);
    STATIC_REQUIRE(has_leaf_light<rulebook_test::Incomplete>::value);
    STATIC_REQUIRE(!has_shadow_filter<rulebook_test::Incomplete>::value);
    STATIC_REQUIRE(!has_sample<rulebook_test::Incomplete>::value);
    STATIC_REQUIRE(!has_describe<rulebook_test::Incomplete>::value);
}

TEST_CASE("Material rulebook: a test-only kind visited beside the built-in ones answers every rule with its own values",
          "[materials]") {
    using Kinds = std::variant<material::Diffuse, material::Dielectric, rulebook_test::Glow>;
    const auto rule = [](const Kinds& k) {
        return std::visit(
            [](const auto& m) {
                return std::make_tuple(leaf_light(m).kind, stochastic_role(m), shadow_filter(m) != nullptr,
                                       casts_shadow(m), dispersive(m), in_packets(m));
            },
            k);
    };
    const auto glow = rule(Kinds{rulebook_test::Glow{}});
    CHECK(std::get<0>(glow) == LeafLight::Kind::Emits);
    CHECK(std::get<1>(glow) == StochasticRole::Leaf);
    CHECK(!std::get<2>(glow));
    CHECK(std::get<3>(glow));
    const auto glass = rule(Kinds{material::Dielectric{}});
    CHECK(std::get<0>(glass) == LeafLight::Kind::None);
    CHECK(std::get<1>(glass) == StochasticRole::Branches);
    CHECK(std::get<2>(glass));  // a crossing transmits its filter
    const auto floor = rule(Kinds{material::Diffuse{}});
    CHECK(std::get<0>(floor) == LeafLight::Kind::Lit);
    CHECK(std::get<1>(floor) == StochasticRole::Leaf);
    CHECK(leaf_light(rulebook_test::Glow{}).emission == Vec3(2, 3, 4));
}

TEST_CASE("Material rulebook: the built-in kinds' rules as the scene file names them (emitters cast no shadow, "
          "crystals ride one ray at a time, Lambertian scatters in the stochastic integrator)",
          "[materials]") {
    CHECK(!casts_shadow(Material{"e", material::Emissive{}}));
    CHECK(casts_shadow(Material{"m", material::Mirror{}}));
    CHECK(!in_packets(Material{"u", material::Uniaxial{}}));
    CHECK(in_packets(Material{"d", material::Dielectric{}}));
    // Exact polarisation needs a dielectric's amplitudes (the physical mode's default model).
    CHECK(carries_stokes(Material{"d", material::Dielectric{}}));
    material::Dielectric schlick;
    schlick.reflectance = ReflectanceModel::Schlick;
    CHECK(!carries_stokes(Material{"s", schlick}));
    CHECK(carries_stokes(Material{"u", material::Uniaxial{}}));
    CHECK(stochastic_role(Material{"l", material::Lambertian{}}) == StochasticRole::Scatters);
    CHECK(stochastic_role(Material{"m", material::Metal{}}) == StochasticRole::Scatters);
    CHECK(stochastic_role(Material{"d", material::Diffuse{}}) == StochasticRole::Leaf);
    CHECK(lit_surface(Material{"l", material::Lambertian{}}));
    CHECK(!lit_surface(Material{"e", material::Emissive{}}));
    CHECK(dispersive(Material{"u", material::Uniaxial{}}));
    CHECK(!dispersive(Material{"d", material::Dielectric{}}));
    CHECK(transparent(Material{"u", material::Uniaxial{}}));
    CHECK(!transparent(Material{"m", material::Metal{}}));
}

TEST_CASE("Material rulebook: POV-Ray lacks birefringence and curved rays, and has every other kind",
          "[materials]") {
    CHECK(povray_lacks(Material{"d", material::Dielectric{}}) == nullptr);
    CHECK(povray_lacks(Material{"f", material::Diffuse{}}) == nullptr);
    CHECK(povray_lacks(Material{"m", material::Mirror{}}) == nullptr);
    CHECK(povray_lacks(Material{"e", material::Emissive{}}) == nullptr);
    CHECK(povray_lacks(Material{"l", material::Lambertian{}}) == nullptr);
    CHECK(povray_lacks(Material{"t", material::Metal{}}) == nullptr);
    REQUIRE(povray_lacks(Material{"u", material::Uniaxial{}}) != nullptr);
    CHECK(std::string(povray_lacks(Material{"u", material::Uniaxial{}})) ==
          "POV-Ray has no birefringence: a uniaxial crystal's rays carry their o/e wave along the ray tree");
    REQUIRE(povray_lacks(Material{"g", material::Grin{}}) != nullptr);
    CHECK(std::string(povray_lacks(Material{"g", material::Grin{}})) == "POV-Ray has no curved rays");
}
