#pragma once
// Faceting designs in GemCad's text format (.asc), read and written; built exactly by
// gemcad_build.cpp (CGAL's exact kernel, the half-space intersection of every tier's facets).
//
// The format (GemCad for Windows user's guide, R. W. Strickland, "ASC file format",
// gemcad.com/downloads/gemcadman.pdf p. 21; the DOS GemCad 4.51 user's manual for the gear
// and its offset): one record a line, the first character its keyword.
//   GemCad 5.0             version line (optional)
//   g GEAR LOCATION        index gear (teeth; negative: indices run clockwise) and the index
//                          shown at the bottom of the top view (location, may be fractional)
//   y FOLDS MIRROR         symmetry the design was drawn with (FOLDS >= 1, MIRROR y or n);
//                          metadata: every tier lists its indices in full
//   I INDEX                the refractive index the design was made for
//   H TEXT / F TEXT        heading / footnote lines
//   a ANGLE DIST I1 [n NAME] I2 ... [TEXT]
//                          a tier: its facets' angle to the girdle plane in degrees, positive
//                          for the crown, negative for the pavilion (-0 is a pavilion culet,
//                          -90/90 the girdle), the plane's distance from the stone's centre,
//                          then its gear indices; `n NAME` names the facet of the index just
//                          before it; the first token that is neither starts the cutting
//                          instructions (rest of the line)
//   G TEXT                 cutting instructions continuing the previous tier
//
// Frame and units (docs/gems.md): z is the stone's axis, crown up; index i of gear N faces
// the azimuth 360° (i − location) / N − 90° counter-clockwise from +x seen from above (so
// index `location` faces −y, the bottom of GemCad's top view). Facet k of a tier is the
// half-space n·x <= DIST with n = (sin|A| cos φ, sin|A| sin φ, ±cos A), the sign that of A.
// Distances are in the design's own unit, as given: GemCad fixes no size (its own Standard
// Round Brilliant has the girdle at 1.0265, the table at 0.3645), so refract keeps them and
// reports the width W (the trade's unit, the narrowest caliper width of the outline seen
// from above); a scene's "diameter" scales the stone so that W equals it.
//
// The cleft (refract's convention, docs/gems.md "The heart"): a tier whose name is CL, or CL
// followed by digits (CL1, CL2, ...), is ground in after the convex preform that the other
// tiers cut. Its facets are written like any facet (n·x <= DIST keeps the stone's side, n the
// outward normal of the facet on the finished stone), but the stone keeps what lies inside
// at least one cleft facet: the notch removed is the convex region outside every cleft facet,
// stone = preform ∩ (∪ cleft facets' inner half-spaces). GemCad itself stores such a stone's
// facets the same way; only the name tells refract which facets cut the notch.
#include <string>
#include <vector>

#include <refract/geometry/gem/brilliant.h>

namespace refract {

struct GemcadTier {
    double angle = 0;                  // degrees, |angle| <= 90
    bool pavilion = false;             // the sign of the angle (-0 counts)
    double distance = 0;               // > 0, the design's unit
    std::vector<double> indices;       // gear indices, 0..|gear|
    std::vector<std::string> names;    // one per index ("" = unnamed)
    std::string instructions;          // cutting instructions, may be empty
    int line = 0;                      // line number in the file (1-based), 0 if built
    std::string name(int tier_number) const;  // first facet name, else "tier N"
};

// Whether the tier is a cleft tier: its name is CL or CL followed by digits.
bool is_cleft_tier(const GemcadTier& tier, int tier_number);

struct GemcadDesign {
    std::string source;                // file name for messages
    std::string version;               // "GemCad 5.0" or ""
    int gear = 96;
    double location = 0;
    int symmetry = 1;
    bool mirror = false;
    double index = 0;                  // 0: not given
    std::vector<std::string> headings, footnotes;
    std::vector<GemcadTier> tiers;
};

// Parses .asc text; InputError "SOURCE: line N: ..." for a truncated line, an unknown keyword,
// a non-finite or out-of-range number, a gear index out of range, or no tier at all.
GemcadDesign parse_gemcad(const std::string& text, const std::string& source);
// Reads and parses a file (at most 1 MiB and 4 096 facets).
GemcadDesign read_gemcad(const std::string& path);
// The design as .asc text (numbers with 17 significant digits: it parses back to the same doubles).
std::string gemcad_text(const GemcadDesign& design);

// A built design: the exact polyhedron as a Gem (facet labels "NAME INDEX", facet_kind() gives
// the tier's name) and its measures, in the design's unit.
struct DesignGem {
    Gem gem;
    int planes = 0;          // facets the design lists
    double volume = 0;       // exact, then rounded
    double width = 0;        // W: narrowest caliper width of the outline (seen along z)
    double length = 0;       // extent perpendicular to the width direction
    double height = 0;       // extent along z
    // With cleft tiers (gem.convex false): the convex preform's exact volume and the notch's
    // (the preform's part outside every cleft facet); volume = preform_volume − notch_volume.
    // Without: preform_volume = volume, notch_volume = 0.
    double preform_volume = 0;
    double notch_volume = 0;
    int cleft_facets = 0;    // facets of the finished stone on cleft planes
};

// Builds the design exactly; InputError "SOURCE: ..." when a tier cuts the whole stone away
// (naming it), when the tiers leave it open (unbounded), or when the result fails the
// closure/convexity check. With cleft tiers the preform is built and checked so, then the
// notch is removed exactly (CGAL's Nef polyhedra, gemcad_cleft.cpp) and the stone checked
// closed (every edge of its triangles shared by two, in opposite directions; Euler
// characteristic 2) and convex except at its cleft (every vertex inside every non-cleft
// facet plane); InputError naming the cleft tier when the cleft removes nothing, removes
// the whole stone, or cuts it in pieces.
DesignGem build_design(const GemcadDesign& design);

// The round brilliant as a design: one tier per facet kind (gear 96, fractional indices where
// a facet's azimuth falls between teeth), distances in girdle radii; it builds back to the
// brilliant's planes and vertices.
GemcadDesign brilliant_design(const Gem& brilliant);

}  // namespace refract
