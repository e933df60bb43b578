// Mesh files drawn onto a random scene (RandomSceneOptions::mesh_files): each chosen inline
// mesh becomes {"type": "mesh", "file": "mesh-K.obj"} (its name, material and transform
// kept) and its vertices and triangles an OBJ text, so that the POV-Ray validation reads
// the mesh through the mesh-file reader (core/mesh_file.h). Coordinates in the shortest
// round-trip form (the reader keeps them to its float precision, ~1e-7 relative, which both
// renderers then see alike); the OBJ's axes are the scene's. A stream of its own ("meshfile").
#include <refract/validation/random_geometry.h>

namespace refract::validation::random_detail {

std::vector<std::pair<std::string, std::string>> draw_mesh_files(json& scene, std::uint64_t seed) {
    Rand rng(seed ^ 0x6d65736866696c65ULL);  // "meshfile"
    std::vector<std::pair<std::string, std::string>> files;
    for (json& o : scene["objects"]) {
        if (o["type"] != "mesh" || !o.contains("vertices") || !rng.chance(0.5)) continue;
        const std::string name = "mesh-" + std::to_string(files.size()) + ".obj";
        std::string obj = "# " + o.value("name", std::string("mesh")) + " (refract random scene, seed " +
                          std::to_string(seed) + ")\n";
        for (const json& v : o["vertices"])
            obj += "v " + num(v[0].get<double>()) + " " + num(v[1].get<double>()) + " " + num(v[2].get<double>()) + "\n";
        for (const json& t : o["triangles"])  // OBJ counts vertices from 1
            obj += "f " + std::to_string(t[0].get<int>() + 1) + " " + std::to_string(t[1].get<int>() + 1) + " " +
                   std::to_string(t[2].get<int>() + 1) + "\n";
        o.erase("vertices");
        o.erase("triangles");
        o["file"] = name;
        files.emplace_back(name, obj);
    }
    if (!files.empty())
        scene["description"] = scene["description"].get<std::string>() + "; " + std::to_string(files.size()) +
                               (files.size() == 1 ? " mesh file" : " mesh files");
    return files;
}

}  // namespace refract::validation::random_detail
