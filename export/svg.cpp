// SPDX-License-Identifier: MIT
#include "export/svg.h"

#include <cstdio>
#include <string_view>

namespace inkline::output {
namespace {

class Writer {
  public:
    explicit Writer(int decimals) : decimals_(decimals) {}

    Writer& operator<<(std::string_view s) {
        out_ += s;
        return *this;
    }
    Writer& operator<<(int v) {
        out_ += std::to_string(v);
        return *this;
    }
    // A coordinate with bounded decimals and no trailing zeros.
    Writer& number(double v) {
        char buf[64];
        int n = std::snprintf(buf, sizeof buf, "%.*f", decimals_, v);
        if (decimals_ > 0) {
            while (n > 0 && buf[n - 1] == '0') --n;
            if (n > 0 && buf[n - 1] == '.') --n;
        }
        if (n == 2 && buf[0] == '-' && buf[1] == '0') {  // "-0" after rounding
            buf[0] = '0';
            n = 1;
        }
        out_.append(buf, size_t(n));
        return *this;
    }
    std::string take() { return std::move(out_); }

  private:
    std::string out_;
    int decimals_;
};

void path_data(Writer& w, const core::Polyline& line) {
    for (size_t i = 0; i < line.points_px.size(); ++i) {
        if (line.closed && i + 1 == line.points_px.size()) break;  // Z closes it
        w << (i == 0 ? "M" : " L");
        w.number(line.points_px[i].x) << " ";
        w.number(line.points_px[i].y);
    }
    if (line.closed) w << " Z";
}

void camera_metadata(Writer& w, const core::FrameLines& frame) {
    auto vec = [&](const glm::dvec3& v) {
        w << "[";
        w.number(v.x) << ",";
        w.number(v.y) << ",";
        w.number(v.z) << "]";
    };
    w << "  <metadata>\n    <inkline:frame number=\"" << frame.frame << "\"/>\n";
    w << "    <inkline:camera eye=\"";
    vec(frame.camera.eye);
    w << "\" target=\"";
    vec(frame.camera.target);
    w << "\" up=\"";
    vec(frame.camera.up);
    w << "\" fov_y_deg=\"";
    w.number(frame.camera.fov_y_deg) << "\"/>\n  </metadata>\n";
}

}  // namespace

std::string centerline_svg(const core::FrameLines& frame, const SvgOptions& options) {
    Writer w(options.decimals);
    const int width = frame.image.width, height = frame.image.height;
    w << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\""
      << " xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""
      << " xmlns:inkline=\"https://inkline.invalid/ns/1\""
      << " width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " "
      << height << "\">\n";
    camera_metadata(w, frame);

    auto layer = [&](std::string_view name, bool visible, core::LineKind kind, bool any_kind) {
        w << "  <g id=\"" << name << "\" inkscape:groupmode=\"layer\" inkscape:label=\"" << name
          << "\" fill=\"none\" stroke=\"" << options.color << "\" stroke-width=\"";
        w.number(options.stroke_width_px) << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
        if (!visible) {
            w << " stroke-dasharray=\"";
            w.number(3.0 * options.stroke_width_px) << " ";
            w.number(2.0 * options.stroke_width_px) << "\" opacity=\"0.5\"";
        }
        w << ">\n";
        for (const core::Polyline& line : frame.strokes) {
            if (line.visible != visible || (!any_kind && line.kind != kind)) continue;
            w << "    <path id=\"stroke-" << int(line.id) << "\" d=\"";
            path_data(w, line);
            w << "\"/>\n";
        }
        w << "  </g>\n";
    };
    for (core::LineKind kind : core::kAllLineKinds) layer(core::line_kind_name(kind), true, kind, false);
    bool any_hidden = false;
    for (const core::Polyline& line : frame.strokes) any_hidden |= !line.visible;
    if (any_hidden) layer("hidden", false, core::LineKind::kSilhouette, true);
    w << "</svg>\n";
    return w.take();
}

}  // namespace inkline::output
