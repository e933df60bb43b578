// refract bench --mesh-file: a 1.3 M-triangle mesh file (an icosphere written by the bench
// itself as binary PLY, binary STL and OBJ in a temporary directory) loaded as a scene object:
// the time to read it, check its closure and build its BVH, and the bytes per triangle it
// holds afterwards (docs/performance.md).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <refract/core/mesh_file.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/icosphere.h>
#include <refract/geometry/mesh_accel.h>

namespace refract::cli::bench {

namespace bench_mesh_file_command {

namespace fs = std::filesystem;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// The process's resident and peak resident set, bytes (/proc/self/status: VmRSS, VmHWM).
struct Rss {
    double current = 0, peak = 0;
};
Rss rss() {
    Rss r;
    std::ifstream f("/proc/self/status");
    std::string key;
    double kb = 0;
    while (f >> key) {
        if (key == "VmRSS:" && f >> kb) r.current = 1024 * kb;
        else if (key == "VmHWM:" && f >> kb) r.peak = 1024 * kb;
    }
    return r;
}
// Resets the peak to the current resident set (Linux: /proc/self/clear_refs, "5").
void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }

void put(std::ofstream& o, float v) { o.write(reinterpret_cast<const char*>(&v), 4); }

void write_ply(const TriangleMesh& m, const fs::path& p) {
    std::ofstream o(p, std::ios::binary);
    o << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Vec3& v : m.vertices)
        for (int c = 0; c < 3; ++c) put(o, static_cast<float>(v[c]));
    for (const auto& t : m.triangles) {
        o.put(3);
        for (int c = 0; c < 3; ++c) {
            const std::int32_t i = t[c];
            o.write(reinterpret_cast<const char*>(&i), 4);
        }
    }
}

void write_stl(const TriangleMesh& m, const fs::path& p) {
    std::ofstream o(p, std::ios::binary);
    const std::string header(80, ' ');
    o.write(header.data(), 80);
    const auto n = static_cast<std::uint32_t>(m.triangles.size());
    o.write(reinterpret_cast<const char*>(&n), 4);
    for (size_t k = 0; k < m.triangles.size(); ++k) {
        const Vec3 nrm = triangle_normal(m, k);
        for (int c = 0; c < 3; ++c) put(o, static_cast<float>(nrm[c]));
        for (int q = 0; q < 3; ++q)
            for (int c = 0; c < 3; ++c) put(o, static_cast<float>(m.vertices[static_cast<size_t>(m.triangles[k][q])][c]));
        const std::uint16_t attr = 0;
        o.write(reinterpret_cast<const char*>(&attr), 2);
    }
}

// Wavefront OBJ: the float32 coordinates in the shortest decimal that reads back to them.
void write_obj(const TriangleMesh& m, const fs::path& p) {
    std::ofstream o(p, std::ios::binary);
    char line[128];
    for (const Vec3& v : m.vertices) {
        const int n = std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", static_cast<double>(static_cast<float>(v.x())),
                                    static_cast<double>(static_cast<float>(v.y())), static_cast<double>(static_cast<float>(v.z())));
        o.write(line, n);
    }
    for (const auto& t : m.triangles) {
        const int n = std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        o.write(line, n);
    }
}

void measure(const fs::path& file, const fs::path& dir) {
    const fs::path scene = dir / (file.stem().string() + "-" + file.extension().string().substr(1) + ".json");
    std::ofstream(scene) << R"({"camera": {"location": [0, 0, -5], "look_at": [0, 0, 0]},
  "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
  "objects": [{"type": "mesh", "file": ")" << file.filename().string() << R"(", "material": "glass"}]})";
    const Rss before = rss();
    reset_peak();
    const double t0 = now(), c0 = process_cpu_seconds();
    const Scene s = load_scene(scene.string());  // read, welded, closure checked (the mesh is glass)
    const double t1 = now(), c1 = process_cpu_seconds();
    const TriangleMesh& m = std::get<TriangleMesh>(s.objects[0].shape);
    const MeshAccel accel(m);
    const double t2 = now(), c2 = process_cpu_seconds();
    const Rss after = rss();
    const double n = static_cast<double>(m.triangles.size());
    const double mesh_bytes = static_cast<double>(m.vertices.capacity() * sizeof(Vec3) +
                                                  m.triangles.capacity() * sizeof(Eigen::Vector3i));
    const double accel_bytes = static_cast<double>(accel.bytes());
    std::printf("  %-5s %8.1f MB %10.0f %5.2f/%5.2f s %5.2f/%5.2f s %8.1f %8.1f %8.1f %8.1f %8.1f\n",
                file.extension().string().substr(1).c_str(), static_cast<double>(fs::file_size(file)) / 1e6, n, t1 - t0,
                c1 - c0, t2 - t1, c2 - c1, mesh_bytes / n, accel_bytes / n, (mesh_bytes + accel_bytes) / n,
                (after.current - before.current) / n, (after.peak - before.current) / n);
}

}  // namespace bench_mesh_file_command
using namespace bench_mesh_file_command;

void mesh_file() {
    const TriangleMesh sphere = icosphere(8);
    const fs::path dir = fs::temp_directory_path() / ("refract-bench-mesh-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const double t0 = now();
    write_ply(sphere, dir / "sphere.ply");
    write_stl(sphere, dir / "sphere.stl");
    write_obj(sphere, dir / "sphere.obj");
    std::printf("Mesh files: an icosphere of %zu triangles (%zu vertices), written as binary PLY, binary STL and OBJ in %.1f s, "
                "each loaded as a glass object of a scene (read, welded, closure checked), then its BVH built; one "
                "process, bytes per triangle after the build\n",
                sphere.triangles.size(), sphere.vertices.size(), now() - t0);
    print_load("before");
    std::printf("  %-5s %11s %10s %15s %15s %8s %8s %8s %8s %8s\n", "file", "size", "triangles", "load wall/CPU",
                "BVH wall/CPU", "mesh B", "accel B", "sum B", "RSS B", "peak B");
    std::error_code ec;
    try {
        measure(dir / "sphere.ply", dir);
        measure(dir / "sphere.stl", dir);
        measure(dir / "sphere.obj", dir);
    } catch (...) {
        fs::remove_all(dir, ec);
        throw;
    }
    fs::remove_all(dir, ec);
    std::printf("  (mesh B: vertices and triangles; accel B: Embree's allocations and the refinement's data; RSS B: the "
                "resident set's growth over the load and build; peak B: the peak resident set over the same span, above "
                "the start; targets: load <= 2 s, <= 120 B per triangle)\n");
    print_load("after");
}

}  // namespace refract::cli::bench
