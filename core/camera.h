#pragma once
// Camera, mapping pixel (i, j) to a primary ray exactly as POV-Ray 3.7 does with
// antialiasing off (tracepixel.cpp CreateCameraRay): x0 = (i+0.5)/W − 0.5,
// y0 = 0.5 − (j+0.5)/H, dir = normalize(D + x0·R + y0·U); row j = 0 is the top.
#include <refract/geometry/ray.h>

namespace refract {

struct Camera {
    enum class Type { Perspective, Orthographic };
    Type type = Type::Perspective;
    Vec3 location{0, 0, -5};
    Vec3 look_at{0, 0, 0};
    Vec3 sky{0, 1, 0};
    double angle_deg = 60;     // perspective: horizontal field of view across |right|
    double ortho_height = 2;   // orthographic: |up| in scene units; |right| = |up|·W/H
    int width = 320;
    int height = 240;

    // The basis POV-Ray builds: D (direction, length from the angle), R (right,
    // |R| = W/H), U (up, |U| = 1), or the orthographic extents.
    struct Basis {
        Vec3 D, R, U;
    };
    Basis basis() const;

    // Ray through the continuous image position (x, y) in pixels, x to the right and
    // y down from the top-left corner; the centre of pixel (i, j) is (i + 0.5, j + 0.5).
    Ray ray(double x, double y) const;
    // The same with the basis computed once (renders: basis() per sample costs a tan and
    // two normalisations).
    Ray ray(const Basis& b, double x, double y) const;
};

}  // namespace refract
