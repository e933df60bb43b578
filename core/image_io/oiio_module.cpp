// The image module (core/image_io.h): every use of OpenImageIO in refract, built as a
// shared module that core loads on the first image read or write. No exception leaves it.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>

#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
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

// Writing through a descriptor the caller opened (a TempFile's): OpenImageIO reads and
// writes at offsets of it and never opens a file by name. close() leaves it to the caller.
class FdProxy final : public OIIO::Filesystem::IOProxy {
public:
    FdProxy(int fd, const std::string& name) : IOProxy(name, Write), fd_(fd) {}
    const char* proxytype() const override { return "refract-fd"; }
    void close() override { m_mode = Closed; }
    size_t write(const void* buf, size_t size) override {
        const size_t n = pwrite(buf, size, m_pos);
        m_pos += static_cast<int64_t>(n);
        return n;
    }
    size_t read(void* buf, size_t size) override {
        const size_t n = pread(buf, size, m_pos);
        m_pos += static_cast<int64_t>(n);
        return n;
    }
    size_t pwrite(const void* buf, size_t size, int64_t offset) override {
        size_t done = 0;
        while (done < size) {
            const ssize_t n = ::pwrite(fd_, static_cast<const char*>(buf) + done, size - done, offset + done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                error(std::strerror(n < 0 ? errno : ENOSPC));
                break;
            }
            done += static_cast<size_t>(n);
        }
        return done;
    }
    size_t pread(void* buf, size_t size, int64_t offset) override {
        size_t done = 0;
        while (done < size) {
            const ssize_t n = ::pread(fd_, static_cast<char*>(buf) + done, size - done, offset + done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            done += static_cast<size_t>(n);
        }
        return done;
    }
    size_t size() const override {
        struct stat st {};
        return ::fstat(fd_, &st) == 0 ? static_cast<size_t>(st.st_size) : 0;
    }

private:
    int fd_;
};

// The writer for the extension of `name`, set to write through `proxy`; an error status
// when there is none or it cannot write through a proxy. (OpenImageIO 2.4.7's TIFF writer
// through a proxy writes a broken file once the header needs an Exif directory, as an
// oiio:ColorSpace does: refract's TIFFs are linear float and carry none.)
IoStatus writer_for(const std::string& name, OIIO::Filesystem::IOProxy& proxy, std::unique_ptr<OIIO::ImageOutput>& out) {
    out = OIIO::ImageOutput::create(name);
    if (!out) return {"no image writer for this extension"};
    if (!out->supports("ioproxy"))
        return {std::string("the ") + out->format_name() + " writer of this OpenImageIO cannot write to an open file"};
    out->set_ioproxy(&proxy);
    return {};
}

bool can_write(const std::string& path) {
    try {
        return OIIO::ImageOutput::create(path) != nullptr;
    } catch (...) {
        return false;
    }
}

IoStatus write(int fd, const std::string& file, int width, int height, int nchannels, PixelType type,
               const void* data, const std::vector<std::string>& names, const std::string& colorspace,
               const std::vector<std::pair<std::string, std::string>>& attributes) {
    return guarded([&]() -> IoStatus {
        OIIO::ImageSpec spec(width, height, nchannels, type_of(type));
        if (!names.empty()) spec.channelnames = names;
        if (!colorspace.empty()) spec.attribute("oiio:ColorSpace", colorspace);
        for (const auto& [name, value] : attributes) {
            if (name == "chromaticities") {  // OpenEXR's: 8 floats (red, green, blue, white xy), given as text
                float c[8] = {};
                if (std::sscanf(value.c_str(), "%f %f %f %f %f %f %f %f", &c[0], &c[1], &c[2], &c[3], &c[4], &c[5],
                                &c[6], &c[7]) != 8)
                    return {"chromaticities: expected 8 numbers"};
                spec.attribute(name, OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), c);
            } else {
                spec.attribute(name, value);
            }
        }
        FdProxy proxy(fd, file);
        std::unique_ptr<OIIO::ImageOutput> out;
        if (IoStatus s = writer_for(file, proxy, out); !s.ok()) return s;
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
            if (p.type() == OIIO::TypeDesc::STRING || p.name() == "chromaticities")  // the latter as text
                out.attributes.emplace_back(p.name().string(), p.get_string());
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

IoStatus heatmap(const double* a, const double* b, int width, int height, int fd, const std::string& file) {
    return guarded([&]() -> IoStatus {
        OIIO::ImageBuf diff = IBA::maxchan(IBA::absdiff(to_buf(a, width, height), to_buf(b, width, height)));
        // Log scale (OpenImageIO has no log operator): 1e-6 -> 0, 1e-1 -> 1.
        for (OIIO::ImageBuf::Iterator<float> it(diff); !it.done(); ++it) {
            const float v = it[0];
            it[0] = v <= 1e-6f ? 0.0f : std::clamp((std::log10(v) + 6.0f) / 5.0f, 0.0f, 1.0f);
        }
        OIIO::ImageBuf heat = IBA::color_map(diff, 0, "inferno");
        if (heat.has_error()) return {"cannot build heat map: " + heat.geterror()};
        FdProxy proxy(fd, file);
        std::unique_ptr<OIIO::ImageOutput> out;
        if (IoStatus s = writer_for(file, proxy, out); !s.ok()) return s;
        OIIO::ImageSpec spec = heat.spec();
        spec.set_format(OIIO::TypeDesc::UINT8);
        if (!(out->open(file, spec) && heat.write(out.get()) && out->close()))
            return {"cannot write heat map: " + out->geterror() + heat.geterror()};
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
