// SPDX-License-Identifier: MIT
#include "core/strokes/write_on.h"

#include "core/strokes/brush.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <numeric>

namespace inkline::core {
namespace {

// The writers draw it: a visible stroke that is drawn, or a hidden one.
bool written(const Stroke& stroke) { return stroke.geometry.visible ? stroke.drawn : true; }

// Arc length of each sample of a drawn centerline; a loop's closing segment comes last.
std::vector<double> arc_lengths(const std::vector<glm::dvec2>& c, bool closed) {
    std::vector<double> arc(c.size() + (closed ? 1 : 0), 0.0);
    for (size_t k = 1; k < arc.size(); ++k) arc[k] = arc[k - 1] + glm::distance(c[k - 1], c[k % c.size()]);
    return arc;
}

// The stroke with its drawn centerline cut `drawn` px from its start and its tip tapered.
Stroke cut_stroke(const Stroke& full, const std::vector<double>& arc, double drawn, const BrushStyle& brush) {
    Stroke s = full;
    const size_t n = full.centerline_px.size();
    const double length = arc.back();  // u runs on by it past a loop's last sample
    std::vector<glm::dvec2> c{full.centerline_px.front()};
    std::vector<double> u{full.centerline_u.front()}, w{full.centerline_width.front()}, a{0.0};
    const auto sample = [&](size_t k) { return k % n; };
    for (size_t k = 1; k < arc.size(); ++k) {
        const size_t i = sample(k), prev = sample(k - 1);
        // u runs on past a loop's last sample by its closing segment.
        const double u_k = k == n ? full.centerline_u.front() + length : full.centerline_u[i];
        const double u_prev = k - 1 == n ? full.centerline_u.front() + length : full.centerline_u[prev];
        if (arc[k] < drawn) {
            c.push_back(full.centerline_px[i]);
            u.push_back(u_k);
            w.push_back(full.centerline_width[i]);
            a.push_back(arc[k]);
            continue;
        }
        const double span = arc[k] - arc[k - 1];
        const double f = span > 0.0 ? (drawn - arc[k - 1]) / span : 1.0;
        c.push_back(glm::mix(full.centerline_px[prev], full.centerline_px[i], f));
        u.push_back(u_prev + (u_k - u_prev) * f);
        w.push_back(full.centerline_width[prev] + (full.centerline_width[i] - full.centerline_width[prev]) * f);
        a.push_back(drawn);
        break;
    }
    // The moving tip thins to a point as a free end does.
    for (size_t k = 0; k < w.size(); ++k) w[k] *= end_profile(StrokeEnd::kFree, drawn - a[k], brush.taper_px);
    // A loop not yet closed is drawn as an open stroke.
    s.geometry.closed = false;
    s.centerline_px = std::move(c);
    s.centerline_u = std::move(u);
    s.centerline_width = std::move(w);
    s.outline.clear();
    s.darkening = 0.0;
    if (s.geometry.visible && !full.outline.empty()) {
        StrokeInk ink = stroke_ink(s.centerline_px, s.centerline_width, s.centerline_u, false, drawn, StrokeEnd::kFree,
                                   s.id, brush);
        s.outline = std::move(ink.outline);
        s.darkening = ink.darkening;
    }
    return s;
}

}  // namespace

double WriteOnSchedule::end_s(const Entry& entry) const {
    return speed_px_s > 0.0 ? entry.start_s + entry.length_px / speed_px_s : entry.start_s;
}

double WriteOnSchedule::drawn_px(const Entry& entry, double t) const {
    if (t < entry.start_s) return 0.0;
    if (t >= end_s(entry)) return entry.length_px;
    return std::min(entry.length_px, (t - entry.start_s) * speed_px_s);
}

WriteOnSchedule schedule_write_on(const FrameStrokes& strokes, double seconds) {
    WriteOnSchedule schedule;
    schedule.seconds = seconds;
    std::vector<uint32_t> order(strokes.strokes.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return strokes.strokes[a].order < strokes.strokes[b].order;
    });
    double total = 0.0;
    for (const uint32_t k : order) {
        const Stroke& s = strokes.strokes[k];
        if (!written(s) || s.centerline_px.size() < 2) continue;
        const double length = arc_lengths(s.centerline_px, s.geometry.closed).back();
        if (!(length > 0.0)) continue;
        schedule.entries.push_back({k, total, length});
        total += length;
    }
    schedule.speed_px_s = total / seconds;
    for (WriteOnSchedule::Entry& e : schedule.entries) e.start_s = total > 0.0 ? e.start_s / schedule.speed_px_s : 0.0;
    return schedule;
}

FrameStrokes strokes_at(const FrameStrokes& strokes, const WriteOnSchedule& schedule, double t) {
    FrameStrokes out;
    out.frame = strokes.frame;
    out.styles = strokes.styles;
    out.stats = strokes.stats;
    WriteOnFrame& progress = out.write_on.emplace();
    progress.time_s = t;
    progress.seconds = schedule.seconds;
    progress.speed_px_s = schedule.speed_px_s;
    const bool done = t >= schedule.seconds;
    std::vector<const WriteOnSchedule::Entry*> entry_of(strokes.strokes.size(), nullptr);
    for (const WriteOnSchedule::Entry& e : schedule.entries) entry_of[e.stroke] = &e;
    for (size_t k = 0; k < strokes.strokes.size(); ++k) {
        const Stroke& s = strokes.strokes[k];
        const WriteOnSchedule::Entry* entry = entry_of[k];
        WriteOnFrame::StrokeProgress p;
        if (!entry) {
            if (!done) continue;
            out.strokes.push_back(s);
            progress.strokes.push_back(p);
            continue;
        }
        p.start_s = entry->start_s;
        p.end_s = schedule.end_s(*entry);
        p.length_px = entry->length_px;
        p.drawn_px = done ? entry->length_px : schedule.drawn_px(*entry, t);
        if (!(p.drawn_px > 0.0)) continue;
        if (p.drawn_px >= entry->length_px) {
            out.strokes.push_back(s);
        } else {
            const BrushStyle& brush = strokes.styles.at(s.style).brush;
            out.strokes.push_back(cut_stroke(s, arc_lengths(s.centerline_px, s.geometry.closed), p.drawn_px, brush));
        }
        progress.strokes.push_back(p);
    }
    return out;
}

}  // namespace inkline::core
