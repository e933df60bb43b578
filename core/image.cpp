#include <refract/core/image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <limits>
#include <stdexcept>
#include <unistd.h>

#include <refract/core/image_io.h>
#include <refract/core/memory.h>
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
    // Written through the temporary's descriptor; the target's extension picks the writer.
    TempFile tmp(path);
    throw_if_failed(io.write(tmp.fd(), path, width, height, nchannels, type, data, names, colorspace, attributes), path);
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
    // Its float pixels as read and the doubles of the copy returned (RGB or every channel),
    // within the default memory budget (core/memory.h).
    const double bytes = values * 4 + std::fmax(3.0 * h.width * h.height, values) * 8;
    if (bytes > static_cast<double>(default_memory_budget()))
        return "a " + std::to_string(h.width) + "x" + std::to_string(h.height) + " image of " +
               std::to_string(h.nchannels) + " channels would need about " + format_bytes(bytes) +
               " of memory, over the budget of " + format_bytes(static_cast<double>(default_memory_budget())) +
               " (3/4 of the physical memory)";
    return {};
}

// A PNM header (P1–P6, PF, Pf) read from the start of `in`: the bytes of pixels it needs
// after it, at least (ASCII formats: one character per value), and its size as text, or
// nothing when `in` does not start with one.
struct PnmNeed {
    double bytes = 0;
    std::string what;
};
std::optional<PnmNeed> pnm_need(std::istream& in, std::uintmax_t& header_end) {
    char magic[2] = {0, 0};
    if (!in.read(magic, 2) || magic[0] != 'P') return std::nullopt;
    const char kind = magic[1];
    if (!((kind >= '1' && kind <= '6') || kind == 'F' || kind == 'f')) return std::nullopt;
    // Whitespace-separated fields; '#' starts a comment to the end of the line.
    const auto field = [&](std::string& token) {
        token.clear();
        int c = in.get();
        while (c != EOF && (std::isspace(c) || c == '#')) {
            if (c == '#')
                while (c != EOF && c != '\n' && c != '\r') c = in.get();
            c = in.get();
        }
        while (c != EOF && !std::isspace(c) && token.size() < 32) {
            token += static_cast<char>(c);
            c = in.get();
        }
        return c != EOF && !token.empty();  // the single whitespace after the field was read
    };
    const bool bitmap = kind == '1' || kind == '4', pfm = kind == 'F' || kind == 'f';
    std::string w, h, max;
    if (!field(w) || !field(h) || (!bitmap && !field(max))) return std::nullopt;
    double width = 0, height = 0, maxval = 1;
    try {
        width = std::stod(w);
        height = std::stod(h);
        if (!bitmap && !pfm) maxval = std::stod(max);
    } catch (const std::exception&) {
        return std::nullopt;  // malformed: the reader says so
    }
    const double channels = kind == '3' || kind == '6' || kind == 'F' ? 3 : 1;
    const double per_sample = pfm ? 4 : maxval < 256 ? 1 : 2;
    const double pixels = width * height;
    header_end = static_cast<std::uintmax_t>(in.tellg());
    PnmNeed need;
    need.what = w + "x" + h + " P" + std::string(1, kind);
    if (kind == '4') need.bytes = std::ceil(width / 8) * height;
    else if (kind <= '3') need.bytes = pixels * channels;  // ASCII: a character per value at least
    else need.bytes = pixels * channels * per_sample;
    return need;
}

// An image is read from a regular file (OpenImageIO would read a pipe or a device without
// end), and a PNM file must hold the pixels its header announces: a truncated file is
// refused before a pixel is allocated. InputError naming the path.
void check_image_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (st.type() == fs::file_type::not_found) throw InputError(path + ": no such file");
    if (ec) throw InputError(path + ": cannot be read (" + ec.message() + ")");
    if (fs::is_directory(st)) throw InputError(path + ": is a directory, not an image file");
    if (!fs::is_regular_file(st))
        throw InputError(path + ": not a regular file (an image is read from a file, not a pipe or a device)");
    const std::uintmax_t size = fs::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) throw InputError(path + ": cannot open image file");
    std::uintmax_t header_end = 0;
    if (const auto need = pnm_need(in, header_end); need && need->bytes > static_cast<double>(size - header_end))
        throw InputError(path + ": truncated: its header announces a " + need->what + " image of " +
                         format_value(need->bytes) + " bytes of pixels, the file holds " +
                         std::to_string(size - header_end) + " after the header");
}

ImageData read_data(const std::string& path) {
    check_image_file(path);
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
