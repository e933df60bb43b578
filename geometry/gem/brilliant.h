#pragma once
// The round brilliant cut: parameters, named presets, validation, and the exact construction.
// Plain doubles here: the construction (brilliant.cpp, with the half-space intersection of
// exact_hull.cpp) uses CGAL's exact kernel; callers get unit outward double planes with facet labels, facet
// polygons and a triangle mesh. The built gem has girdle radius R = 1 (diameter D = 2),
// z up, table at the top; callers scale and place it.
//
// Sources: M. Tolkowsky, "Diamond Design" (1919) for the ideal proportions; GIA (Facetware
// input ranges and the default proportion chart) for the parameter domain. docs/gems.md
// gives the construction.
#include <string>
#include <utility>
#include <vector>

#include <refract/geometry/shapes.h>

namespace refract {

// Percentages are of the average girdle diameter D; angles in degrees from the girdle plane.
struct BrilliantCut {
    double table = 57.0;            // table width, corner to corner of the octagon
    double crown_angle = 34.5;      // bezel facets to the girdle plane
    double pavilion_angle = 40.75;  // pavilion mains to the girdle plane
    double star = 55.0;             // horizontal, table edge -> star tip, % of table edge -> girdle
    double lower_half = 80.0;       // horizontal, girdle -> lower-half point, % of girdle -> axis
    double girdle = 3.0;            // thickness at the bezel/main positions; 0 = knife edge
    double culet = 0.0;             // culet width across the flats; 0 = pointed
    int girdle_facets = 0;          // 0 = bruted girdle, else a multiple of 16 (16..192)
    int bruted_planes = 64;         // a bruted (round) girdle is approximated by this many
                                    // vertical tangent planes (multiple of 16, 16..512)
};

// Named presets: "tolkowsky" (1919) and "gia-default" (GIA default chart).
std::vector<std::string> brilliant_preset_names();
BrilliantCut brilliant_preset(const std::string& name);  // InputError for an unknown name

// Throws InputError (one line: parameter, value, allowed range) when the cut is outside the
// documented domain or cannot make a brilliant (star tip above the table, lower halves reaching
// the culet, a girdle so thin that the upper and lower halves would meet).
void validate(const BrilliantCut& cut);

// Thinnest girdle (in % of D) for which a girdle of `cut.girdle_facets` facets (or the bruted
// approximation) keeps every girdle facet, given the crown and pavilion of `cut`; a knife
// edge (0 %) is always possible.
double min_girdle_percent(const BrilliantCut& cut);

// The number of vertical girdle planes the construction uses.
int girdle_plane_count(const BrilliantCut& cut);
// "bruted (round girdle approximated by 64 vertical planes)", "32 facets", "knife edge".
std::string girdle_description(const BrilliantCut& cut);

// Proportions in the trade's units (% of D, degrees).
struct BrilliantProportions {
    double table = 0;
    double crown_angle = 0;
    double pavilion_angle = 0;
    double star = 0;
    double lower_half = 0;
    double girdle = 0;
    double culet = 0;
    double crown_height = 0;
    double pavilion_depth = 0;
    double total_depth = 0;
};

// The requested parameters and the derived heights in closed form:
// crown height = (1 - t)·tanβ / 2, pavilion depth = (1 - c)·tanα / 2 (fractions of D).
BrilliantProportions closed_form_proportions(const BrilliantCut& cut);

struct GemFacet {
    std::string label;              // "table", "star 3", "bezel 0", "upper half 2+", "girdle 5", ...
    Plane plane;                    // unit outward normal, normal·x <= offset inside
    std::vector<Vec3> polygon;      // vertex loop, counter-clockwise seen from outside
    std::vector<int> vertex_ids;    // the same loop as indices into Gem::mesh.vertices
};

struct Gem {
    BrilliantCut cut;
    ConvexPolyhedron solid;          // planes[i] and labels[i] are facets[i]
    std::vector<GemFacet> facets;
    TriangleMesh mesh;               // facets fan-triangulated, vertices shared
    std::vector<int> triangle_facet; // facet index of each mesh triangle
    BrilliantProportions measured;   // measured back from the exact polyhedron
    std::string description;         // written files' header comment; empty: the brilliant's
    // false for a stone with a cleft ground into it (gemcad.h, cleft tiers): not the
    // intersection of its facets' half-spaces; `solid` then lists the facets' planes and
    // labels only, and `mesh` (closed, outward, triangle_facet labelled) is the stone.
    bool convex = true;
};

// The shape that traces the stone: the plane set `solid` for a convex gem (the exact cut,
// as always), the closed mesh for a stone with a cleft; a hit's facet is a plane index in
// the one and a triangle index (triangle_facet gives its facet) in the other.
Shape tracing_shape(const Gem& gem);
// The gem facet of each facet index a hit of tracing_shape(gem) reports: each plane its own
// facet for the plane set, triangle_facet for the mesh.
std::vector<int> hit_facets(const Gem& gem);

// Validates, then builds the cut exactly (CGAL) and converts to doubles at the end.
Gem build_brilliant(const BrilliantCut& cut);

// "upper half 2+" -> "upper half", "girdle 5" -> "girdle", "table" -> "table".
std::string facet_kind(const std::string& label);
// (kind, count) in construction order: table, star, bezel, upper half, girdle, lower half,
// pavilion main, culet (kinds with no facet are left out).
std::vector<std::pair<std::string, int>> facet_counts(const Gem& gem);

}  // namespace refract
