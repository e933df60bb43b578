#pragma once
// Mesh files in scenes ({"type": "mesh", "file": "ring.glb", "node": …}, docs/scene-format.md):
// OBJ, PLY, STL and glTF 2.0 (.gltf, .glb), read through Assimp (whose types stay in
// core/mesh_file.cpp). Coordinates are taken as the file gives them (no change of axes: y
// up, as glTF), each mesh placed by its node's transforms in the file; the vertices are
// joined where their positions are equal (exactly), so that the closure check sees the
// mesh's topology whatever the format (STL stores every corner apart).
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <refract/geometry/shapes.h>

namespace refract {

// How a triangle mesh closes: each undirected edge should be shared by exactly two
// triangles that run along it in opposite directions, and the enclosed volume be positive
// (counter-clockwise seen from outside).
struct MeshClosure {
    std::size_t open_edges = 0;          // used by one triangle
    std::size_t inconsistent_edges = 0;  // two triangles running the same way
    std::size_t nonmanifold_edges = 0;   // more than two triangles
    double volume = 0;                   // signed, from the triangles' orientation
    bool closed_outward() const {
        return open_edges == 0 && inconsistent_edges == 0 && nonmanifold_edges == 0 && volume > 0;
    }
    // "3 open edges, 0 inconsistently oriented edges" (and the rest when not zero).
    std::string describe() const;
};
MeshClosure mesh_closure(const TriangleMesh& m);

// Reads `path`: the meshes of the whole file, or those of the node (or mesh) named `node`
// and its children. Throws MeshFileError, whose `field` is "file" or "node" and whose
// message names the file: unreadable, unsupported, truncated or empty files, non-finite
// or degenerate geometry, an unknown node.
struct MeshFileError : std::runtime_error {
    MeshFileError(std::string field_, const std::string& what) : std::runtime_error(what), field(std::move(field_)) {}
    std::string field;
};
TriangleMesh read_mesh_file(const std::string& path, const std::string& node = "");

// The mesh files of one scene, each (canonical path, node) read once however many objects
// use it. get() returns the shared mesh (a TriangleMesh); the closure is computed on first
// request.
class MeshFileCache {
public:
    std::shared_ptr<const Shape> get(const std::string& path, const std::string& node);
    const MeshClosure& closure(const std::string& path, const std::string& node);

private:
    struct Entry {
        std::shared_ptr<const Shape> mesh;
        std::optional<MeshClosure> closure;
    };
    std::map<std::pair<std::string, std::string>, Entry> entries_;
    Entry& entry(const std::string& path, const std::string& node);
};

// How many times read_mesh_file() has read a file in this process (the instancing test).
std::uint64_t mesh_file_reads();

}  // namespace refract
