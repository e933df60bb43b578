#include <refract/core/image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <unistd.h>

#include <refract/core/image_io.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace refract {

double srgb_encode(double linear) {
    // IEC 61966-2-1.
    const double c = std::clamp(linear, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// Writes through a TempFile beside `path` (geometry/atomic_file.h) with the image module.
void write_atomically(const std::string& path, int width, int height, int nchannels, PixelType type, const void* data,
                      const std::vector<std::string>& names = {}, const std::string& colorspace = {},
                      const std::vector<std::pair<std::string, std::string>>& attributes = {});

// What is written is checked value by value, as stored, before anything is converted:
// finite (for the float formats, as a float: 1e300 would be written as infinity, and the
// conversion itself is undefined), and >= 0 once stored unless the channel may be negative
// (`is_signed`, per channel). A value that fails is refract's own error (scenes are
// checked on loading so that none can arise): reported naming the pixel and the channel,
// before anything is written.
void check_written(const std::string& path, int width, const std::vector<std::string>& names,
                   const std::vector<bool>& is_signed, const std::vector<double>& values, bool as_float) {
    const size_t nc = names.size();
    for (size_t k = 0; k < values.size(); ++k) {
        const double v = values[k];
        const bool finite = std::isfinite(v) && (!as_float || std::fabs(v) <= std::numeric_limits<float>::max());
        const double stored = finite && as_float ? static_cast<double>(static_cast<float>(v)) : v;
        if (finite && (is_signed[k % nc] || !(stored < 0))) continue;
        const size_t pixel = k / nc;
        throw std::runtime_error("internal error: " + path + ": pixel (" + std::to_string(pixel % width) + ", " +
                                 std::to_string(pixel / width) + ") channel " + names[k % nc] + " is " +
                                 format_value(v) + (finite ? ", negative" : ", not finite as stored") +
                                 "; nothing was written; please report it");
    }
}

}  // namespace

void check_image_path(const std::string& path) {
    const std::string ext = lower_extension(path);
    const bool linear_float = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
    const bool encoded = ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".bmp";
    if (!linear_float && !encoded)
        throw InputError(path + ": unknown image extension '" + ext +
                         "' (use .exr, .hdr, .tif for linear, .png, .jpg, .ppm, .bmp for sRGB)");
    if (!image_io().can_write(path))
        throw InputError(path + ": this OpenImageIO has no writer for '" + ext + "' files");
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory, not an image file");
    const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    if (!fs::is_directory(dir, ec)) throw InputError(path + ": the directory " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0) throw InputError(path + ": the directory " + dir.string() + " is not writable");
}

void write_image(const std::string& path, const Image& img, const WriteOptions& opt) {
    if (img.width <= 0 || img.height <= 0) throw InputError(path + ": cannot write an empty image");
    check_image_path(path);
    const std::string ext = lower_extension(path);
    const bool linear_float = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
    const size_t n = img.rgb.size();
    const std::vector<std::string> names{"R", "G", "B"};
    if (linear_float) {
        check_written(path, img.width, names, std::vector<bool>(3, opt.signed_values), img.rgb, true);
        std::vector<float> buf(n);
        for (size_t k = 0; k < n; ++k) buf[k] = static_cast<float>(img.rgb[k]);
        write_atomically(path, img.width, img.height, 3, PixelType::float32, buf.data());
        return;
    }
    // The integer formats clamp to [0, 1] (negative values are written as 0): only a value
    // that is not finite is an error there.
    check_written(path, img.width, names, std::vector<bool>(3, true), img.rgb, false);
    if (ext == ".png" && opt.linear16) {
        std::vector<unsigned short> buf(n);
        for (size_t k = 0; k < n; ++k)
            buf[k] = static_cast<unsigned short>(std::lround(std::clamp(img.rgb[k], 0.0, 1.0) * 65535.0));
        write_atomically(path, img.width, img.height, 3, PixelType::uint16, buf.data(), {}, "Linear");
    } else {
        std::vector<unsigned char> buf(n);
        for (size_t k = 0; k < n; ++k)
            buf[k] = static_cast<unsigned char>(std::lround(srgb_encode(img.rgb[k]) * 255.0));
        write_atomically(path, img.width, img.height, 3, PixelType::uint8, buf.data(), {}, "sRGB");
    }
}

void write_channels(const std::string& path, int width, int height, const std::vector<std::string>& names,
                    const std::vector<double>& data,
                    const std::vector<std::pair<std::string, std::string>>& attributes,
                    const std::vector<std::string>& signed_channels) {
    if (lower_extension(path) != ".exr") throw InputError(path + ": named channels need an .exr file");
    check_image_path(path);
    const size_t n = static_cast<size_t>(width) * height * names.size();
    if (width <= 0 || height <= 0 || names.empty() || data.size() != n)
        throw InputError(path + ": channel data do not match the image size");
    std::vector<bool> is_signed(names.size());
    for (size_t c = 0; c < names.size(); ++c)
        is_signed[c] = std::find(signed_channels.begin(), signed_channels.end(), names[c]) != signed_channels.end();
    check_written(path, width, names, is_signed, data, true);
    std::vector<float> buf(n);
    for (size_t k = 0; k < n; ++k) buf[k] = static_cast<float>(data[k]);
    write_atomically(path, width, height, static_cast<int>(names.size()), PixelType::float32, buf.data(), names, {},
                     attributes);
}

namespace {

void write_atomically(const std::string& path, int width, int height, int nchannels, PixelType type, const void* data,
                      const std::vector<std::string>& names, const std::string& colorspace,
                      const std::vector<std::pair<std::string, std::string>>& attributes) {
    const ImageIoModule& io = image_io();
    // The temporary keeps the extension so that OpenImageIO picks the right writer.
    TempFile tmp(path, true);
    throw_if_failed(io.write(tmp.path(), width, height, nchannels, type, data, names, colorspace, attributes), path);
    tmp.commit();
}

}  // namespace

namespace {

// Images read are bounded as images rendered are (docs/limits.md): before any allocation.
// The message after "<path>: ", empty when within the limits.
std::string check_read_size(const ImageData& h) {
    const double values = static_cast<double>(h.width) * h.height * h.nchannels;
    if (h.width <= 0 || h.height <= 0 || static_cast<double>(h.width) * h.height > 67108864.0 || h.nchannels <= 0 ||
        values > 268435456.0)
        return "a " + std::to_string(h.width) + "x" + std::to_string(h.height) + " image of " +
               std::to_string(h.nchannels) + " channels is beyond the limit of 2^26 pixels and 2^28 values";
    return {};
}

ImageData read_data(const std::string& path) {
    ImageData d;
    throw_if_failed(image_io().read(path, d, check_read_size), path);
    return d;
}

}  // namespace

Image read_image(const std::string& path) {
    const ImageData d = read_data(path);
    Image img(d.width, d.height);
    for (int j = 0; j < d.height; ++j)
        for (int i = 0; i < d.width; ++i) {
            const size_t k = (static_cast<size_t>(j) * d.width + i) * d.nchannels;
            const double r = d.data[k];
            const double g = d.nchannels >= 3 ? d.data[k + 1] : r;
            const double b = d.nchannels >= 3 ? d.data[k + 2] : r;
            img.set(i, j, {r, g, b});
        }
    return img;
}

const std::string* Channels::attribute(const std::string& name) const {
    for (const auto& [k, v] : attributes)
        if (k == name) return &v;
    return nullptr;
}

int Channels::channel(const std::string& name) const {
    for (size_t k = 0; k < names.size(); ++k)
        if (names[k] == name) return static_cast<int>(k);
    return -1;
}

Channels read_channels(const std::string& path) {
    ImageData d = read_data(path);
    Channels c;
    c.width = d.width;
    c.height = d.height;
    c.names = std::move(d.names);
    c.data.assign(d.data.begin(), d.data.end());
    c.attributes = std::move(d.attributes);
    return c;
}

}  // namespace refract
