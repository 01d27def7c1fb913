// SPDX-License-Identifier: MIT
#include "export/png.h"

#include "core/error.h"
#include "export/internal/cairo_paint.h"

#include <cairo.h>
#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace inkline::output {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// The Sub filter, then run-length deflate (zlib's Z_RLE: matches at distance 1 only). Line art
// is long runs of one pixel (transparent, the background, solid ink); Sub turns any such run
// into a run of zero bytes, whatever its colour, and Z_RLE finds those as well as the full
// matcher does in a fraction of the time. On the torus sample and Suzanne at 1024x1024, against
// Cairo's encoder (libpng's defaults: zlib level 6, adaptive filters): encoding 3.4-3.8x
// faster, files 1.00-1.08x the size (bench/png/). Unfiltered Z_RLE is a little faster still, but only
// for runs of repeated bytes: on a coloured background its files grow 17x.
constexpr int kZlibLevel = 1;  // any level but 0 is the same for Z_RLE
constexpr int kZlibStrategy = Z_RLE;
constexpr int kPngFilters = PNG_FILTER_SUB;
// Bytes of compressed data per IDAT chunk (libpng's default is 8 KiB).
constexpr size_t kIdatBytes = 64 * 1024;

// A blank ARGB32 image surface.
Surface image_surface(int width, int height) {
    check_png_size(width, height);
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
    internal::check_cairo(cairo_surface_status(surface.get()), "PNG image surface");
    return surface;
}

// What libpng's callbacks reach: the output, and why encoding stopped.
struct EncodeState {
    std::string* bytes = nullptr;
    bool out_of_memory = false;
    std::string error;  // libpng's message
};

void on_png_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<EncodeState*>(png_get_error_ptr(png));
    try {
        if (state->error.empty()) state->error = message ? message : "libpng error";
    } catch (const std::bad_alloc&) {
        state->out_of_memory = true;
    }
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

void append_png_bytes(png_structp png, png_bytep data, png_size_t length) {
    auto* state = static_cast<EncodeState*>(png_get_io_ptr(png));
    try {
        state->bytes->append(reinterpret_cast<const char*>(data), length);
    } catch (const std::bad_alloc&) {
        state->out_of_memory = true;
    }
    // Outside the handler: png_error() longjmps.
    if (state->out_of_memory) png_error(png, "out of memory");
}

void flush_png_bytes(png_structp) {}

png_voidp allocate_for_png(png_structp png, png_alloc_size_t size) {
    void* p = std::malloc(size);
    if (!p) static_cast<EncodeState*>(png_get_mem_ptr(png))->out_of_memory = true;
    return p;
}

void free_for_png(png_structp, png_voidp p) { std::free(p); }

// Cairo's ARGB32 image (premultiplied, one native-endian word per pixel) as PNG rows, exactly
// as cairo_surface_write_to_png_stream converts them: RGB when every pixel is opaque, else
// RGBA un-premultiplied with Cairo's rounding. Same rows, same decoded image.
class PngRows {
  public:
    explicit PngRows(cairo_surface_t* image)
        : data_(cairo_image_surface_get_data(image)),
          width_(cairo_image_surface_get_width(image)),
          height_(cairo_image_surface_get_height(image)),
          stride_(size_t(cairo_image_surface_get_stride(image))) {
        for (int y = 0; y < height_ && opaque_; ++y) {
            const uint32_t* row = pixels(y);
            for (int x = 0; x < width_; ++x) {
                if (row[x] >> 24 != 0xff) {
                    opaque_ = false;
                    break;
                }
            }
        }
        row_.resize(size_t(width_) * (opaque_ ? 3 : 4));
    }

    bool opaque() const { return opaque_; }
    int width() const { return width_; }
    int height() const { return height_; }

    // Row y in PNG byte order; valid until the next call.
    png_bytep row(int y) {
        const uint32_t* in = pixels(y);
        uint8_t* out = row_.data();
        if (opaque_) {
            for (int x = 0; x < width_; ++x, out += 3) {
                out[0] = uint8_t(in[x] >> 16);
                out[1] = uint8_t(in[x] >> 8);
                out[2] = uint8_t(in[x]);
            }
            return row_.data();
        }
        for (int x = 0; x < width_; ++x, out += 4) {
            const uint32_t p = in[x], alpha = p >> 24;
            if (alpha == 0) {
                std::memset(out, 0, 4);
            } else if (alpha == 0xff) {
                out[0] = uint8_t(p >> 16);
                out[1] = uint8_t(p >> 8);
                out[2] = uint8_t(p);
                out[3] = 0xff;
            } else {
                // Cairo's unpremultiply_data(), its uint8_t truncation included.
                out[0] = uint8_t((((p >> 16) & 0xff) * 255 + alpha / 2) / alpha);
                out[1] = uint8_t((((p >> 8) & 0xff) * 255 + alpha / 2) / alpha);
                out[2] = uint8_t(((p & 0xff) * 255 + alpha / 2) / alpha);
                out[3] = uint8_t(alpha);
            }
        }
        return row_.data();
    }

  private:
    const uint32_t* pixels(int y) const { return reinterpret_cast<const uint32_t*>(data_ + size_t(y) * stride_); }

    const unsigned char* data_;
    int width_, height_;
    size_t stride_;
    bool opaque_ = true;
    std::vector<uint8_t> row_;
};

// Writes the PNG through libpng; returns false when libpng stopped with an error (`state`
// says which). Holds nothing that needs destroying: libpng's errors longjmp out of it.
bool write_png(png_structp png, png_infop info, PngRows& rows, EncodeState& state) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, &state, append_png_bytes, flush_png_bytes);
    png_set_IHDR(png, info, png_uint_32(rows.width()), png_uint_32(rows.height()), 8,
                 rows.opaque() ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // White background, as Cairo's encoder writes it: viewers that honour bKGD show the same.
    png_color_16 white{};
    white.red = white.green = white.blue = white.gray = 0xff;
    png_set_bKGD(png, info, &white);
    png_set_compression_level(png, kZlibLevel);
    png_set_compression_strategy(png, kZlibStrategy);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, kPngFilters);
    png_set_compression_buffer_size(png, kIdatBytes);
    png_write_info(png, info);
    for (int y = 0; y < rows.height(); ++y) png_write_row(png, rows.row(y));
    png_write_end(png, info);
    return true;
}

std::string encode_png(const Surface& surface) {
    cairo_surface_flush(surface.get());
    internal::check_cairo(cairo_surface_status(surface.get()), "PNG drawing");
    PngRows rows(surface.get());
    std::string bytes;
    // Line art deflates to well under a bit a pixel: a guess that saves most regrowing.
    bytes.reserve(size_t(rows.width()) * size_t(rows.height()) / 16 + 1024);
    EncodeState state;
    state.bytes = &bytes;
    png_structp png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning, &state,
                                                allocate_for_png, free_for_png);
    if (!png) throw std::bad_alloc();
    png_infop info = png_create_info_struct(png);
    const bool have_info = info != nullptr;
    const bool written = have_info && write_png(png, info, rows, state);
    png_destroy_write_struct(&png, have_info ? &info : nullptr);
    if (!have_info || state.out_of_memory) throw std::bad_alloc();
    if (!written) throw OutputError("PNG encoding: " + state.error);
    return bytes;
}

}  // namespace

void check_png_size(int width, int height) {
    if (width > kMaxPngSide || height > kMaxPngSide) {
        throw InputError("PNG of " + std::to_string(width) + "x" + std::to_string(height) +
                         " px: Cairo draws images of at most " + std::to_string(kMaxPngSide) + " px a side");
    }
    INKLINE_CHECK(width > 0 && height > 0);
}

std::string png_image(const Drawing& drawing) {
    const Surface surface = image_surface(drawing.image.width, drawing.image.height);
    {
        const std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
        internal::check_cairo(cr.get(), "PNG drawing");
        internal::paint_drawing(cr.get(), drawing);
        // Cairo records a failure (out of memory in a layer group, say) in the context and draws
        // nothing more: a blank or half-drawn image is never encoded.
        internal::check_cairo(cr.get(), "PNG drawing");
    }
    return encode_png(surface);
}

std::string png_from_rgba(int width, int height, std::span<const uint8_t> rgba) {
    INKLINE_CHECK(width > 0 && height > 0);
    INKLINE_CHECK_EQ(rgba.size(), size_t(width) * size_t(height) * 4);
    const Surface surface = image_surface(width, height);
    // Cairo's ARGB32 is premultiplied, one native-endian 32-bit word per pixel. Going through it
    // keeps the files these pixels made before (premultiplied, then un-premultiplied on encoding).
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < height; ++y) {
        auto* row = reinterpret_cast<uint32_t*>(data + size_t(y) * size_t(stride));
        for (int x = 0; x < width; ++x) {
            const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
            const uint32_t a = p[3];
            auto premultiply = [a](uint32_t c) { return (c * a + 127) / 255; };
            row[x] = a << 24 | premultiply(p[0]) << 16 | premultiply(p[1]) << 8 | premultiply(p[2]);
        }
    }
    cairo_surface_mark_dirty(surface.get());
    return encode_png(surface);
}

}  // namespace inkline::output
