#pragma once
// Writing exact polarisation's images beside a rendered image IMAGE.ext:
//   IMAGE.stokes.exr  S0.R S0.G S0.B S1.R ... S3.B (linear, the conventions of
//                     docs/polarisation.md; S0 is the image itself)
//   IMAGE.dolp.exr    Y: degree of linear polarisation of the channels' sum, in [0, 1]
//   IMAGE.aolp.exr    Y: its angle in degrees on the image, from the right towards the top
#include <string>
#include <vector>

#include <refract/core/render.h>

namespace refract {

// The three paths for IMAGE.ext.
std::vector<std::string> polarisation_paths(const std::string& image_path);

// Writes them (atomically each); returns their paths. S1–S3 and the angle may be negative,
// S0 too with `signed_colours` (RenderResult::signed_colours); every other value must be >= 0.
std::vector<std::string> write_polarisation(const std::string& image_path, int width, int height,
                                            const PolarisationImages& p, bool signed_colours = false);

}  // namespace refract
