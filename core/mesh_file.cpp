#include <refract/core/mesh_file.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <functional>
#include <unordered_map>
#include <vector>

#include <malloc.h>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>

namespace refract {

namespace {

namespace fs = std::filesystem;

std::atomic<std::uint64_t> reads{0};

using Affine = Eigen::Matrix<double, 3, 4>;  // [linear | translation], acting on column vectors

Affine affine(const aiMatrix4x4& m) {
    Affine a;
    a << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4;
    return a;
}

Affine compose(const Affine& outer, const Affine& inner) {
    Affine a;
    a.leftCols<3>() = outer.leftCols<3>() * inner.leftCols<3>();
    a.col(3) = outer.leftCols<3>() * inner.col(3) + outer.col(3);
    return a;
}

// The node's transform to the file's world: its own times its ancestors'.
Affine global(const aiNode* n) {
    Affine a = affine(n->mTransformation);
    for (const aiNode* p = n->mParent; p; p = p->mParent) a = compose(affine(p->mTransformation), a);
    return a;
}

struct Placed {
    const aiMesh* mesh;
    Affine to_world;
};

void collect(const aiScene* sc, const aiNode* n, const Affine& to_world, std::vector<Placed>& out) {
    for (unsigned i = 0; i < n->mNumMeshes; ++i) out.push_back({sc->mMeshes[n->mMeshes[i]], to_world});
    for (unsigned c = 0; c < n->mNumChildren; ++c)
        collect(sc, n->mChildren[c], compose(to_world, affine(n->mChildren[c]->mTransformation)), out);
}

// Every instance of the mesh named `name` in the node tree.
void collect_named_mesh(const aiScene* sc, const aiNode* n, const std::string& name, std::vector<Placed>& out) {
    for (unsigned i = 0; i < n->mNumMeshes; ++i) {
        const aiMesh* m = sc->mMeshes[n->mMeshes[i]];
        if (name == m->mName.C_Str()) out.push_back({m, global(n)});
    }
    for (unsigned c = 0; c < n->mNumChildren; ++c) collect_named_mesh(sc, n->mChildren[c], name, out);
}

void node_names(const aiNode* n, std::string& list) {
    if (n->mName.length > 0) list += (list.empty() ? "" : ", ") + clip_echo(n->mName.C_Str());
    for (unsigned c = 0; c < n->mNumChildren && list.size() < 200; ++c) node_names(n->mChildren[c], list);
}

std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return clip_echo(s, 200);
}

// Equal positions, bit for bit (−0 taken as +0 by the caller), are one vertex: an
// open-addressing table of vertex numbers (no allocation per vertex; the weld was a third of
// a large file's load through a node-based map), grown at half full.
class PositionIndex {
public:
    explicit PositionIndex(std::size_t expected) { rehash(expected); }

    // The number of the vertex at `p` in `vertices`, appended when new.
    int find_or_add(const Vec3& p, std::vector<Vec3>& vertices) {
        if (2 * (vertices.size() + 1) > slots_.size()) rehash(2 * vertices.size() + 2, vertices);
        for (std::size_t i = hash(p) & mask_;; i = (i + 1) & mask_) {
            const int k = slots_[i];
            if (k < 0) {
                slots_[i] = static_cast<int>(vertices.size());
                vertices.push_back(p);
                return slots_[i];
            }
            if (same(vertices[static_cast<std::size_t>(k)], p)) return k;
        }
    }

private:
    std::vector<int> slots_;
    std::size_t mask_ = 0;

    static std::uint64_t bits(double v) {
        std::uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    }
    static bool same(const Vec3& a, const Vec3& b) {
        return bits(a.x()) == bits(b.x()) && bits(a.y()) == bits(b.y()) && bits(a.z()) == bits(b.z());
    }
    static std::size_t hash(const Vec3& p) {
        std::uint64_t h = bits(p.x()) * 0x9e3779b97f4a7c15ULL;
        h = (h ^ (h >> 29) ^ bits(p.y())) * 0xbf58476d1ce4e5b9ULL;
        h = (h ^ (h >> 31) ^ bits(p.z())) * 0x94d049bb133111ebULL;
        return static_cast<std::size_t>(h ^ (h >> 32));
    }
    void rehash(std::size_t expected, const std::vector<Vec3>& vertices = {}) {
        std::size_t n = 16;
        while (n < 2 * expected) n *= 2;
        slots_.assign(n, -1);
        mask_ = n - 1;
        for (std::size_t k = 0; k < vertices.size(); ++k) {
            std::size_t i = hash(vertices[k]) & mask_;
            while (slots_[i] >= 0) i = (i + 1) & mask_;
            slots_[i] = static_cast<int>(k);
        }
    }
};

}  // namespace

std::string MeshClosure::describe() const {
    std::string s = std::to_string(open_edges) + " open edges, " + std::to_string(inconsistent_edges) +
                    " inconsistently oriented edges";
    if (nonmanifold_edges) s += ", " + std::to_string(nonmanifold_edges) + " edges shared by more than two triangles";
    if (open_edges == 0 && inconsistent_edges == 0 && nonmanifold_edges == 0 && !(volume > 0))
        s += ", wound inside out (volume " + format_value(volume) + ")";
    return s;
}

MeshClosure mesh_closure(const TriangleMesh& m) {
    // Each directed edge as (smaller index, larger index, direction bit), sorted: an
    // undirected edge's uses are then adjacent.
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * m.triangles.size());
    MeshClosure c;
    double volume6 = 0;
    for (const auto& t : m.triangles) {
        for (int e = 0; e < 3; ++e) {
            const auto a = static_cast<std::uint64_t>(t[e]), b = static_cast<std::uint64_t>(t[(e + 1) % 3]);
            edges.push_back((std::min(a, b) << 32 | std::max(a, b)) << 1 | (a < b ? 1u : 0u));
        }
        volume6 += m.vertices[static_cast<std::size_t>(t[0])].dot(
            m.vertices[static_cast<std::size_t>(t[1])].cross(m.vertices[static_cast<std::size_t>(t[2])]));
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && (edges[j] >> 1) == (edges[i] >> 1)) ++j;
        const std::size_t uses = j - i;
        if (uses == 1) ++c.open_edges;
        else if (uses > 2) ++c.nonmanifold_edges;
        else if ((edges[i] & 1) == (edges[i + 1] & 1)) ++c.inconsistent_edges;
        i = j;
    }
    c.volume = volume6 / 6;
    return c;
}

namespace {

TriangleMesh read_with_assimp(const std::string& path, const std::string& node) {
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".gltf" && ext != ".glb")
        throw MeshFileError("file", path + ": unsupported mesh format '" + clip_echo(ext) + "' (obj, ply, stl, gltf, glb)");
    std::error_code ec;
    const auto st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw MeshFileError("file", path + ": cannot open the mesh file");
    if (!fs::is_regular_file(st)) throw MeshFileError("file", path + ": is not a regular file");
    ++reads;

    Assimp::Importer importer;
    // Triangulate: polygons (OBJ, PLY) fanned into triangles, nothing else changed: no
    // joining by normals, smoothing, repair or change of axes (the welding below is exact).
    const aiScene* sc = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_ValidateDataStructure);
    if (!sc) throw MeshFileError("file", path + ": cannot read the mesh: " + one_line(importer.GetErrorString()));
    if ((sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !sc->mRootNode)
        throw MeshFileError("file", path + ": the file holds no complete scene");

    std::vector<Placed> placed;
    if (node.empty()) {
        collect(sc, sc->mRootNode, affine(sc->mRootNode->mTransformation), placed);
    } else if (const aiNode* n = sc->mRootNode->FindNode(node.c_str())) {
        collect(sc, n, global(n), placed);
    } else {
        collect_named_mesh(sc, sc->mRootNode, node, placed);
        if (placed.empty()) {
            std::string names;
            node_names(sc->mRootNode, names);
            throw MeshFileError("node", path + ": no node or mesh named '" + clip_echo(node) + "'" +
                                            (names.empty() ? std::string() : " (nodes: " + names + ")"));
        }
    }

    TriangleMesh out;
    std::size_t corners = 0, listed = 0;
    for (const Placed& p : placed) {
        corners += 3 * static_cast<std::size_t>(p.mesh->mNumFaces);
        listed += p.mesh->mNumVertices;
    }
    if (corners / 3 > static_cast<std::size_t>(1) << 30) throw MeshFileError("file", path + ": more than 2^30 triangles");
    // A closed mesh has about half as many vertices as triangles (Euler); STL lists every
    // corner apart, so the file's own count can be six times that.
    const std::size_t expected = std::min(listed, corners / 6 + 16);
    PositionIndex index(expected);
    out.vertices.reserve(expected);
    out.triangles.reserve(corners / 3);
    const std::string where = node.empty() ? std::string() : " (node '" + clip_echo(node) + "')";
    for (const Placed& p : placed) {
        const aiMesh* m = p.mesh;
        const std::string mesh_name = "mesh '" + clip_echo(m->mName.C_Str()) + "'";
        // A node of negative determinant (a mirror) turns its triangles round (glTF 2.0,
        // "Meshes": the winding order then is clockwise): rewound, they stay counter-clockwise
        // seen from outside once placed.
        const bool mirrored = p.to_world.leftCols<3>().determinant() < 0;
        std::vector<int> ids(m->mNumVertices, -1);
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
            const aiFace& face = m->mFaces[f];
            if (face.mNumIndices != 3)
                throw MeshFileError("file", path + ": " + mesh_name + " holds points or lines (only surfaces are read)");
            Eigen::Vector3i tri;
            for (int c = 0; c < 3; ++c) {
                const unsigned v = face.mIndices[c];
                if (ids[v] < 0) {
                    const aiVector3D& q = m->mVertices[v];
                    const Vec3 local(q.x, q.y, q.z);
                    if (!local.allFinite())
                        throw MeshFileError("file", path + ": " + mesh_name + ": vertex " + std::to_string(v) + " is not finite");
                    const Vec3 w = p.to_world.leftCols<3>() * local + p.to_world.col(3);
                    if (!w.allFinite())
                        throw MeshFileError("file", path + ": " + mesh_name + ": vertex " + std::to_string(v) +
                                                        " is not finite once placed by its node's transform");
                    ids[v] = index.find_or_add(Vec3(w.x() + 0.0, w.y() + 0.0, w.z() + 0.0), out.vertices);
                }
                tri[c] = ids[v];
            }
            const Vec3& a = out.vertices[static_cast<std::size_t>(tri[0])];
            if ((out.vertices[static_cast<std::size_t>(tri[1])] - a).cross(out.vertices[static_cast<std::size_t>(tri[2])] - a).norm() == 0)
                throw MeshFileError("file", path + ": " + mesh_name + ": triangle " + std::to_string(f) + " is degenerate (zero area)");
            if (mirrored) std::swap(tri[1], tri[2]);
            out.triangles.push_back(tri);
        }
    }
    if (out.triangles.empty()) throw MeshFileError("file", path + where + ": holds no triangles");
    out.vertices.shrink_to_fit();
    out.triangles.shrink_to_fit();
    return out;
}

}  // namespace

TriangleMesh read_mesh_file(const std::string& path, const std::string& node) {
    TriangleMesh out = read_with_assimp(path, node);
    // The importer's scene and the weld's table are freed by now, but the allocator keeps
    // the pages: an OBJ's text-parsing buffers left the resident set 222 bytes per triangle
    // larger where the mesh holds 106. Give the free pages back (glibc).
    malloc_trim(0);
    return out;
}

MeshFileCache::Entry& MeshFileCache::entry(const std::string& path, const std::string& node) {
    std::error_code ec;
    const fs::path canon = fs::weakly_canonical(path, ec);
    const std::pair<std::string, std::string> key{ec ? path : canon.string(), node};
    auto it = entries_.find(key);
    if (it == entries_.end())
        it = entries_.emplace(key, Entry{std::make_shared<const Shape>(read_mesh_file(path, node)), std::nullopt}).first;
    return it->second;
}

std::shared_ptr<const Shape> MeshFileCache::get(const std::string& path, const std::string& node) {
    return entry(path, node).mesh;
}

const MeshClosure& MeshFileCache::closure(const std::string& path, const std::string& node) {
    Entry& e = entry(path, node);
    if (!e.closure) e.closure = mesh_closure(std::get<TriangleMesh>(*e.mesh));
    return *e.closure;
}

std::uint64_t mesh_file_reads() { return reads.load(); }

}  // namespace refract
