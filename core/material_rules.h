#pragma once
// The rulebook of a material kind: every property the rest of refract asks of a kind is one
// function overloaded on it, and a kind lives with all of its rules in one file
// (core/materials/NAME.h). The kinds are visited exhaustively (core/material.h): a kind
// that lacks a rule does not compile, and check_kind<K>() names each missing rule. There is
// no default anywhere. The rules (K a kind, all in namespace refract::material):
//
//   static constexpr const char* kType              its `type` in scene files
//   static K read(const JsonReader&, const std::string& file)   its scene-file fields
//   Interaction interact(const K&, const SurfaceHit&, const Ray&, const InteractionContext&)
//        its branches at a hit (core/interaction.h), or a leaf
//   LeafLight leaf_light(const K&)                  how a leaf is lit (None: not a leaf)
//   StochasticRole stochastic_role(const K&)        what the stochastic integrator does there
//   std::optional<Scatter> sample(const K&, const SurfaceHit&, const Ray&,
//        const InteractionContext&, Rng&)           the stochastic integrator's continuation
//   const Vec3* shadow_filter(const K&)             the colour a crossing transmits (POV-Ray's
//        shadow rays through glass; null: opaque)
//   bool casts_shadow(const K&)                     emitters do not
//   bool dispersive(const K&)                       an RGB ray splits into bands there
//   double band_index(const K&, double nm, const CompatRules&)   its index at a band's
//        wavelength (0: not dispersive, the interaction's own index)
//   const spectrum::Absorption* absorption(const K&)   Beer–Lambert inside (null: clear)
//   bool in_packets(const K&)                       rays meeting it can ride in packets
//   bool carries_stokes(const K&)                   exact polarisation can pass it (the
//        physical mode's default model needs every material to say so)
//   const char* povray_lacks(const K&)              what POV-Ray lacks to render it (null: it
//        has a counterpart); the compatibility policy refuses such a kind (core/compat.cpp)
//   NodeRecord describe(const K&, const Interaction&, const SurfaceHit&, const Ray&,
//        double band_ior)                           what `trace` records of its node
//   void validate(const K&, const MaterialCheck&)   settings it cannot honour (InputError)
// The dielectric's node and sampled branch depend on the render's compatibility policy
// (core/compat.h); a kind reaches the policy through InteractionContext::rules.
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include <refract/core/interaction.h>
#include <refract/core/json_reader.h>
#include <refract/core/materials/pigment.h>
#include <refract/core/random.h>
#include <refract/core/spectrum/absorption.h>
#include <refract/core/spectrum/dispersion.h>

namespace refract {

struct RenderSettings;

// How a leaf is lit: not a leaf (None); lit by the lights, POV-Ray's convention
// ambient·pigment + Σ diffuse·pigment·light·max(0, N·L)·shadow (Lit); or shining its own
// colour (Emits).
struct LeafLight {
    enum class Kind { None, Lit, Emits };
    Kind kind = Kind::None;
    const Pigment* pigment = nullptr;  // Lit
    double diffuse = 0, ambient = 0;   // Lit
    Vec3 emission{0, 0, 0};            // Emits
};

// What the stochastic integrator does at a kind: its light ends the path (Leaf: lit
// surfaces and emitters), it scatters randomly (Scatters: RTIOW's Lambertian and metal, whose
// light the path gathers as it goes on), or one of its branches is sampled (Branches).
enum class StochasticRole { Leaf, Scatters, Branches };

// What `refract trace` records of a node: its event, and for a dielectric the relative
// index, the cosines and the reflectances.
struct NodeRecord {
    std::string event;
    double R = 0;
    bool dielectric = false;
    double eta = 0, cos_i = 0, cos_t = 0, Rs = 0, Rp = 0;
};

// What a kind's validation sees: how to name the material, and the render's settings
// that a kind may not be able to honour.
struct MaterialCheck {
    std::string where;          // "FILE: material 'NAME'"
    bool exact = false;         // exact polarisation (render.polarisation "exact")
    bool fresnel_tree = false;  // the fresnel-tree integrator (or the spectral eye pass)
};

// The policy's colour of a pigment at a point (CompatRules::pigment).
Vec3 pigment_at(const CompatRules& rules, const Pigment& p, const Vec3& point);

namespace material {

// Whether K has every rule; check_kind<K>() names the missing ones at compile time.
template <class K, class = void>
struct has_interact : std::false_type {};
template <class K>
struct has_interact<K, std::void_t<decltype(interact(std::declval<const K&>(), std::declval<const SurfaceHit&>(),
                                                     std::declval<const Ray&>(),
                                                     std::declval<const InteractionContext&>()))>>
    : std::is_same<decltype(interact(std::declval<const K&>(), std::declval<const SurfaceHit&>(),
                                     std::declval<const Ray&>(), std::declval<const InteractionContext&>())),
                   Interaction> {};
template <class K, class = void>
struct has_sample : std::false_type {};
template <class K>
struct has_sample<K, std::void_t<decltype(sample(std::declval<const K&>(), std::declval<const SurfaceHit&>(),
                                                 std::declval<const Ray&>(), std::declval<const InteractionContext&>(),
                                                 std::declval<Rng&>()))>> : std::true_type {};
#define REFRACT_MATERIAL_RULE(NAME, RESULT)                                                                 \
    template <class K, class = void>                                                                        \
    struct has_##NAME : std::false_type {};                                                                 \
    template <class K>                                                                                      \
    struct has_##NAME<K, std::void_t<decltype(NAME(std::declval<const K&>()))>>                             \
        : std::is_convertible<decltype(NAME(std::declval<const K&>())), RESULT> {};
REFRACT_MATERIAL_RULE(leaf_light, LeafLight)
REFRACT_MATERIAL_RULE(stochastic_role, StochasticRole)
REFRACT_MATERIAL_RULE(shadow_filter, const Vec3*)
REFRACT_MATERIAL_RULE(casts_shadow, bool)
REFRACT_MATERIAL_RULE(dispersive, bool)
REFRACT_MATERIAL_RULE(absorption, const spectrum::Absorption*)
REFRACT_MATERIAL_RULE(in_packets, bool)
REFRACT_MATERIAL_RULE(carries_stokes, bool)
REFRACT_MATERIAL_RULE(povray_lacks, const char*)
#undef REFRACT_MATERIAL_RULE
template <class K, class = void>
struct has_band_index : std::false_type {};
template <class K>
struct has_band_index<K, std::void_t<decltype(band_index(std::declval<const K&>(), 0.0, std::declval<const CompatRules&>()))>>
    : std::is_convertible<decltype(band_index(std::declval<const K&>(), 0.0, std::declval<const CompatRules&>())), double> {};
template <class K, class = void>
struct has_describe : std::false_type {};
template <class K>
struct has_describe<K, std::void_t<decltype(describe(std::declval<const K&>(), std::declval<const Interaction&>(),
                                                     std::declval<const SurfaceHit&>(), std::declval<const Ray&>(),
                                                     0.0))>> : std::true_type {};
template <class K, class = void>
struct has_validate : std::false_type {};
template <class K>
struct has_validate<K, std::void_t<decltype(validate(std::declval<const K&>(), std::declval<const MaterialCheck&>()))>>
    : std::true_type {};
template <class K, class = void>
struct has_reader : std::false_type {};
template <class K>
struct has_reader<K, std::void_t<decltype(K::kType), decltype(K::read(std::declval<const JsonReader&>(),
                                                                      std::declval<const std::string&>()))>>
    : std::true_type {};

template <class K>
constexpr bool is_complete_kind = has_interact<K>::value && has_sample<K>::value && has_leaf_light<K>::value &&
                                  has_stochastic_role<K>::value && has_shadow_filter<K>::value &&
                                  has_casts_shadow<K>::value && has_dispersive<K>::value && has_band_index<K>::value && has_absorption<K>::value &&
                                  has_in_packets<K>::value && has_carries_stokes<K>::value && has_povray_lacks<K>::value && has_describe<K>::value && has_validate<K>::value &&
                                  has_reader<K>::value;

// One line per missing rule, naming it.
template <class K>
constexpr bool check_kind() {
    static_assert(has_reader<K>::value, "material kind lacks kType and read(const JsonReader&, file)");
    static_assert(has_interact<K>::value, "material kind lacks interact(kind, hit, ray, context)");
    static_assert(has_sample<K>::value, "material kind lacks sample(kind, hit, ray, context, rng)");
    static_assert(has_leaf_light<K>::value, "material kind lacks leaf_light(kind)");
    static_assert(has_stochastic_role<K>::value, "material kind lacks stochastic_role(kind)");
    static_assert(has_shadow_filter<K>::value, "material kind lacks shadow_filter(kind)");
    static_assert(has_casts_shadow<K>::value, "material kind lacks casts_shadow(kind)");
    static_assert(has_dispersive<K>::value, "material kind lacks dispersive(kind)");
    static_assert(has_band_index<K>::value, "material kind lacks band_index(kind, nm, rules)");
    static_assert(has_absorption<K>::value, "material kind lacks absorption(kind)");
    static_assert(has_in_packets<K>::value, "material kind lacks in_packets(kind)");
    static_assert(has_carries_stokes<K>::value, "material kind lacks carries_stokes(kind)");
    static_assert(has_povray_lacks<K>::value, "material kind lacks povray_lacks(kind)");
    static_assert(has_describe<K>::value, "material kind lacks describe(kind, interaction, hit, ray, band_ior)");
    static_assert(has_validate<K>::value, "material kind lacks validate(kind, check)");
    return true;
}

}  // namespace material
}  // namespace refract
