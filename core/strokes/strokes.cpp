// SPDX-License-Identifier: MIT
#include "core/strokes/strokes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <iterator>
#include <optional>

#include "core/internal/parallel.h"
#include "core/strokes/bridge_gaps.h"
#include "core/strokes/brush.h"
#include "core/strokes/brush_texture.h"
#include "core/strokes/occluded_gaps.h"
#include "core/strokes/pure_strokes.h"
#include "core/strokes/rejoin_strokes.h"
#include "core/strokes/reversals.h"
#include "core/strokes/stroke_path.h"
#include "core/strokes/t_junctions.h"

namespace inkline::core {
namespace {

// A loop start this close (px) to an exact point starts there instead of splitting a segment.
constexpr double kOnPointPx = 1e-6;

// Strokes turning back by more than this (deg) over max_fold_px are cut (split_at_reversals).
constexpr double kReversalDeg = 120.0;

// Frames with less drawn length (px) build their strokes on the calling thread: starting another
// costs about what 50 px of stroke does.
constexpr double kMinParallelLengthPx = 500.0;

StrokePathOptions path_options(const BrushStyle& style) {
    StrokePathOptions options;
    options.smooth_px = style.smooth_px;
    options.max_deviation_px = style.max_deviation_px;
    return options;
}

template <typename T>
std::vector<T> pick(const std::vector<T>& values, const std::vector<size_t>& indices) {
    std::vector<T> out;
    out.reserve(indices.size());
    for (size_t k : indices) out.push_back(values[k]);
    return out;
}

// Where each exact point lies along the drawn points (a fractional index): a left-out point
// between drawn points i and i + 1 lies in proportion to its index between theirs.
std::vector<double> drawn_parameter(const std::vector<size_t>& drawn, size_t count) {
    std::vector<double> out(count, 0.0);
    for (size_t i = 0; i < drawn.size(); ++i) {
        out[drawn[i]] = double(i);
        if (i + 1 == drawn.size()) break;
        const size_t a = drawn[i], b = drawn[i + 1];
        for (size_t k = a + 1; k < b; ++k) out[k] = double(i) + double(k - a) / double(b - a);
    }
    return out;
}

StrokePath drawn_path(const StrokeGeometry& g, const BrushStyle& style) {
    return build_stroke_path(pick(g.points_px, g.drawn_indices()), g.closed, path_options(style));
}

// Samples about kTraceSpacingPx apart: indices into the path's samples.
std::vector<size_t> trace_samples(const StrokePath& path) {
    std::vector<size_t> out;
    double next = 0.0;
    for (size_t i = 0; i < path.points_px.size(); ++i) {
        if (path.arc_px[i] + 1e-9 < next) continue;
        out.push_back(i);
        next = path.arc_px[i] + kTraceSpacingPx;
    }
    return out;
}

StrokeCandidate candidate_of(StrokeGeometry g, const StrokePath& path) {
    StrokeCandidate c;
    c.geometry = std::move(g);
    c.length_px = path.length_px;
    for (size_t i : trace_samples(path)) {
        c.samples_px.push_back(path.points_px[i]);
        c.samples_arc.push_back(path.arc_px[i]);
    }
    return c;
}

struct PointOnPolyline {
    size_t segment = 0;
    double t = 0.0;  // along the segment in the image
    double distance = HUGE_VAL;
};

PointOnPolyline nearest_on(const std::vector<glm::dvec2>& points, const glm::dvec2& p) {
    PointOnPolyline best;
    for (size_t s = 0; s + 1 < points.size(); ++s) {
        const glm::dvec2 ab = points[s + 1] - points[s];
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - points[s], ab) / len2, 0.0, 1.0) : 0.0;
        const double d = glm::length(p - (points[s] + ab * t));
        if (d < best.distance) best = {s, t, d};
    }
    return best;
}

// Restarts a loop (points repeat the first point last) at a point of segment s, splitting the
// segment there when the point lies inside it. The new point is exact: found along the edge
// with perspective-correct interpolation and projected again.
void restart_loop(StrokeGeometry& g, size_t s, double t, const Projection& projection,
                  const glm::dmat4& object_from_world) {
    const size_t m = g.points_px.size() - 1;  // distinct points
    const double len = glm::length(g.points_px[s + 1] - g.points_px[s]);
    if (t * len <= kOnPointPx) t = 0.0;
    if ((1.0 - t) * len <= kOnPointPx) t = 0.0, s = (s + 1) % m;
    std::vector<glm::dvec2> px;
    std::vector<glm::dvec3> world;
    std::vector<uint32_t> edges;
    std::vector<uint8_t> bridged;
    auto mark = [&](size_t k) {
        if (!g.bridged.empty()) bridged.push_back(g.bridged[k % m]);
    };
    auto push = [&](size_t k) {
        px.push_back(g.points_px[k % m]);
        world.push_back(g.points_world[k % m]);
    };
    if (t == 0.0) {
        for (size_t k = s; k <= s + m; ++k) push(k);
        for (size_t k = s; k < s + m; ++k) edges.push_back(g.edges[k % m]), mark(k);
    } else {
        // Image fraction t to world fraction: 1/w is linear in the image.
        const glm::dvec3 a = g.points_world[s], b = g.points_world[s + 1];
        const glm::dvec3 a_obj(object_from_world * glm::dvec4(a, 1.0)), b_obj(object_from_world * glm::dvec4(b, 1.0));
        const double wa = projection.clip(a_obj).w, wb = projection.clip(b_obj).w;
        const double tw = (wa > 0.0 && wb > 0.0) ? (t / wb) / ((1.0 - t) / wa + t / wb) : t;
        const glm::dvec3 start_world = a + (b - a) * tw;
        const glm::dvec2 start_px = projection.pixel(a_obj + (b_obj - a_obj) * tw);
        px.push_back(start_px);
        world.push_back(start_world);
        for (size_t k = s + 1; k <= s + m; ++k) push(k);
        px.push_back(start_px);
        world.push_back(start_world);
        for (size_t k = s; k <= s + m; ++k) edges.push_back(g.edges[k % m]), mark(k);
    }
    g.bridged = std::move(bridged);
    g.points_px = std::move(px);
    g.points_world = std::move(world);
    g.edges = std::move(edges);
}

// Where a loop starts: where coherence carried last frame's start to, else at the point whose
// normal faces the light least (something fixed in the scene rather than the chain's seam).
// Returns true when the start was anchored.
bool choose_loop_start(StrokeGeometry& g, const StrokeMatch& match, const StrokeLighting& lighting,
                       const Projection& projection, const glm::dmat4& object_from_world) {
    if (match.start_px) {
        const PointOnPolyline near = nearest_on(g.points_px, *match.start_px);
        if (near.distance <= kMatchRadiusPx) {
            restart_loop(g, near.segment, near.t, projection, object_from_world);
            return false;
        }
    }
    const std::vector<double> facing = lighting.facing(g.points_world, g.edges);
    size_t least = 0;
    for (size_t k = 1; k + 1 < facing.size(); ++k) {
        if (facing[k] < facing[least]) least = k;
    }
    restart_loop(g, least, 0.0, projection, object_from_world);
    return true;
}

// The ink of a dashed centerline: one outline per dash of `pattern` along u, one dot outline per
// dash of no length. A loop's closing segment is dashed too.
std::vector<Ring> dashed_outline(std::vector<glm::dvec2> c, std::vector<double> w, std::vector<double> u, bool closed,
                                 double length_px, std::span<const double> pattern, const OutlineOptions& options) {
    std::vector<Ring> rings;
    if (c.size() < 2) return rings;
    if (closed) {
        c.push_back(c.front());
        w.push_back(w.front());
        u.push_back(u.front() + length_px);
    }
    struct At {
        size_t next;  // first sample past the point
        glm::dvec2 p;
        double width;
    };
    const auto at = [&](double x) {
        const size_t k = std::clamp<size_t>(size_t(std::upper_bound(u.begin(), u.end(), x) - u.begin()), 1, u.size() - 1);
        const double span = u[k] - u[k - 1];
        const double f = span > 0.0 ? std::clamp((x - u[k - 1]) / span, 0.0, 1.0) : 0.0;
        return At{k, c[k - 1] + (c[k] - c[k - 1]) * f, w[k - 1] + (w[k] - w[k - 1]) * f};
    };
    for (const auto& [a, b] : dash_intervals(pattern, u.front(), u.back())) {
        const At start = at(a);
        if (b <= a) {
            const glm::dvec2 d = c[start.next] - c[start.next - 1];
            const double len = glm::length(d);
            const glm::dvec2 tangent = len > 0.0 ? d / len : glm::dvec2(1.0, 0.0);
            for (Ring& ring : dot_outline(start.p, tangent, start.width, options)) rings.push_back(std::move(ring));
            continue;
        }
        const At end = at(b);
        std::vector<glm::dvec2> piece{start.p};
        std::vector<double> width{start.width};
        for (size_t k = start.next; k < end.next; ++k) {
            if (u[k] <= a || u[k] >= b) continue;
            piece.push_back(c[k]);
            width.push_back(w[k]);
        }
        piece.push_back(end.p);
        width.push_back(end.width);
        for (Ring& ring : build_outline(piece, width, false, options)) rings.push_back(std::move(ring));
    }
    return rings;
}

// Width-by-depth factors at the exact points `drawn` of g, or none without style.depth_width.
std::vector<double> depth_scales(const StrokeGeometry& g, const std::vector<size_t>& drawn, const BrushStyle& style,
                                 const Camera& camera) {
    std::vector<double> out;
    if (!style.depth_width) return out;
    const DepthWidth& d = *style.depth_width;
    const glm::dvec3 axis = camera.target - camera.eye;
    const double axis_len = glm::length(axis);
    const glm::dvec3 forward = axis_len > 0.0 ? axis / axis_len : glm::dvec3(0.0, 0.0, -1.0);
    const double near = d.near.value_or(camera.near), far = d.far.value_or(camera.far);
    out.reserve(drawn.size());
    for (const size_t k : drawn) {
        out.push_back(depth_width_scale(glm::dot(g.points_world[k] - camera.eye, forward), near, far, d.far_scale));
    }
    return out;
}

// path: the drawn centerline of g when already built, else empty. Without `ink`, no outline (the
// stroke is only remembered).
Stroke style_stroke(StrokeGeometry g, std::optional<StrokePath> path_built, uint32_t id, double u_offset,
                    const StrokeLighting& lighting, const BrushStyle& style, const Camera& camera, bool ink) {
    Stroke stroke;
    stroke.id = id;
    const std::vector<size_t> drawn = g.drawn_indices();
    const StrokePath path = path_built ? std::move(*path_built) : drawn_path(g, style);
    const std::vector<double> facing = pick(lighting.facing(g.points_world, g.edges), drawn);
    const BrushSamples brush = brush_samples(path, facing, g.ends, style, depth_scales(g, drawn, style, camera));
    const std::vector<double> at = drawn_parameter(drawn, g.points_px.size());

    // The drawn centerline and its attributes; a loop's u starts at 0 on its first sample.
    const double offset = g.closed ? 0.0 : u_offset;
    stroke.centerline_px = path.points_px;
    stroke.centerline_width = brush.width;
    for (double a : path.arc_px) stroke.centerline_u.push_back(offset + a);
    // Exact points take the values where they map onto the drawn centerline.
    for (size_t k = 0; k < g.points_px.size(); ++k) {
        const double sample = path.sample_at(at[k]);
        stroke.u.push_back(offset + path.arc_at(sample));
        stroke.intensity.push_back(path.interpolate(brush.intensity, sample));
        stroke.width.push_back(path.interpolate(brush.width, sample));
    }
    if (g.closed && !stroke.u.empty()) stroke.u.back() = path.length_px;  // the seam, reached again

    stroke.drawn = path.length_px >= style.min_length_px && path.points_px.size() >= 2;
    if (stroke.drawn && ink) {
        StrokeInk made = stroke_ink(path.points_px, brush.width, stroke.centerline_u, path.closed, path.length_px,
                                    g.ends[1], id, style);
        stroke.outline = std::move(made.outline);
        stroke.darkening = made.darkening;
    }
    stroke.deviation_px = path.deviation_px;
    stroke.removed_px = removed_extent_px(pick(g.points_px, drawn), path);
    if (std::find(g.bridged.begin(), g.bridged.end(), uint8_t(1)) == g.bridged.end()) g.bridged.clear();
    stroke.geometry = std::move(g);
    return stroke;
}

StrokeTrace trace_of(const Stroke& stroke, bool start_anchored) {
    StrokeTrace t;
    t.start_anchored = start_anchored;
    t.id = stroke.id;
    t.kind = stroke.geometry.kind;
    t.visible = stroke.geometry.visible;
    t.closed = stroke.geometry.closed;
    t.edges = stroke.geometry.edges;
    std::sort(t.edges.begin(), t.edges.end());
    t.edges.erase(std::unique(t.edges.begin(), t.edges.end()), t.edges.end());
    double next = 0.0;
    const std::vector<double>& u = stroke.centerline_u;
    for (size_t i = 0; i < stroke.centerline_px.size(); ++i) {
        const double a = u[i] - u.front();
        if (a + 1e-9 < next) continue;
        t.samples_px.push_back(stroke.centerline_px[i]);
        t.samples_u.push_back(u[i]);
        next = a + kTraceSpacingPx;
    }
    t.length_px = stroke.u.empty() ? 0.0 : stroke.u.back() - stroke.u.front();
    const std::vector<glm::dvec2>& points = stroke.geometry.points_px;
    t.start_px = points.empty() ? glm::dvec2(0.0) : points.front();
    return t;
}

}  // namespace

StrokeInk stroke_ink(std::span<const glm::dvec2> centerline, std::span<const double> width, std::span<const double> u,
                     bool closed, double length_px, StrokeEnd last_end, uint32_t id, const BrushStyle& style) {
    StrokeInk ink;
    OutlineOptions outline;
    outline.cap = style.cap;
    if (style.dash_px.empty()) {
        ink.outline = build_outline(centerline, width, closed, outline);
    } else {
        ink.outline = dashed_outline({centerline.begin(), centerline.end()}, {width.begin(), width.end()},
                                     {u.begin(), u.end()}, closed, length_px, style.dash_px, outline);
    }
    if (style.texture && style.dash_px.empty()) {
        for (TextureHole& hole : texture_gaps(centerline, u, width, closed, last_end, id, *style.texture, ink.outline)) {
            ink.outline.push_back(std::move(hole.ring));
        }
        ink.darkening = pressure_darkening(width, style);
    }
    return ink;
}

namespace {

// build_strokes, made once from the memory r_coherence holds; without `ink`, the strokes have no
// outlines (a pass made only to be remembered).
FrameStrokes build_strokes_once(const FrameLines& frame, const Mesh& mesh, const EdgeTable& table,
                                const Projection& projection, const BrushStyle& style, StrokeCoherence& r_coherence,
                                std::span<const StyleRule> rules, const ObjectOfEdges& object_of,
                                VertexNormalCache* normals, bool ink) {
    FrameStrokes out;
    out.frame = frame.frame;
    // Visible lines are stroked alike whether or not hidden lines are output: with hidden lines
    // (visible == false in frame.polylines) those are set aside here as set_aside_occluded would,
    // and what the visible strokes do not take of them is stroked on its own.
    std::vector<Polyline> shown_lines, hidden_lines;
    const bool hidden_out =
        std::any_of(frame.polylines.begin(), frame.polylines.end(), [](const Polyline& line) { return !line.visible; });
    if (hidden_out) {
        for (const Polyline& line : frame.polylines) (line.visible ? shown_lines : hidden_lines).push_back(line);
    }
    const std::vector<Polyline>& shown = hidden_out ? shown_lines : frame.polylines;
    const std::vector<Polyline>& occluded_lines = hidden_out ? hidden_lines : frame.occluded;

    const PureStrokeOptions pure_options{style.turn_angle_deg};
    PureStrokes pure = build_pure_strokes(shown, pure_options);
    out.stats.polylines = frame.polylines.size();
    out.stats.pure_strokes = pure.pure_strokes;
    out.stats.corners = pure.corners;
    out.stats.links = pure.links;

    // Short occluded gaps bridged, and strokes split at a tangle joined again, with last frame's
    // strokes as memory.
    const GapBridgeOptions bridge = gap_bridge_options(style.width_max_px);
    OccludedUse use;
    if (!occluded_lines.empty()) {
        const std::vector<StrokeGeometry> occluded = occluded_parts(occluded_lines);
        out.stats.bridges = bridge_hidden_gaps(pure.strokes, occluded, r_coherence, bridge, use.bridged_whole);
        out.stats.bridges += rejoin_split_strokes(pure.strokes, occluded, use, r_coherence, bridge);
        out.stats.bridges += join_at_t_junctions(pure.strokes, r_coherence, bridge);
        std::erase_if(pure.strokes, [](const StrokeGeometry& g) { return g.points_px.empty(); });
    }
    // Hairpins cut at their tips, whether or not a join ran through them. Beyond a fold's
    // length, a turn back is no fold.
    out.stats.corners += split_at_reversals(pure.strokes, bridge.max_fold_px, kReversalDeg);
    if (hidden_out) {
        PureStrokes hidden = build_pure_strokes(occluded_left(occluded_lines, use), pure_options);
        std::move(hidden.strokes.begin(), hidden.strokes.end(), std::back_inserter(pure.strokes));
        out.stats.pure_strokes += hidden.pure_strokes;
        out.stats.corners += hidden.corners;
        out.stats.links += hidden.links;
    }

    // Ids, direction and u from the previous frame. Each stroke's centerline, and below its
    // styling, depends on that stroke alone: built in parallel, gathered in stroke order.
    // A stroke's cost follows its length: the longest go first, one at a time, to every core.
    const size_t n = pure.strokes.size();
    std::vector<double> weight(n);
    for (size_t i = 0; i < n; ++i) weight[i] = pure.strokes[i].length_px();
    std::vector<StrokePath> paths(n);
    std::vector<StrokeCandidate> candidates(n);
    // Roles only when a rule asks for them: the mask rasterises the whole mesh.
    const std::optional<BackgroundMask> background =
        selects_role(rules) ? std::optional<BackgroundMask>(std::in_place, mesh, projection) : std::nullopt;
    std::vector<LineRole> roles(n, LineRole::kInner);
    internal::parallel_for_each(weight, kMinParallelLengthPx, [&](size_t i) {
        paths[i] = drawn_path(pure.strokes[i], style);
        if (background && pure.strokes[i].visible) roles[i] = role_of(paths[i], *background);
        candidates[i] = candidate_of(std::move(pure.strokes[i]), paths[i]);
    });
    const std::vector<StrokeMatch> matches = r_coherence.match(candidates);

    // Each stroke's object and style, from what it is.
    StyleSheet sheet(style, rules);
    std::vector<uint32_t> stroke_style(n, 0);
    std::vector<int32_t> objects(n, -1);
    for (size_t i = 0; i < n; ++i) {
        const StrokeGeometry& g = candidates[i].geometry;
        if (object_of && !g.edges.empty()) objects[i] = object_of({matches[i].reverse ? &g.edges.back() : &g.edges.front(), 1});
        if (rules.empty()) continue;
        const int32_t o = objects[i];
        const std::string_view object =
            o >= 0 && size_t(o) < frame.objects.size() ? std::string_view(frame.objects[size_t(o)].name) : "";
        stroke_style[i] = sheet.resolve({g.kind, g.visible, object, roles[i]});
    }

    // Normals only where the strokes run (bridged gaps included): a full pass over a million vertices would cost
    // more than the rest of this stage.
    std::vector<uint32_t> line_edges;
    for (const StrokeCandidate& c : candidates)
        line_edges.insert(line_edges.end(), c.geometry.edges.begin(), c.geometry.edges.end());
    const StrokeLighting lighting(mesh, table, projection.world_from_object(), frame.light, line_edges, normals);
    const glm::dmat4 object_from_world = glm::inverse(projection.world_from_object());
    std::vector<Stroke> styled(n);
    std::vector<StrokeTrace> traces(n);
    internal::parallel_for_each(weight, kMinParallelLengthPx, [&](size_t i) {
        StrokeGeometry& g = candidates[i].geometry;
        const StrokeMatch& m = matches[i];
        // The centerline is built again only where the stroke was turned round or restarted.
        std::optional<StrokePath> path = std::move(paths[i]);
        if (m.reverse) g.reverse(), path.reset();
        bool anchored = false;
        if (g.closed && g.points_px.size() > 2) {
            anchored = choose_loop_start(g, m, lighting, projection, object_from_world);
            path.reset();
        }
        styled[i] = style_stroke(std::move(g), std::move(path), m.id, m.u_offset, lighting,
                                 sheet.styles()[stroke_style[i]].brush, frame.camera, ink);
        styled[i].style = stroke_style[i];
        styled[i].geometry.object = objects[i];
        traces[i] = trace_of(styled[i], anchored);
    });
    uint32_t next_id = r_coherence.next_id();
    for (size_t i = 0; i < n; ++i) {
        Stroke& stroke = styled[i];
        const StrokeMatch& m = matches[i];
        next_id = std::max(next_id, m.id + 1);

        StrokeStats& s = out.stats;
        s.drawn += stroke.drawn;
        s.inherited += m.inherited;
        const StrokeGeometry& g = stroke.geometry;
        if (g.visible) {
            // The whole length less the bridged segments.
            double len = g.length_px();
            for (size_t k = 0; k < g.bridged.size(); ++k) {
                if (g.bridged[k]) len -= glm::length(g.points_px[k + 1] - g.points_px[k]);
            }
            s.visible_length_px += len;
            if (m.inherited) s.inherited_length_px += len;
        }
        if (stroke.drawn) {
            s.max_deviation_px = std::max(s.max_deviation_px, stroke.deviation_px);
            s.max_removed_px = std::max(s.max_removed_px, stroke.removed_px);
        }
        out.strokes.push_back(std::move(stroke));
    }
    r_coherence.remember(std::move(traces), next_id);
    out.styles = sheet.take();
    return out;
}

}  // namespace

FrameStrokes build_strokes(const FrameLines& frame, const Mesh& mesh, const EdgeTable& table,
                           const Projection& projection, const BrushStyle& style, StrokeCoherence& r_coherence,
                           std::span<const StyleRule> rules, const ObjectOfEdges& object_of,
                           VertexNormalCache* normals) {
    const bool first = r_coherence.traces().empty();
    if (first) {
        // Without memory the repairs join less (gaps up to new_gap_px, no strokes rejoined), and
        // the next frame, with it, would join more: the first frame is drawn as if it followed
        // itself. That pass is only remembered: it draws no outlines.
        build_strokes_once(frame, mesh, table, projection, style, r_coherence, rules, object_of, normals, false);
    }
    FrameStrokes out =
        build_strokes_once(frame, mesh, table, projection, style, r_coherence, rules, object_of, normals, true);
    if (first) {
        out.stats.inherited = 0;
        out.stats.inherited_length_px = 0.0;
    }
    return out;
}

}  // namespace inkline::core
