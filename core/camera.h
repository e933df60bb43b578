#pragma once
// Camera, mapping pixel (i, j) to a primary ray exactly as POV-Ray 3.7 does with
// antialiasing off (tracepixel.cpp CreateCameraRay): x0 = (i+0.5)/W − 0.5,
// y0 = 0.5 − (j+0.5)/H, dir = normalize(D + x0·R + y0·U); row j = 0 is the top.
//
// A perspective camera with an `aperture` is a thin lens (defocus blur, Shirley, "Ray
// Tracing in One Weekend", §"Defocus Blur"): the ray of image position (x, y) leaves a
// point of the lens disk (diameter `aperture`, centred on `location`, in the R–U plane)
// towards the point where the pinhole ray meets the plane in focus, the plane normal to
// D at `focus_distance` from the lens. Points on that plane image to points; a point at
// distance z along D images to a disk of diameter aperture·|z − f|/z on the plane in
// focus (thin_lens_blur_diameter).
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
    double aperture = 0;        // thin lens: the lens diameter (scene units); 0 = a pinhole
    double focus_distance = 0;  // thin lens: distance of the plane in focus along D (scene units)

    bool thin_lens() const { return aperture > 0; }

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
    // The thin lens's ray through (x, y) from the lens point of the unit-square sample
    // (u, v) (uniform over the disk: radius aperture/2·√u, angle 2πv); the pinhole ray
    // when there is no aperture.
    Ray ray(const Basis& b, double x, double y, double u, double v) const;
};

// The thin lens's circle of confusion: the diameter of the blur disk, on the plane in
// focus, of a point at depth z (along the view direction) seen through a lens of diameter
// `aperture` focused at depth f: aperture·|z − f|/z (similar triangles through the lens
// edge and the image of the point).
double thin_lens_blur_diameter(double aperture, double focus_distance, double z);

}  // namespace refract
