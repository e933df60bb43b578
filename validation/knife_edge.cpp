#include <refract/validation/knife_edge.h>

#include <algorithm>
#include <cmath>

#include <refract/core/render.h>

namespace refract::validation {

Camera shifted_camera(const Camera& camera, double dx, double dy) {
    // Camera::ray: a pixel's ray runs along D + x0·R + y0·U (perspective) or starts at
    // location + x0·R + y0·U (orthographic), x0 = x/W − ½, y0 = ½ − y/H.
    const Camera::Basis b = camera.basis();
    const Vec3 shift = b.R * (dx / camera.width) - b.U * (dy / camera.height);
    Camera c = camera;
    switch (camera.type) {  // every camera type (-Wswitch names one left out)
        case Camera::Type::Perspective:
            c.look_at = camera.location + b.D + shift;
            break;
        case Camera::Type::Orthographic:
            c.location += shift;
            c.look_at += shift;
            break;
    }
    return c;
}

std::vector<char> knife_edge_pixels(const Scene& scene, const Image& centre, double tolerance, int threads) {
    const int w = scene.camera.width, h = scene.camera.height;
    std::vector<char> edge(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
    const double s = kKnifeEdgeShift;
    for (const auto& [dx, dy] : {std::pair{s, 0.0}, {-s, 0.0}, {0.0, s}, {0.0, -s}}) {
        Scene moved = scene;
        moved.camera = shifted_camera(scene.camera, dx, dy);
        RenderOptions ro;
        ro.threads = threads;
        const Image img = clamp01(render(moved, ro).image);
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const Vec3 d = img.at(i, j) - centre.at(i, j);
                if (d.cwiseAbs().maxCoeff() > tolerance) edge[static_cast<size_t>(j) * w + i] = 1;
            }
    }
    return edge;
}

bool met_outside_knife_edges(const Image& refract, const Image& povray, const std::vector<char>& knife_edge,
                             const Targets& targets, int& set_aside, ImageDifference& outside) {
    Image merged = refract;
    set_aside = 0;
    for (int j = 0; j < refract.height; ++j)
        for (int i = 0; i < refract.width; ++i) {
            if (!knife_edge[static_cast<size_t>(j) * refract.width + i]) continue;
            if ((refract.at(i, j) - povray.at(i, j)).cwiseAbs().maxCoeff() <= targets.pixel_tolerance) continue;
            merged.set(i, j, povray.at(i, j));
            ++set_aside;
        }
    outside = compare_images(merged, povray, targets.pixel_tolerance);
    // The set-aside pixels still count as over the tolerance.
    const double fraction = static_cast<double>(outside.pixels_over + set_aside) / static_cast<double>(outside.pixels);
    return set_aside > 0 && fraction <= targets.max_fraction_over && outside.rmse <= targets.rmse;
}

}  // namespace refract::validation
