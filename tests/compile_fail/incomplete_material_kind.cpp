// Must NOT compile: a material kind that lacks rules, checked as Material::Kind checks its
// kinds. The build names what it lacks (the ctest entry expects "lacks shadow_filter").
#include <refract/core/material.h>

namespace incomplete {

struct Kind {
    static constexpr const char* kType = "incomplete";
    static Kind read(const refract::JsonReader&, const std::string&) { return Kind{}; }
};
inline refract::Interaction interact(const Kind&, const refract::SurfaceHit&, const refract::Ray&,
                                     const refract::InteractionContext&) {
    return refract::leaf_interaction();
}

}  // namespace incomplete

static_assert(refract::material::check_kind<incomplete::Kind>());
