// SPDX-License-Identifier: MIT
#include "tests/support/raster.h"

#include <cairo.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace inkline::test {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

std::vector<uint8_t> coverage(const Surface& surface, Ink ink, const std::string& what) {
    cairo_surface_t* s = surface.get();
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(what + ": " + cairo_status_to_string(cairo_surface_status(s)));
    }
    const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    const bool has_alpha = cairo_image_surface_get_format(s) == CAIRO_FORMAT_ARGB32;
    std::vector<uint8_t> out(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            // Premultiplied ARGB32 (or RGB24), one native-endian word per pixel.
            uint32_t p = 0;
            std::memcpy(&p, data + size_t(y) * size_t(stride) + 4 * size_t(x), sizeof p);
            const uint32_t a = has_alpha ? p >> 24 : 255, g = (p >> 8) & 0xff;
            const bool inked = ink == Ink::kFaint ? a > 51 : ink == Ink::kAlphaOrDark && a == 255 ? g < 128 : a > 127;
            out[size_t(y) * size_t(w) + size_t(x)] = inked;
        }
    }
    return out;
}

// A PNG in memory, decoded by Cairo.
Surface decoded(const std::string& png_bytes) {
    struct Reader {
        const std::string& bytes;
        size_t at = 0;
    } reader{png_bytes};
    auto read = [](void* closure, unsigned char* data, unsigned int length) {
        auto* r = static_cast<Reader*>(closure);
        if (r->at + length > r->bytes.size()) return CAIRO_STATUS_READ_ERROR;
        std::memcpy(data, r->bytes.data() + r->at, length);
        r->at += length;
        return CAIRO_STATUS_SUCCESS;
    };
    return Surface(cairo_image_surface_create_from_png_stream(read, &reader), cairo_surface_destroy);
}

}  // namespace

std::vector<uint8_t> png_coverage(const std::string& png_bytes, Ink ink) {
    return coverage(decoded(png_bytes), ink, "PNG in memory");
}

double png_alpha_sum(const std::string& png_bytes) {
    const Surface surface = decoded(png_bytes);
    cairo_surface_t* s = surface.get();
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(std::string("PNG in memory: ") + cairo_status_to_string(cairo_surface_status(s)));
    }
    if (cairo_image_surface_get_format(s) != CAIRO_FORMAT_ARGB32) {
        return double(cairo_image_surface_get_width(s)) * double(cairo_image_surface_get_height(s));
    }
    const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    double sum = 0.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            uint32_t p = 0;
            std::memcpy(&p, data + size_t(y) * size_t(stride) + 4 * size_t(x), sizeof p);
            sum += double(p >> 24) / 255.0;
        }
    }
    return sum;
}

std::vector<uint8_t> png_file_coverage(const std::filesystem::path& png, Ink ink) {
    return coverage(Surface(cairo_image_surface_create_from_png(png.c_str()), cairo_surface_destroy), ink,
                    png.string());
}

Pixels png_file_pixels(const std::filesystem::path& png) {
    const Surface surface(cairo_image_surface_create_from_png(png.c_str()), cairo_surface_destroy);
    cairo_surface_t* s = surface.get();
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(png.string() + ": " + cairo_status_to_string(cairo_surface_status(s)));
    }
    Pixels out{cairo_image_surface_get_width(s), cairo_image_surface_get_height(s), {}};
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    const bool has_alpha = cairo_image_surface_get_format(s) == CAIRO_FORMAT_ARGB32;
    out.rgba.reserve(size_t(out.width) * size_t(out.height));
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            uint32_t p = 0;
            std::memcpy(&p, data + size_t(y) * size_t(stride) + 4 * size_t(x), sizeof p);
            const uint32_t a = has_alpha ? p >> 24 : 255;
            // Premultiplied: the colour is divided by the alpha again.
            const auto straight = [&](uint32_t c) {
                return uint8_t(a == 0 ? 0 : std::min<uint32_t>(255, (c * 255 + a / 2) / a));
            };
            out.rgba.push_back({straight((p >> 16) & 0xff), straight((p >> 8) & 0xff), straight(p & 0xff), uint8_t(a)});
        }
    }
    return out;
}

double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    if (a.size() != b.size()) throw std::invalid_argument("coverages of different image sizes");
    size_t both = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        both += a[i] && b[i];
        either += a[i] || b[i];
    }
    return either ? double(both) / double(either) : 1.0;
}

}  // namespace inkline::test
