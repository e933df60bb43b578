#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "geometry/atomic_file.h"
#include "geometry/error.h"

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

// Writes through a TempFile beside `path` (geometry/atomic_file.h).
void write_atomically(const std::string& path, const OIIO::ImageSpec& spec, const void* data);

}  // namespace

void check_image_path(const std::string& path) {
    const std::string ext = lower_extension(path);
    const bool linear_float = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
    const bool encoded = ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".bmp";
    if (!linear_float && !encoded)
        throw InputError(path + ": unknown image extension '" + ext +
                         "' (use .exr, .hdr, .tif for linear, .png, .jpg, .ppm, .bmp for sRGB)");
    if (!OIIO::ImageOutput::create(path))
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
    OIIO::ImageSpec spec;
    std::vector<float> fbuf;
    std::vector<unsigned short> sbuf;
    std::vector<unsigned char> bbuf;
    const void* data = nullptr;
    if (linear_float) {
        spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT);
        fbuf.resize(n);
        for (size_t k = 0; k < n; ++k) fbuf[k] = static_cast<float>(img.rgb[k]);
        data = fbuf.data();
    } else if (ext == ".png" && opt.linear16) {
        spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::UINT16);
        spec.attribute("oiio:ColorSpace", "Linear");
        sbuf.resize(n);
        for (size_t k = 0; k < n; ++k)
            sbuf[k] = static_cast<unsigned short>(std::lround(std::clamp(img.rgb[k], 0.0, 1.0) * 65535.0));
        data = sbuf.data();
    } else {
        spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        bbuf.resize(n);
        for (size_t k = 0; k < n; ++k)
            bbuf[k] = static_cast<unsigned char>(std::lround(srgb_encode(img.rgb[k]) * 255.0));
        data = bbuf.data();
    }
    write_atomically(path, spec, data);
}

void write_channels(const std::string& path, int width, int height, const std::vector<std::string>& names,
                    const std::vector<double>& data,
                    const std::vector<std::pair<std::string, std::string>>& attributes) {
    if (lower_extension(path) != ".exr") throw InputError(path + ": named channels need an .exr file");
    check_image_path(path);
    const size_t n = static_cast<size_t>(width) * height * names.size();
    if (width <= 0 || height <= 0 || names.empty() || data.size() != n)
        throw InputError(path + ": channel data do not match the image size");
    OIIO::ImageSpec spec(width, height, static_cast<int>(names.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    for (const auto& [name, value] : attributes) spec.attribute(name, value);
    std::vector<float> buf(n);
    for (size_t k = 0; k < n; ++k) buf[k] = static_cast<float>(data[k]);
    write_atomically(path, spec, buf.data());
}

namespace {

void write_atomically(const std::string& path, const OIIO::ImageSpec& spec, const void* data) {
    // The temporary keeps the extension so that OpenImageIO picks the right writer.
    TempFile tmp(path, true);
    auto out = OIIO::ImageOutput::create(tmp.path());
    if (!out) throw InputError(path + ": no image writer for this extension");
    if (!(out->open(tmp.path(), spec) && out->write_image(spec.format, data) && out->close()))
        throw InputError(path + ": cannot write image: " + out->geterror());
    tmp.commit();
}

}  // namespace

namespace {

// Images read are bounded as images rendered are (docs/limits.md): before any allocation.
void check_read_size(const std::string& path, const OIIO::ImageSpec& spec) {
    const double values = static_cast<double>(spec.width) * spec.height * spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || static_cast<double>(spec.width) * spec.height > 67108864.0 ||
        spec.nchannels <= 0 || values > 268435456.0)
        throw InputError(path + ": a " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " image of " +
                         std::to_string(spec.nchannels) + " channels is beyond the limit of 2^26 pixels and 2^28 values");
}

}  // namespace

Image read_image(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    check_read_size(path, spec);
    Image img(spec.width, spec.height);
    std::vector<float> buf(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buf.data()))
        throw InputError(path + ": cannot read image: " + in->geterror());
    for (int j = 0; j < spec.height; ++j)
        for (int i = 0; i < spec.width; ++i) {
            const size_t k = (static_cast<size_t>(j) * spec.width + i) * spec.nchannels;
            const double r = buf[k];
            const double g = spec.nchannels >= 3 ? buf[k + 1] : r;
            const double b = spec.nchannels >= 3 ? buf[k + 2] : r;
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
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    check_read_size(path, spec);
    Channels c;
    c.width = spec.width;
    c.height = spec.height;
    c.names = spec.channelnames;
    std::vector<float> buf(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buf.data()))
        throw InputError(path + ": cannot read image: " + in->geterror());
    c.data.assign(buf.begin(), buf.end());
    for (const auto& p : spec.extra_attribs)
        if (p.type() == OIIO::TypeDesc::STRING) c.attributes.emplace_back(p.name().string(), p.get_string());
    return c;
}

}  // namespace refract
