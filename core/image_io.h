#pragma once
// OpenImageIO lives in a plugin, core/image_io/ (a shared module linked to it), loaded on
// the first image read or write: a process that reads and writes no image (refract --help,
// refract trace) does not load the ~260 shared libraries OpenImageIO brings. The module's
// table holds plain functions that throw nothing across the boundary; they report an
// IoStatus. Both sides are built by the same compiler from this tree, so the table passes
// standard-library types.
#include <string>
#include <utility>
#include <vector>

namespace refract {

// What a module function reports: success (empty), a message for the InputError the
// caller throws (the text after "<path>: "), or an exception caught inside the module
// (std::bad_alloc...), which the caller throws again as std::runtime_error.
struct IoStatus {
    std::string error;
    bool exception = false;
    bool ok() const { return error.empty(); }
};

// Pixels as the module reads them: every channel, float, interleaved, row-major.
struct ImageData {
    int width = 0, height = 0, nchannels = 0;
    std::vector<std::string> names;
    std::vector<float> data;
    std::vector<std::pair<std::string, std::string>> attributes;  // the header's string attributes
};

// What OpenImageIO's ImageBufAlgo::compare reports.
struct CompareStats {
    double rms_error = 0, max_error = 0, mean_error = 0;
    int max_x = -1, max_y = -1;
    long long nfail = 0;
};

enum class PixelType { uint8, uint16, float32 };

struct ImageIoModule {
    int version;    // kImageIoVersion and sizeof(ImageIoModule): the module and refract
    unsigned size;  // built from the same tree
    // True when OpenImageIO has a writer for the file's extension.
    bool (*can_write)(const std::string& path);
    // Writes `data` (width × height × nchannels values of `type`, interleaved) through
    // `fd`, an empty file open for reading and writing (a TempFile's, geometry/atomic_file.h;
    // OpenImageIO writes through an IOProxy on it and opens no file by name); the format
    // follows the extension of `file`, the target's name. Empty `names`: OpenImageIO's
    // defaults. `colorspace` (may be empty) and `attributes` go into the header.
    IoStatus (*write)(int fd, const std::string& file, int width, int height, int nchannels, PixelType type,
                      const void* data, const std::vector<std::string>& names, const std::string& colorspace,
                      const std::vector<std::pair<std::string, std::string>>& attributes);
    // Reads every channel of `path`. `check(header)` runs on the header before any pixel
    // is allocated; a message from it is returned as the error.
    IoStatus (*read)(const std::string& path, ImageData& out, std::string (*check)(const ImageData& header));
    // The validation's operations on RGB images of one size (double, 3 per pixel), on float
    // copies: ImageBufAlgo::compare (`tolerance` for failure and warning), every channel
    // clamped to [0, 1] into `out`.
    IoStatus (*compare)(const double* a, const double* b, int width, int height, double tolerance,
                        CompareStats& out);
    IoStatus (*clamp01)(const double* rgb, int width, int height, double* out);
    // The log-scale difference heat map (validation/compare.h), 8-bit, written through
    // `fd` as `write` does, in the format of the extension of `file`.
    IoStatus (*heatmap)(const double* a, const double* b, int width, int height, int fd, const std::string& file);
};

constexpr int kImageIoVersion = 2;

// The module's one entry point.
using ImageIoEntry = const ImageIoModule* (*)();
constexpr const char* kImageIoEntry = "refract_image_io_module";

// The loaded module (dlopen once, thread-safe). Looked for in $REFRACT_IMAGE_IO when set,
// else beside the executable, in its ../lib/refract, then in the build tree. InputError
// naming the module and the loader's message when it cannot be loaded.
const ImageIoModule& image_io();

// Throws what a failed status reports: InputError("<path>: <error>") (just the error when
// `path` is empty), or std::runtime_error for an exception inside the module.
void throw_if_failed(const IoStatus& status, const std::string& path);

}  // namespace refract
