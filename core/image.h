#pragma once
// Linear RGB images in double precision; files go through OpenImageIO, in the image module
// that the first image operation loads (core/image_io.h; InputError if it cannot be loaded).
// The format is chosen by the extension: .exr/.hdr/.tif (linear, float), .png/.jpg/.ppm/.bmp
// (sRGB-encoded 8-bit, or 16-bit linear for .png with `linear16`).
#include <string>
#include <utility>
#include <vector>

#include <refract/geometry/ray.h>

namespace refract {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<double> rgb;  // row-major, 3 per pixel, row 0 at the top

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, 0.0) {}
    Vec3 at(int i, int j) const {
        const size_t k = (static_cast<size_t>(j) * width + i) * 3;
        return {rgb[k], rgb[k + 1], rgb[k + 2]};
    }
    void set(int i, int j, const Vec3& c) {
        const size_t k = (static_cast<size_t>(j) * width + i) * 3;
        rgb[k] = c.x(); rgb[k + 1] = c.y(); rgb[k + 2] = c.z();
    }
};

struct WriteOptions {
    bool linear16 = false;  // .png only: 16-bit linear instead of 8-bit sRGB
    // The values may be negative (the xyz-srgb pipeline's colours out of the sRGB gamut).
    bool signed_values = false;
};

// Writes to a temporary name beside `path`, then renames: never a half-written file.
// Throws InputError naming the path on failure (unknown extension, unwritable). What is
// written is checked first: every value finite as stored (a float for .exr/.hdr/.tif, where
// 1e300 would be infinity), and, for the float formats, >= 0 unless `signed_values` (the
// integer formats clamp to [0, 1]); a value that fails throws std::runtime_error, an
// internal error naming the pixel and the channel, and nothing is written.
void write_image(const std::string& path, const Image& img, const WriteOptions& opt = {});

// Checks, before any work, that an image can be written at `path`: a known extension this
// OpenImageIO writes, an existing writable directory, not a directory itself. InputError
// naming the path otherwise. write_image and write_channels check it too.
void check_image_path(const std::string& path);

// A float OpenEXR file with the given channel names; `data` interleaved, row-major
// (names.size() values per pixel). Atomic like write_image, checked like it: every value
// finite as a float, and >= 0 except in the channels named in `signed_channels` (Stokes
// S1–S3, angles, colours of a signed pipeline).
// `attributes`: string metadata (name, value) stored in the file's header.
void write_channels(const std::string& path, int width, int height, const std::vector<std::string>& names,
                    const std::vector<double>& data,
                    const std::vector<std::pair<std::string, std::string>>& attributes = {},
                    const std::vector<std::string>& signed_channels = {});

// Every channel of an image with its names and its header's string attributes (data
// interleaved, row-major). Throws InputError naming the path.
struct Channels {
    int width = 0, height = 0;
    std::vector<std::string> names;
    std::vector<double> data;
    std::vector<std::pair<std::string, std::string>> attributes;
    const std::string* attribute(const std::string& name) const;
    int channel(const std::string& name) const;  // −1 when absent
};
Channels read_channels(const std::string& path);

// Reads any image OpenImageIO can read, as stored (integer formats scaled to [0, 1],
// no transfer function applied: POV-Ray's File_Gamma=1.0 PNGs are linear as read).
// Throws InputError naming the path; before reading a pixel for a file that is missing,
// a directory, not a regular file (a pipe, a device), a PNM file shorter than its header
// announces, or an image beyond 2^26 pixels or 2^28 values (docs/limits.md).
Image read_image(const std::string& path);

// sRGB transfer function (IEC 61966-2-1), linear → encoded, clamped to [0, 1].
double srgb_encode(double linear);

}  // namespace refract
