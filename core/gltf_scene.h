#pragma once
// glTF 2.0 scenes as a whole (docs/gltf.md): `refract import model.glb -o scene.json` and
// `refract export-gltf scene.json -o out.glb`. The glTF JSON is read and written with
// nlohmann-json (already refract's JSON library; glTF is JSON plus one binary chunk): the
// import needs no vertex data (a mesh is referenced as {"type": "mesh", "file": …, "node": …}
// and read by the mesh-file reader, core/mesh_file.h), and the export writes its buffer
// itself. What refract cannot honour is named in one warning per item.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/scene.h>

namespace refract {

struct GltfImport {
    nlohmann::json scene;               // a refract scene file's JSON
    std::vector<std::string> warnings;  // one line each, naming the file and the item
};

// Reads the glTF file `path` (.gltf or .glb) into a refract scene whose mesh objects refer
// to `path` by `mesh_file` (the path as the scene should write it: relative to the scene
// file's directory). The image is `width` wide; `height` 0: from the camera's aspect
// ratio. Throws InputError naming the file and the item (a truncated or malformed file,
// an index out of range, a non-finite number).
GltfImport import_gltf(const std::string& path, const std::string& mesh_file, int width = 0, int height = 0);

struct GltfExport {
    std::string bytes;                  // the .glb file, or the .gltf text (buffer embedded)
    std::vector<std::string> warnings;  // one line each, naming the object or material
};

// The scene as glTF 2.0: meshes, polyhedra and gems as triangles (float32), spheres
// tessellated (a warning each), planes left out (a warning each), every object's node with
// its transform, the camera, point and directional lights (KHR_lights_punctual),
// dielectrics with KHR_materials_transmission, _ior, _volume and _dispersion.
GltfExport export_gltf(const Scene& s, bool binary);

// Base64 (RFC 4648 §4, with padding), as glTF's data URIs carry a buffer.
std::string base64(const std::string& in);

// glTF's frame to refract's: the mirror z → −z (glTF is right-handed, refract's camera
// POV-Ray's left-handed one); its own inverse, so the import and the export both use it.
inline Eigen::Matrix4d gltf_mirror() { return Eigen::Vector4d(1, 1, -1, 1).asDiagonal(); }

// KHR_materials_dispersion's `dispersion` is 20/V_d (V_d the Abbe number): both ways.
double gltf_dispersion_of_abbe(double Vd);
double abbe_of_gltf_dispersion(double dispersion);

}  // namespace refract
