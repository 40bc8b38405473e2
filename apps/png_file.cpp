#include "png_file.h"

#include <csetjmp>
#include <cstdio>
#include <fmt/format.h>
#include <png.h>
#include <vector>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo::app {

namespace {

/// libpng reports errors by longjmp; this keeps the message for the exception.
struct PngError {
    std::string message;
};

void onError(png_structp png, png_const_charp message)
{
    static_cast<PngError*>(png_get_error_ptr(png))->message = message;
    png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

void writeRgb(const std::string& path, const gl::Image& image)
{
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw IoError(fmt::format("{}: cannot be created", path));
    std::vector<uint8_t> rgb(size_t(image.width) * 3 * size_t(image.height));
    for (size_t i = 0, n = size_t(image.width) * size_t(image.height); i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + size_t(c)] = image.rgba[4 * i + size_t(c)];
    PngError error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    // Nothing with a destructor may be created between setjmp and the end of the writes.
    bool ok = png && info && setjmp(png_jmpbuf(png)) == 0;
    if (ok) {
        png_init_io(png, f);
        png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, PNG_COLOR_TYPE_RGB,
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (int y = 0; y < image.height; ++y) png_write_row(png, &rgb[size_t(y) * size_t(image.width) * 3]);
        png_write_end(png, nullptr);
    }
    png_destroy_write_struct(png ? &png : nullptr, info ? &info : nullptr);
    const bool closed = std::fclose(f) == 0;
    if (!ok) throw IoError(fmt::format("{}: PNG writing failed: {}", path, error.message.empty() ? "out of memory" : error.message));
    if (!closed) throw IoError(fmt::format("{}: writing failed", path));
}

} // namespace

void writePng(const std::string& path, const gl::Image& image)
{
    writeAtomically(path, [&](const std::string& tmp) { writeRgb(tmp, image); });
}

} // namespace svo::app
