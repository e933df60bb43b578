// The image module (core/image_io.h): every use of OpenImageIO in refract, built as a
// shared module that core loads on the first image read or write. No exception leaves it.
#include <algorithm>
#include <cmath>
#include <exception>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <refract/core/image_io.h>

namespace refract {
namespace {

namespace IBA = OIIO::ImageBufAlgo;

// Runs `body`, turning any exception into a status.
template <class F>
IoStatus guarded(F&& body) {
    try {
        return body();
    } catch (const std::exception& e) {
        return {e.what(), true};
    } catch (...) {
        return {"unknown exception in the image module", true};
    }
}

OIIO::TypeDesc type_of(PixelType t) {
    switch (t) {
    case PixelType::uint8: return OIIO::TypeDesc::UINT8;
    case PixelType::uint16: return OIIO::TypeDesc::UINT16;
    default: return OIIO::TypeDesc::FLOAT;
    }
}

bool can_write(const std::string& path) {
    try {
        return OIIO::ImageOutput::create(path) != nullptr;
    } catch (...) {
        return false;
    }
}

IoStatus write(const std::string& file, int width, int height, int nchannels, PixelType type, const void* data,
               const std::vector<std::string>& names, const std::string& colorspace,
               const std::vector<std::pair<std::string, std::string>>& attributes) {
    return guarded([&]() -> IoStatus {
        OIIO::ImageSpec spec(width, height, nchannels, type_of(type));
        if (!names.empty()) spec.channelnames = names;
        if (!colorspace.empty()) spec.attribute("oiio:ColorSpace", colorspace);
        for (const auto& [name, value] : attributes) spec.attribute(name, value);
        auto out = OIIO::ImageOutput::create(file);
        if (!out) return {"no image writer for this extension"};
        if (!(out->open(file, spec) && out->write_image(spec.format, data) && out->close()))
            return {"cannot write image: " + out->geterror()};
        return {};
    });
}

// OpenImageIO's message, or a reason when it gives none (its PNM reader, on a file
// shorter than its header announces).
std::string reason(const std::string& error) {
    return "cannot read image: " + (error.empty() ? std::string("truncated or malformed (no detail given)") : error);
}

IoStatus read(const std::string& path, ImageData& out, std::string (*check)(const ImageData& header)) {
    return guarded([&]() -> IoStatus {
        auto in = OIIO::ImageInput::open(path);
        if (!in) return {reason(OIIO::geterror())};
        const OIIO::ImageSpec& spec = in->spec();
        out.width = spec.width;
        out.height = spec.height;
        out.nchannels = spec.nchannels;
        if (std::string e = check(out); !e.empty()) return {e};
        out.names = spec.channelnames;
        out.data.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.data.data()))
            return {reason(in->geterror())};
        for (const auto& p : spec.extra_attribs)
            if (p.type() == OIIO::TypeDesc::STRING) out.attributes.emplace_back(p.name().string(), p.get_string());
        return {};
    });
}

OIIO::ImageBuf to_buf(const double* rgb, int width, int height) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::DOUBLE, rgb);
    return buf;
}

IoStatus compare(const double* a, const double* b, int width, int height, double tolerance, CompareStats& out) {
    return guarded([&]() -> IoStatus {
        const auto r = IBA::compare(to_buf(a, width, height), to_buf(b, width, height), static_cast<float>(tolerance),
                                    static_cast<float>(tolerance));
        // (r.error is also set when any pixel fails the threshold: not an error here.)
        out = {r.rms_error, r.maxerror, r.meanerror, r.maxx, r.maxy, static_cast<long long>(r.nfail)};
        return {};
    });
}

IoStatus clamp01(const double* rgb, int width, int height, double* out) {
    return guarded([&]() -> IoStatus {
        const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
        const OIIO::ImageBuf c = IBA::clamp(to_buf(rgb, width, height), lo, hi);
        OIIO::ROI roi = c.roi();
        roi.chend = 3;
        c.get_pixels(roi, OIIO::TypeDesc::DOUBLE, out);
        return {};
    });
}

IoStatus heatmap(const double* a, const double* b, int width, int height, const std::string& file) {
    return guarded([&]() -> IoStatus {
        OIIO::ImageBuf diff = IBA::maxchan(IBA::absdiff(to_buf(a, width, height), to_buf(b, width, height)));
        // Log scale (OpenImageIO has no log operator): 1e-6 -> 0, 1e-1 -> 1.
        for (OIIO::ImageBuf::Iterator<float> it(diff); !it.done(); ++it) {
            const float v = it[0];
            it[0] = v <= 1e-6f ? 0.0f : std::clamp((std::log10(v) + 6.0f) / 5.0f, 0.0f, 1.0f);
        }
        OIIO::ImageBuf heat = IBA::color_map(diff, 0, "inferno");
        if (heat.has_error()) return {"cannot build heat map: " + heat.geterror()};
        heat.set_write_format(OIIO::TypeDesc::UINT8);
        if (!heat.write(file)) return {"cannot write heat map: " + heat.geterror()};
        return {};
    });
}

const ImageIoModule module = {kImageIoVersion, sizeof(ImageIoModule), can_write, write, read, compare, clamp01,
                              heatmap};

}  // namespace
}  // namespace refract

extern "C" __attribute__((visibility("default"))) const refract::ImageIoModule* refract_image_io_module() {
    return &refract::module;
}
