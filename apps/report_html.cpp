#include "apps/report_html.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <ostream>
#include <sstream>
#include <unordered_set>

#include "apps/report_measures.h"

namespace delmesh::app {

namespace {

using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Text
// ---------------------------------------------------------------------------------------------

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

//! x with `digits` significant digits ("%g"): "inf", "-inf", "nan" as such.
std::string number(double x, int digits = 6) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "∞" : "−∞";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

//! x for the embedded JSON: a number with `digits` significant digits, null if not finite.
std::string json_number(double x, int digits) {
  if (!std::isfinite(x)) return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

//! JSON text that can sit inside a <script> element: '<' only occurs in strings, as \u003c.
std::string script_safe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (const char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

//! A value of the statistics as table text (the full number in a title attribute).
std::string value_html(const Json& v) {
  if (v.is_null()) return "<span class=\"muted\">–</span>";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_number_integer() || v.is_number_unsigned()) return escape(v.dump());
  if (v.is_number_float()) {
    const double x = v.get<double>();
    return "<span title=\"" + escape(v.dump()) + "\">" + escape(number(x)) + "</span>";
  }
  if (v.is_string()) return escape(v.get<std::string>());
  return escape(v.dump());
}

//! A JSON string literal of text (invalid UTF-8 replaced).
std::string json_string(const std::string& text) { return Json(text).dump(-1, ' ', false, Json::error_handler_t::replace); }

bool is_scalar(const Json& v) { return !v.is_object() && !v.is_array(); }

//! The statistics flattened into rows (key path, value html): nested objects as dotted paths,
//! arrays of at most 8 scalars inline, longer ones as their length and first values, arrays of
//! at most 4 objects with [i] in the path, longer ones as their length.
void flatten(const Json& v, const std::string& path, std::vector<std::pair<std::string, std::string>>& rows) {
  if (v.is_object()) {
    if (v.empty()) rows.emplace_back(path, "<span class=\"muted\">{}</span>");
    for (auto it = v.begin(); it != v.end(); ++it) flatten(it.value(), path.empty() ? it.key() : path + "." + it.key(), rows);
    return;
  }
  if (v.is_array()) {
    const bool scalars = std::all_of(v.begin(), v.end(), [](const Json& e) { return is_scalar(e); });
    if (v.empty()) {
      rows.emplace_back(path, "<span class=\"muted\">[]</span>");
    } else if (scalars) {
      std::string text = v.size() > 8 ? std::to_string(v.size()) + " values: " : "";
      for (std::size_t i = 0; i < v.size() && i < 8; ++i) text += (i ? ", " : "") + value_html(v[i]);
      rows.emplace_back(path, v.size() > 8 ? text + ", …" : text);
    } else if (v.size() <= 4) {
      for (std::size_t i = 0; i < v.size(); ++i) flatten(v[i], path + "[" + std::to_string(i) + "]", rows);
    } else {
      rows.emplace_back(path, std::to_string(v.size()) + " entries");
    }
    return;
  }
  rows.emplace_back(path, value_html(v));
}

//! A two-column table of rows (key, html value).
void write_table(std::ostream& out, const std::vector<std::pair<std::string, std::string>>& rows) {
  out << "<table class=\"kv\">\n";
  for (const auto& [key, value] : rows) out << "<tr><th>" << escape(key) << "</th><td>" << value << "</td></tr>\n";
  out << "</table>\n";
}

//! The value at a "/"-separated JSON pointer in the statistics, or nullptr.
const Json* find(const Json& root, const std::string& pointer) {
  const Json::json_pointer p(pointer);
  return root.contains(p) ? &root.at(p) : nullptr;
}

std::string badge(const std::string& status) {
  const bool good = status == "complete" || status == "certified" || status == "pass" || status == "yes";
  const bool fair = status == "uncertified" || status == "undecided" || status == "not attempted";
  return std::string("<span class=\"badge ") + (good ? "good" : fair ? "fair" : "bad") + "\">" + escape(status) +
         "</span>";
}

// ---------------------------------------------------------------------------------------------
// Colours
// ---------------------------------------------------------------------------------------------

//! viridis at nine evenly spaced stops (sRGB).
constexpr std::array<std::array<int, 3>, 9> colormap{{{68, 1, 84},
                                                      {71, 45, 123},
                                                      {59, 82, 139},
                                                      {44, 114, 142},
                                                      {33, 145, 140},
                                                      {40, 174, 128},
                                                      {94, 201, 98},
                                                      {173, 220, 48},
                                                      {253, 231, 37}}};

std::string colormap_css(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * static_cast<double>(colormap.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(t), colormap.size() - 2);
  const double f = t - static_cast<double>(i);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x",
                static_cast<int>(std::lround(colormap[i][0] + f * (colormap[i + 1][0] - colormap[i][0]))),
                static_cast<int>(std::lround(colormap[i][1] + f * (colormap[i + 1][1] - colormap[i][1]))),
                static_cast<int>(std::lround(colormap[i][2] + f * (colormap[i + 1][2] - colormap[i][2]))));
  return buffer;
}

//! How a measure maps to the colour map: value lo → 0, hi → 1, reversed if worse is higher (so
//! that the better end is always yellow).
struct ColorRange {
  const char* key;
  const char* label;
  double lo, hi;
  bool reversed;
  double position(double x) const {
    const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return reversed ? 1 - t : t;
  }
};

// ---------------------------------------------------------------------------------------------
// Histograms
// ---------------------------------------------------------------------------------------------

struct Marker {
  double value;
  std::string label;
  bool dashed;
  bool label_left = false;  //!< the label to the left of the line (it goes there anyway near the right end)
};

//! An SVG bar chart of `h` (bars coloured by `range`), with `outline` drawn as a step line over
//! it (may be empty), vertical markers, and x ticks every `tick`.
void write_histogram(std::ostream& out, const Histogram& h, const ColorRange& range, const Histogram* outline,
                     const std::vector<Marker>& markers, double tick, const std::string& x_label, int tick_digits) {
  const double width = 560, height = 250, left = 52, right = 14, top = 26, bottom = 42;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  std::size_t largest = std::max<std::size_t>(1, h.largest());
  if (outline) largest = std::max(largest, outline->largest());
  // y ticks: 1, 2 or 5 times a power of ten, about four of them.
  const double raw = static_cast<double>(largest) / 4;
  const double magnitude = std::pow(10.0, std::floor(std::log10(std::max(raw, 1.0))));
  double step = magnitude;
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * magnitude >= raw) {
      step = std::max(1.0, m * magnitude);
      break;
    }
  const double y_max = std::ceil(static_cast<double>(largest) / step) * step;
  const auto x_of = [&](double x) { return left + (x - h.lo) / (h.hi - h.lo) * plot_w; };
  const auto y_of = [&](double count) { return top + plot_h - count / y_max * plot_h; };
  out << "<svg class=\"hist\" viewBox=\"0 0 " << width << " " << height << "\" role=\"img\">\n";
  for (double y = 0; y <= y_max + 0.5 * step; y += step)
    out << "<line class=\"grid\" x1=\"" << left << "\" x2=\"" << width - right << "\" y1=\"" << y_of(y) << "\" y2=\""
        << y_of(y) << "\"/><text class=\"tick\" x=\"" << left - 6 << "\" y=\"" << y_of(y) + 4
        << "\" text-anchor=\"end\">" << number(y, 6) << "</text>\n";
  const double bar = plot_w / static_cast<double>(h.counts.size());
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    if (h.counts[i] == 0) continue;
    const double centre = h.lo + (static_cast<double>(i) + 0.5) * h.bin_width();
    out << "<rect x=\"" << left + static_cast<double>(i) * bar << "\" y=\"" << y_of(static_cast<double>(h.counts[i]))
        << "\" width=\"" << std::max(bar - 0.6, 0.6) << "\" height=\""
        << plot_h - (y_of(static_cast<double>(h.counts[i])) - top) << "\" fill=\""
        << colormap_css(range.position(centre)) << "\"><title>" << number(centre - 0.5 * h.bin_width(), 4) << " – "
        << number(centre + 0.5 * h.bin_width(), 4) << ": " << h.counts[i] << "</title></rect>\n";
  }
  if (outline) {
    std::ostringstream points;
    points << left << "," << y_of(0);
    for (std::size_t i = 0; i < outline->counts.size(); ++i) {
      const double y = y_of(static_cast<double>(outline->counts[i]));
      points << " " << left + static_cast<double>(i) * bar << "," << y << " " << left + static_cast<double>(i + 1) * bar
             << "," << y;
    }
    points << " " << width - right << "," << y_of(0);
    out << "<polyline class=\"outline\" points=\"" << points.str() << "\"/>\n";
  }
  out << "<line class=\"axis\" x1=\"" << left << "\" x2=\"" << width - right << "\" y1=\"" << y_of(0) << "\" y2=\""
      << y_of(0) << "\"/>\n";
  const double first_tick = std::ceil(h.lo / tick - 1e-9) * tick;
  for (double x = first_tick; x <= h.hi + 1e-9 * tick; x += tick)
    out << "<line class=\"axis\" x1=\"" << x_of(x) << "\" x2=\"" << x_of(x) << "\" y1=\"" << y_of(0) << "\" y2=\""
        << y_of(0) + 4 << "\"/><text class=\"tick\" x=\"" << x_of(x) << "\" y=\"" << y_of(0) + 16
        << "\" text-anchor=\"middle\">" << number(std::abs(x) < 1e-9 * tick ? 0.0 : x, tick_digits) << "</text>\n";
  out << "<text class=\"label\" x=\"" << left + plot_w / 2 << "\" y=\"" << height - 6 << "\" text-anchor=\"middle\">"
      << escape(x_label) << "</text>\n";
  int row = 0;
  for (const Marker& m : markers) {
    if (!(m.value >= h.lo && m.value <= h.hi)) continue;
    const double x = x_of(m.value);
    const bool right_side = m.label_left || x > left + 0.7 * plot_w;
    out << "<line class=\"marker" << (m.dashed ? " dashed" : "") << "\" x1=\"" << x << "\" x2=\"" << x << "\" y1=\""
        << top - 4 + 12 * row << "\" y2=\"" << y_of(0) << "\"/><text class=\"marker-label\" x=\""
        << x + (right_side ? -4 : 4) << "\" y=\"" << top + 6 + 12 * row << "\" text-anchor=\""
        << (right_side ? "end" : "start") << "\">" << escape(m.label) << "</text>\n";
    row = (row + 1) % 3;
  }
  out << "</svg>\n";
}

// ---------------------------------------------------------------------------------------------
// The page
// ---------------------------------------------------------------------------------------------

const char* const style = R"css(
:root { --fg: #1c2230; --muted: #5f6b7d; --line: #e2e6ec; --bg: #f4f6f9; --card: #ffffff; --accent: #2c728e; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--fg); background: var(--bg);
       font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
header { padding: 16px 28px 10px; display: flex; align-items: baseline; gap: 18px; flex-wrap: wrap; }
header h1 { font-size: 21px; margin: 0; font-weight: 650; letter-spacing: -0.01em; }
header h1 .file { font-family: ui-monospace, "SFMono-Regular", Menlo, Consolas, monospace; font-weight: 600; }
.facts { color: var(--muted); }
.facts b { color: var(--fg); font-weight: 600; }
.notes { margin: 0 28px 10px; padding: 8px 12px; background: #fff6e0; border: 1px solid #f0d48a; border-radius: 8px; }
.viewer { display: grid; grid-template-columns: minmax(0, 1fr) 300px; gap: 16px; padding: 0 28px; }
#view { position: relative; height: max(460px, min(74vh, 820px)); background: #ffffff; border: 1px solid var(--line);
        border-radius: 10px; overflow: hidden; cursor: grab; touch-action: none; }
#view:active { cursor: grabbing; }
#view canvas { display: block; }
#view-status { position: absolute; left: 16px; top: 12px; color: var(--muted); }
#view-hint { position: absolute; left: 14px; bottom: 10px; color: var(--muted); font-size: 12px;
             background: rgba(255,255,255,0.8); padding: 2px 8px; border-radius: 6px; pointer-events: none; }
.panel, .card { background: var(--card); border: 1px solid var(--line); border-radius: 10px; padding: 14px 16px; }
.panel { display: flex; flex-direction: column; gap: 14px; }
.panel h2, .card h2 { font-size: 13px; text-transform: uppercase; letter-spacing: 0.06em; color: var(--muted);
                      margin: 0 0 8px; font-weight: 650; }
.panel label { display: flex; align-items: center; gap: 8px; }
select, button { font: inherit; padding: 5px 8px; border: 1px solid #c9d0da; border-radius: 6px; background: #fff; }
button { cursor: pointer; }
#legend-bar { height: 16px; border-radius: 4px; border: 1px solid rgba(0,0,0,0.15); }
#legend-ticks { display: flex; justify-content: space-between; font-size: 12px; font-variant-numeric: tabular-nums;
                margin-top: 3px; }
#legend-ends { display: flex; justify-content: space-between; font-size: 12px; color: var(--muted); }
#legend-title { font-weight: 600; margin-bottom: 6px; }
#legend-extra { font-size: 12px; color: var(--muted); margin-top: 6px; }
#pick { font-size: 12.5px; font-variant-numeric: tabular-nums; min-height: 3.2em; }
.toggles { display: flex; flex-direction: column; gap: 4px; }
.buttons { display: flex; gap: 8px; }
.panel table.kv th, .panel table.kv td { padding: 3px 4px; font-size: 13px; }
.panel table.kv th { width: 42%; }
.cards { display: grid; grid-template-columns: repeat(auto-fit, minmax(380px, 1fr)); gap: 16px; padding: 16px 28px 0;
         align-items: start; }
.wide { grid-column: 1 / -1; }
table.kv { border-collapse: collapse; width: 100%; font-variant-numeric: tabular-nums; }
table.kv th, table.kv td { text-align: left; padding: 4px 8px; border-bottom: 1px solid var(--line); vertical-align: top; }
table.kv th { font-weight: 500; color: var(--muted); width: 46%; }
table.kv td { overflow-wrap: anywhere; }
table.kv tr:last-child th, table.kv tr:last-child td { border-bottom: none; }
.eq { font-family: ui-monospace, "SFMono-Regular", Menlo, Consolas, monospace; font-size: 12.5px; }
.badge { display: inline-block; padding: 0 8px; border-radius: 10px; font-weight: 600; font-size: 12.5px; }
.badge.good { background: #dff3e4; color: #1d6b34; }
.badge.fair { background: #fdf0d2; color: #8a5a00; }
.badge.bad { background: #fbe0e0; color: #a12626; }
.muted { color: var(--muted); }
svg.hist { width: 100%; height: auto; display: block; }
svg.hist .grid { stroke: #edf0f4; }
svg.hist .axis { stroke: #9aa4b2; }
svg.hist .tick { font-size: 11px; fill: #5f6b7d; }
svg.hist .label { font-size: 12px; fill: #1c2230; }
svg.hist .outline { fill: none; stroke: #1c2230; stroke-width: 1.2; stroke-opacity: 0.55; }
svg.hist .marker { stroke: #b3261e; stroke-width: 1.5; }
svg.hist .marker.dashed { stroke-dasharray: 5 3; stroke: #1c2230; }
svg.hist .marker-label { font-size: 11px; fill: #1c2230; }
.caption { color: var(--muted); font-size: 12.5px; margin-top: 4px; }
details { border-top: 1px solid var(--line); padding: 6px 0; }
details:first-of-type { border-top: none; }
summary { cursor: pointer; font-weight: 600; }
footer { color: var(--muted); font-size: 12px; padding: 18px 28px 28px; }
@media (max-width: 900px) { .viewer { grid-template-columns: 1fr; } }
)css";

// The viewer: three.js from the embedded text through a Blob URL (a file:// page cannot fetch
// modules), hand-written orbit controls, flat per-triangle colours on smooth vertex normals.
const char* const script = R"js(
const data = JSON.parse(document.getElementById('mesh-data').textContent);
const view = document.getElementById('view');
const status = document.getElementById('view-status');
const fail = (message) => { status.textContent = message; throw new Error(message); };
let THREE;
try {
  const url = URL.createObjectURL(new Blob([document.getElementById('three-js').textContent], {type: 'text/javascript'}));
  THREE = await import(url);
  URL.revokeObjectURL(url);
} catch (e) { fail('three.js could not be loaded: ' + e); }
let renderer;
try {
  renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
} catch (e) { fail('This browser cannot show the 3-D view (no WebGL): ' + e.message); }
status.textContent = '';
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0xffffff, 1);
view.insertBefore(renderer.domElement, view.firstChild);

const nt = data.triangles.length / 3, nv = data.positions.length / 3;
const P = data.positions, T = data.triangles;
// Smooth vertex normals (area-weighted), then one copy of each corner so that colours are per triangle.
const vn = new Float32Array(3 * nv);
for (let t = 0; t < nt; ++t) {
  const a = 3 * T[3 * t], b = 3 * T[3 * t + 1], c = 3 * T[3 * t + 2];
  const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
  const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
  const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
  for (const i of [a, b, c]) { vn[i] += nx; vn[i + 1] += ny; vn[i + 2] += nz; }
}
const position = new Float32Array(9 * nt), normal = new Float32Array(9 * nt), color = new Float32Array(9 * nt);
for (let t = 0; t < nt; ++t)
  for (let k = 0; k < 3; ++k) {
    const v = 3 * T[3 * t + k], o = 9 * t + 3 * k;
    const n = Math.hypot(vn[v], vn[v + 1], vn[v + 2]) || 1;
    for (let j = 0; j < 3; ++j) { position[o + j] = P[v + j]; normal[o + j] = vn[v + j] / n; }
  }
const geometry = new THREE.BufferGeometry();
geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
geometry.setAttribute('normal', new THREE.BufferAttribute(normal, 3));
geometry.setAttribute('color', new THREE.BufferAttribute(color, 3));
const material = new THREE.MeshStandardMaterial({vertexColors: true, roughness: 0.62, metalness: 0.0,
  side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1});
const model = new THREE.Group();
model.add(new THREE.Mesh(geometry, material));

// The edges, each once.
const seen = new Set(), edgeList = [];
for (let t = 0; t < nt; ++t)
  for (let k = 0; k < 3; ++k) {
    const i = T[3 * t + k], j = T[3 * t + (k + 1) % 3];
    const key = Math.min(i, j) * nv + Math.max(i, j);
    if (!seen.has(key)) { seen.add(key); edgeList.push(i, j); }
  }
const edgePositions = new Float32Array(3 * edgeList.length);
edgeList.forEach((v, n) => { for (let j = 0; j < 3; ++j) edgePositions[3 * n + j] = P[3 * v + j]; });
const edgeGeometry = new THREE.BufferGeometry();
edgeGeometry.setAttribute('position', new THREE.BufferAttribute(edgePositions, 3));
const edges = new THREE.LineSegments(edgeGeometry,
  new THREE.LineBasicMaterial({color: 0x1c2230, transparent: true, opacity: nt > 200000 ? 0.12 : 0.32}));
edges.visible = nt <= 50000;  // denser meshes would turn black
document.getElementById('show-edges').checked = edges.visible;
model.add(edges);

const scene = new THREE.Scene();
scene.add(model);
scene.add(new THREE.HemisphereLight(0xffffff, 0x6f7480, 1.25));
const camera = new THREE.PerspectiveCamera(32, 1, 0.01, 100);
const headlight = new THREE.DirectionalLight(0xffffff, 2.1);
headlight.position.set(0.5, 0.9, 1);
camera.add(headlight);
scene.add(camera);

// Colours.
const srgb = (r, g, b) => new THREE.Color().setRGB(r / 255, g / 255, b / 255, THREE.SRGBColorSpace);
const map = data.colormap;
const ramp = (t) => {
  t = Math.min(1, Math.max(0, t)) * (map.length - 1);
  const i = Math.min(Math.floor(t), map.length - 2), f = t - i;
  return [0, 1, 2].map((j) => map[i][j] + f * (map[i + 1][j] - map[i][j]));
};
const degenerateColor = [214, 39, 40], plainColor = [168, 184, 204];
function recolor(key) {
  const range = data.ranges[key], values = data.measures[key];
  let degenerate = 0;
  for (let t = 0; t < nt; ++t) {
    let rgb = plainColor;
    if (range) {
      const x = values[t];
      if (x === null) { rgb = degenerateColor; ++degenerate; }
      else {
        let s = (x - range.lo) / (range.hi - range.lo);
        if (range.reversed) s = 1 - s;
        rgb = ramp(s);
      }
    }
    const c = srgb(rgb[0], rgb[1], rgb[2]);
    for (let k = 0; k < 3; ++k) { color[9 * t + 3 * k] = c.r; color[9 * t + 3 * k + 1] = c.g; color[9 * t + 3 * k + 2] = c.b; }
  }
  geometry.attributes.color.needsUpdate = true;
  const legend = document.getElementById('legend');
  legend.style.display = range ? '' : 'none';
  if (range) {
    const stops = [];
    for (let i = 0; i <= 20; ++i) {
      const rgb = ramp(range.reversed ? 1 - i / 20 : i / 20);
      stops.push(`rgb(${rgb.map(Math.round).join(',')}) ${i * 5}%`);
    }
    document.getElementById('legend-bar').style.background = `linear-gradient(to right, ${stops.join(', ')})`;
    document.getElementById('legend-title').textContent = range.label;
    const ticks = [];
    for (let i = 0; i <= 4; ++i) ticks.push(`<span>${+(range.lo + i / 4 * (range.hi - range.lo)).toPrecision(3)}</span>`);
    document.getElementById('legend-ticks').innerHTML = ticks.join('');
    document.getElementById('legend-ends').innerHTML = range.reversed
      ? '<span>better</span><span>worse</span>' : (key === 'area' ? '<span>smaller</span><span>larger</span>'
                                                                  : '<span>worse</span><span>better</span>');
    document.getElementById('legend-extra').textContent = range.note +
      (degenerate ? ` ${degenerate} degenerate triangle${degenerate > 1 ? 's' : ''} in red.` : '');
  }
  requestRender();
}

// Orbit controls: drag rotates the model about the view's axes, the wheel zooms, right or
// shift-drag pans, a double click resets.
let fitDistance = 1, distance = 1;
const target = new THREE.Vector3();
const home = new THREE.Quaternion().setFromEuler(new THREE.Euler(-1.05, 0, -0.55, 'ZXY'));
// The distance and target at which the model, as rotated now, fills the view with a margin.
function fit() {
  const ty = 0.86 * Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)), tx = ty * camera.aspect;
  const v = new THREE.Vector3(), lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (const i of T) {
    v.set(P[3 * i], P[3 * i + 1], P[3 * i + 2]).applyQuaternion(model.quaternion);
    lo[0] = Math.min(lo[0], v.x); hi[0] = Math.max(hi[0], v.x);
    lo[1] = Math.min(lo[1], v.y); hi[1] = Math.max(hi[1], v.y);
  }
  if (!(hi[0] >= lo[0])) { lo[0] = lo[1] = -1; hi[0] = hi[1] = 1; }
  target.set((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 0);
  let d = 0.01;
  for (const i of T) {
    v.set(P[3 * i], P[3 * i + 1], P[3 * i + 2]).applyQuaternion(model.quaternion);
    d = Math.max(d, v.z + Math.abs(v.x - target.x) / tx, v.z + Math.abs(v.y - target.y) / ty);
  }
  fitDistance = distance = d;
}
function reset() {
  model.quaternion.copy(home);
  fit();
  requestRender();
}
let drag = null;
view.addEventListener('contextmenu', (e) => e.preventDefault());
view.addEventListener('pointerdown', (e) => {
  view.setPointerCapture(e.pointerId);
  drag = {x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, pan: e.button === 2 || e.shiftKey};
});
view.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX; drag.y = e.clientY;
  if (drag.pan) {
    const scale = 2 * distance * Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) / view.clientHeight;
    target.x -= dx * scale; target.y += dy * scale;
  } else {
    const speed = 4 / Math.max(view.clientWidth, view.clientHeight);
    const q = new THREE.Quaternion();
    q.setFromAxisAngle(new THREE.Vector3(0, 1, 0), dx * speed);
    model.quaternion.premultiply(q);
    q.setFromAxisAngle(new THREE.Vector3(1, 0, 0), dy * speed);
    model.quaternion.premultiply(q);
  }
  requestRender();
});
view.addEventListener('pointerup', (e) => {
  if (drag && Math.hypot(e.clientX - drag.x0, e.clientY - drag.y0) < 3) pick(e);
  drag = null;
});
view.addEventListener('wheel', (e) => {
  e.preventDefault();
  distance = Math.min(20 * fitDistance, Math.max(0.05 * fitDistance, distance * Math.exp(e.deltaY * 0.0012)));
  requestRender();
}, {passive: false});
view.addEventListener('dblclick', reset);

// A click on a triangle shows its measures.
const raycaster = new THREE.Raycaster();
const outline = new THREE.LineLoop(new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3)),
  new THREE.LineBasicMaterial({color: 0xd62728, depthTest: false}));
outline.visible = false;
outline.renderOrder = 1;
outline.add(new THREE.Mesh(outline.geometry, new THREE.MeshBasicMaterial({color: 0xd62728, transparent: true,
  opacity: 0.55, side: THREE.DoubleSide, depthTest: false})));
model.add(outline);
function pick(e) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2((e.clientX - rect.left) / rect.width * 2 - 1, -(e.clientY - rect.top) / rect.height * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObject(model.children[0])[0];
  const out = document.getElementById('pick');
  outline.visible = !!hit;
  requestRender();
  if (!hit) { out.textContent = 'Click a triangle to see its measures.'; return; }
  const t = hit.faceIndex, m = data.measures;
  outline.geometry.attributes.position.array.set(position.subarray(9 * t, 9 * t + 9));
  outline.geometry.attributes.position.needsUpdate = true;
  outline.geometry.computeBoundingSphere();
  const fmt = (x, d) => x === null ? '∞ (degenerate)' : (+x).toPrecision(d);
  out.innerHTML = `<b>triangle ${t}</b> (vertices ${T[3 * t]}, ${T[3 * t + 1]}, ${T[3 * t + 2]})<br>` +
    `min angle ${fmt(m['min-angle'][t], 4)}° · radius-edge ${fmt(m['radius-edge'][t], 4)} · ` +
    `area ${fmt(m.area[t], 3)} × mean`;
}

let pending = false;
function render() {
  pending = false;
  camera.position.set(target.x, target.y, distance);
  camera.lookAt(target);
  renderer.render(scene, camera);
}
function requestRender() { if (!pending) { pending = true; requestAnimationFrame(render); } }
function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}
new ResizeObserver(resize).observe(view);

const select = document.getElementById('color-by');
select.value = data.color;
select.addEventListener('change', () => recolor(select.value));
document.getElementById('show-edges').addEventListener('change', (e) => { edges.visible = e.target.checked; requestRender(); });
document.getElementById('flat').addEventListener('change', (e) => {
  material.flatShading = e.target.checked; material.needsUpdate = true; requestRender();
});
document.getElementById('reset').addEventListener('click', reset);
document.getElementById('save').addEventListener('click', () => {
  render();
  const a = document.createElement('a');
  a.href = renderer.domElement.toDataURL('image/png');
  a.download = data.name.replace(/\.[^.]*$/, '') + '_view.png';
  a.click();
});
recolor(data.color);
resize();
reset();
render();
)js";

//! The bounding box of the points used by triangles (all points if none is used).
struct Bounds {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0}, centre{0, 0, 0};
  double half_diagonal = 1;
};

Bounds bounds_of(const TriangleSoup& soup) {
  Bounds b;
  bool any = false;
  const auto add = [&](const Point3& p) {
    const Vec3 x{p.x(), p.y(), p.z()};
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = any ? std::min(b.lo[k], x[k]) : x[k];
      b.hi[k] = any ? std::max(b.hi[k], x[k]) : x[k];
    }
    any = true;
  };
  for (const auto& t : soup.triangles)
    for (const std::size_t v : t) add(soup.points[v]);
  if (!any)
    for (const Point3& p : soup.points) add(p);
  Vec3 half{};
  for (int k = 0; k < 3; ++k) {
    b.centre[k] = b.lo[k] / 2 + b.hi[k] / 2;
    half[k] = b.hi[k] / 2 - b.lo[k] / 2;
  }
  b.half_diagonal = std::hypot(half[0], half[1], half[2]);
  if (!(b.half_diagonal > 0) || !std::isfinite(b.half_diagonal)) b.half_diagonal = 1;
  return b;
}

std::string text_of(const std::vector<int>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + (values[i] >= 0 ? std::to_string(values[i]) : "–");
  return text.empty() ? "–" : text;
}

std::string yes_no(bool b) { return b ? "yes" : "no"; }

//! Adds (label, value html) to rows if the statistics have a value other than null at `pointer`.
void add_if(std::vector<std::pair<std::string, std::string>>& rows, const Json& stats, const std::string& label,
            const std::string& pointer) {
  if (const Json* v = find(stats, pointer); v && !v->is_null()) {
    if (v->is_string() && (pointer == "/status" || pointer.find("status") != std::string::npos))
      rows.emplace_back(label, badge(v->get<std::string>()));
    else if (is_scalar(*v))
      rows.emplace_back(label, value_html(*v));
    else {
      std::vector<std::pair<std::string, std::string>> flat;
      flatten(*v, "", flat);
      std::string text;
      for (const auto& [k, value] : flat) text += (text.empty() ? "" : "; ") + (k.empty() ? "" : escape(k) + " ") + value;
      rows.emplace_back(label, text);
    }
  }
}

//! Per triangle, in the soup's order: the measures the page shows and colours by, and the colour
//! ranges drawn from them.  Angles and ratios are measured on the coordinates as given, areas on
//! the normalised ones (relative to the mean triangle area).
struct PageMeasures {
  std::vector<double> min_angles, ratios, areas, angles;
  std::size_t degenerate = 0;                  //!< triangles whose ratio is not finite
  double largest_ratio = 1 / std::sqrt(3.0);   //!< over the finite ratios
  double ratio_hi = 1;                         //!< the upper end of the ratio colour range
  ColorRange angle_range{}, ratio_range{}, area_range{};
};

//! x centred on the box and divided by its half-diagonal.
Vec3 normalised(const Point3& x, const Bounds& box) {
  return Vec3{(x.x() - box.centre[0]) / box.half_diagonal, (x.y() - box.centre[1]) / box.half_diagonal,
              (x.z() - box.centre[2]) / box.half_diagonal};
}

PageMeasures measure_triangles(const TriangleSoup& soup, const Bounds& box) {
  const std::size_t nt = soup.triangles.size();
  PageMeasures m;
  m.min_angles.resize(nt);
  m.ratios.resize(nt);
  m.areas.resize(nt);
  m.angles.reserve(3 * nt);
  const auto at = [](const Point3& p) { return Vec3{p.x(), p.y(), p.z()}; };
  double area_sum = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = soup.triangles[t];
    const TriangleMeasures measures = triangle_measures(at(soup.points[tri[0]]), at(soup.points[tri[1]]), at(soup.points[tri[2]]));
    m.min_angles[t] = measures.min_angle_deg;
    m.ratios[t] = measures.radius_edge_ratio;
    m.degenerate += std::isfinite(measures.radius_edge_ratio) ? 0 : 1;
    m.angles.insert(m.angles.end(), measures.angles_deg.begin(), measures.angles_deg.end());
    m.areas[t] = triangle_measures(normalised(soup.points[tri[0]], box), normalised(soup.points[tri[1]], box),
                                   normalised(soup.points[tri[2]], box))
                     .area;
    area_sum += m.areas[t];
  }
  const double mean_area = nt > 0 && area_sum > 0 ? area_sum / static_cast<double>(nt) : 1;
  for (double& a : m.areas) a /= mean_area;

  double smallest_angle = 60, largest_area = 1, smallest_area = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    smallest_angle = std::min(smallest_angle, m.min_angles[t]);
    if (std::isfinite(m.ratios[t])) m.largest_ratio = std::max(m.largest_ratio, m.ratios[t]);
    largest_area = std::max(largest_area, m.areas[t]);
  }
  if (nt > 0) smallest_area = *std::min_element(m.areas.begin(), m.areas.end());

  const double angle_lo = std::min(50.0, 5 * std::floor(smallest_angle / 5));
  m.ratio_hi = std::clamp(std::ceil(m.largest_ratio * 10) / 10, 1.0, 3.0);
  m.angle_range = {"min-angle", "Minimum angle (degrees)", angle_lo, 60, false};
  m.ratio_range = {"radius-edge", "Radius-edge ratio", 1 / std::sqrt(3.0), m.ratio_hi, true};
  m.area_range = {"area", "Area ÷ mean triangle area", std::floor(smallest_area * 10) / 10,
                  std::max(std::ceil(largest_area * 10) / 10, std::floor(smallest_area * 10) / 10 + 0.1), false};
  return m;
}

//! What the page reads from the run's statistics besides the tables: Theorem 6.1's bounds and the status.
struct StatisticsBounds {
  std::optional<double> angle, ratio, roughness;
  std::string status;
};

StatisticsBounds bounds_in(const Json* stats) {
  StatisticsBounds b;
  if (!stats) return b;
  const auto number_at = [&](const std::string& pointer) -> std::optional<double> {
    const Json* v = find(*stats, pointer);
    if (v && v->is_number()) return v->get<double>();
    return std::nullopt;
  };
  b.angle = number_at("/bounds/min_angle_deg");
  b.ratio = number_at("/bounds/max_radius_edge_ratio");
  b.roughness = number_at("/bounds/max_roughness_rad");
  if (const Json* s = find(*stats, "/status"); s && s->is_string()) b.status = s->get<std::string>();
  return b;
}

//! The document's head and the header line with the checked facts.
void write_head(std::ostream& out, const ReportPage& page, std::size_t nt, const std::string& status) {
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<meta name=\"generator\" content=\""
      << escape(page.program_version) << "\">\n<title>" << escape(page.mesh_name) << " · delmesh report</title>\n<style>"
      << style << "</style>\n</head>\n<body>\n";
  out << "<header><h1>delmesh report · <span class=\"file\">" << escape(page.mesh_name) << "</span></h1>"
      << "<div class=\"facts\"><b>" << page.check.vertices << "</b> vertices · <b>" << nt << "</b> triangles · genus <b>"
      << escape(text_of(page.check.genus_per_component)) << "</b> · min angle <b>" << number(page.check.min_angle_deg, 4)
      << "°</b> · max radius-edge <b>" << number(page.check.max_radius_edge_ratio, 4) << "</b>";
  if (!status.empty()) out << " · " << badge(status);
  out << "</div></header>\n";
  if (!page.notes.empty()) {
    out << "<div class=\"notes\">";
    for (const std::string& note : page.notes) out << escape(note) << "<br>";
    out << "</div>\n";
  }

}

//! The 3-D view and the panel beside it: colour choice, legend, the facts at a glance, display toggles.
void write_panel(std::ostream& out, const ReportPage& page, const Json* stats, const StatisticsBounds& bounds,
                 std::size_t nt) {
  out << "<section class=\"viewer\">\n<div id=\"view\"><div id=\"view-status\">Loading the 3-D view…</div>"
         "<div id=\"view-hint\">drag: rotate · wheel: zoom · right-drag or shift-drag: pan · double-click: reset · "
         "click: pick a triangle</div></div>\n"
         "<aside class=\"panel\">\n<div><h2>Colour</h2><label>by <select id=\"color-by\">"
         "<option value=\"min-angle\">minimum angle</option><option value=\"radius-edge\">radius-edge ratio</option>"
         "<option value=\"area\">area</option><option value=\"none\">none</option></select></label></div>\n"
         "<div id=\"legend\"><div id=\"legend-title\"></div><div id=\"legend-bar\"></div><div id=\"legend-ticks\"></div>"
         "<div id=\"legend-ends\"></div><div id=\"legend-extra\"></div></div>\n"
         ;
  {
    const MeshReport& c = page.check;
    std::vector<std::pair<std::string, std::string>> glance;
    const auto verdict = [&](std::optional<double> bound, bool pass) {
      return bound ? " " + badge(pass ? "pass" : "fail") : std::string();
    };
    glance.emplace_back("min angle", number(c.min_angle_deg, 4) + "°" +
                                         verdict(bounds.angle, nt > 0 && bounds.angle && c.min_angle_deg >= *bounds.angle));
    glance.emplace_back("max radius-edge", number(c.max_radius_edge_ratio, 4) +
                                               verdict(bounds.ratio, nt > 0 && bounds.ratio && c.max_radius_edge_ratio <= *bounds.ratio));
    glance.emplace_back("max roughness", number(c.max_roughness_rad, 3) + " rad" +
                                             verdict(bounds.roughness, nt > 0 && bounds.roughness && c.max_roughness_rad <= *bounds.roughness));
    glance.emplace_back("topology", (c.closed && c.manifold && c.orientable ? "closed 2-manifold" : std::string("not a closed 2-manifold")) +
                                        ", genus " + escape(text_of(c.genus_per_component)));
    if (stats)
      if (const Json* d = find(*stats, "/distance"); d && d->is_object()) {
        const Json* bound = find(*d, "/hausdorff_upper_bound");
        const Json* state = find(*d, "/status");
        if (state && state->is_string())
          glance.emplace_back("distance to Σ", (bound && bound->is_number() ? "≤ " + number(bound->get<double>(), 3) + " " : std::string()) +
                                                  badge(state->get<std::string>()));
      }
    out << "<div><h2>At a glance</h2>\n";
    write_table(out, glance);
    out << "</div>\n";
  }
  out <<          "<div><h2>Display</h2><div class=\"toggles\"><label><input type=\"checkbox\" id=\"show-edges\" checked> "
         "edges</label><label><input type=\"checkbox\" id=\"flat\"> flat shading</label></div></div>\n"
         "<div class=\"buttons\"><button id=\"reset\">Reset view</button><button id=\"save\">Save PNG</button></div>\n"
         "<div><h2>Picked triangle</h2><div id=\"pick\" class=\"muted\">Click a triangle to see its measures.</div></div>\n"
         "</aside>\n</section>\n";

}

//! The cards with the histograms of the angles and of the radius-edge ratios; they open the section
//! of cards that write_report_page() closes.
void write_histograms(std::ostream& out, const ReportPage& page, const PageMeasures& m, const StatisticsBounds& bounds) {
  const std::size_t nt = m.ratios.size();
  out << "<section class=\"cards\">\n<div class=\"card\"><h2>Angles</h2>\n";
  {
    double largest_angle = 0;
    for (const double a : m.angles) largest_angle = std::max(largest_angle, a);
    const double hi = std::clamp(30 * std::ceil(largest_angle / 30), 120.0, 180.0);
    const auto bins = static_cast<std::size_t>(hi / 2);
    const Histogram all = histogram(m.angles, 0, hi, bins);
    const Histogram smallest = histogram(m.min_angles, 0, hi, bins);
    std::vector<Marker> markers;
    if (nt > 0) markers.push_back({page.check.min_angle_deg, "min " + number(page.check.min_angle_deg, 4) + "°", false, false});
    if (bounds.angle) markers.push_back({*bounds.angle, "bound " + number(*bounds.angle, 4) + "°", true, true});
    write_histogram(out, smallest, m.angle_range, &all, markers, 30, "angle (degrees)", 3);
    out << "<div class=\"caption\">Bars: the smallest angle of each triangle, coloured as in the view. Line: all "
        << 3 * nt << " angles. Bins of 2°.";
    if (bounds.angle) out << " Dashed: Theorem 6.1's lower bound for λ.";
    out << "</div>\n";
  }
  out << "</div>\n<div class=\"card\"><h2>Radius-edge ratios</h2>\n";
  {
    const double hi = std::max(m.ratio_hi, bounds.ratio ? std::ceil(*bounds.ratio * 10) / 10 : 0.0);
    const Histogram h = histogram(m.ratios, 0.5, hi, 60);
    std::vector<Marker> markers;
    markers.push_back({1 / std::sqrt(3.0), "equilateral 1/√3", true, false});
    if (nt > 0 && std::isfinite(page.check.max_radius_edge_ratio))
      markers.push_back({page.check.max_radius_edge_ratio, "max " + number(page.check.max_radius_edge_ratio, 4), false, true});
    if (bounds.ratio) markers.push_back({*bounds.ratio, "bound " + number(*bounds.ratio, 4), true, false});
    write_histogram(out, h, m.ratio_range, nullptr, markers, hi - 0.5 > 1.2 ? 0.5 : 0.1, "circumradius / shortest edge", 3);
    out << "<div class=\"caption\">One count per triangle, coloured as in the view; " << h.counts.size()
        << " bins from 0.5 to " << number(hi, 3) << ".";
    if (h.above > m.degenerate)
      out << " " << h.above - m.degenerate << " triangles above " << number(hi, 3) << " (the largest ratio is "
          << number(m.largest_ratio, 4) << ").";
    if (m.degenerate > 0) out << " " << m.degenerate << " degenerate (ratio ∞).";
    if (bounds.ratio) out << " Dashed at right: the quality bound 1 + λ.";
    out << "</div>\n";
  }
  out << "</div>\n";

}

//! The card of the independent checker's report on the file.
void write_mesh_card(std::ostream& out, const ReportPage& page, const Bounds& box) {
  const MeshReport& c = page.check;
  std::vector<std::pair<std::string, std::string>> rows{
      {"file", "<span class=\"eq\">" + escape(page.mesh_name) + "</span>"},
      {"vertices", std::to_string(c.vertices) + (c.unreferenced_vertices ? " (+" + std::to_string(c.unreferenced_vertices) + " unused)" : "")},
      {"edges", std::to_string(c.edges)},
      {"triangles", std::to_string(c.triangles)},
      {"components", std::to_string(c.components)},
      {"Euler characteristic", std::to_string(c.euler_characteristic)},
      {"genus per component", escape(text_of(c.genus_per_component))},
      {"closed", yes_no(c.closed) + (c.closed ? "" : " (" + std::to_string(c.boundary_edges) + " boundary edges in " +
                                                        std::to_string(c.boundary_loops) + " loops)")},
      {"manifold", yes_no(c.manifold)},
      {"orientable", yes_no(c.orientable) + (c.orientable && !c.oriented ? " (not consistently oriented)" : "")},
      {"min angle", number(c.min_angle_deg, 6) + "°"},
      {"max radius-edge ratio", number(c.max_radius_edge_ratio, 6)},
      {"max roughness", number(c.max_roughness_rad, 6) + " rad"},
      {"edge length", number(c.min_edge_length, 4) + " to " + number(c.max_edge_length, 4)},
      {"bounding box", "[" + number(box.lo[0], 4) + ", " + number(box.hi[0], 4) + "] × [" + number(box.lo[1], 4) + ", " +
                           number(box.hi[1], 4) + "] × [" + number(box.lo[2], 4) + ", " + number(box.hi[2], 4) + "]"}};
  out << "<div class=\"card\"><h2>Mesh (checked from the file)</h2>\n";
  write_table(out, rows);
  out << "</div>\n";

}

//! The statistics' peak_memory_bytes (the process's peak resident set) in MiB, and per output
//! vertex when the statistics count the vertices: "512.3 MiB (4321 B per vertex)".  Nothing if
//! the statistics have no such number.
std::optional<std::string> peak_memory_text(const Json& stats) {
  const Json* bytes = find(stats, "/peak_memory_bytes");
  if (!bytes || !bytes->is_number()) return std::nullopt;
  const double b = bytes->get<double>();
  std::string text = number(b / (1024.0 * 1024.0), 4) + " MiB";
  if (const Json* v = find(stats, "/vertices"); v && v->is_number_unsigned() && v->get<std::uint64_t>() > 0)
    text += " (" + std::to_string(std::llround(b / v->get<double>())) + " B per vertex)";
  return text;
}

//! The card of the run's settings and results, with Theorem 6.1's bounds checked on the file.
void write_run_card(std::ostream& out, const ReportPage& page, const Json& stats, const StatisticsBounds& bounds) {
  const MeshReport& c = page.check;
  const std::size_t nt = page.soup->triangles.size();
  std::vector<std::pair<std::string, std::string>> rows;
  add_if(rows, stats, "status", "/status");
  add_if(rows, stats, "status of the run", "/run_status");
  add_if(rows, stats, "surface", "/surface/name");
  if (const Json* e = find(stats, "/surface/equation"); e && e->is_string())
    rows.emplace_back("equation", "<span class=\"eq\">" + escape(e->get<std::string>()) + " = 0</span>");
  add_if(rows, stats, "box", "/surface/box");
  add_if(rows, stats, "input mesh", "/input_mesh/file");
  add_if(rows, stats, "λ", "/lambda");
  add_if(rows, stats, "phase", "/phase");
  add_if(rows, stats, "size bound", "/size_bound");
  add_if(rows, stats, "seed", "/seed");
  add_if(rows, stats, "vertices", "/vertices");
  add_if(rows, stats, "triangles", "/triangles");
  add_if(rows, stats, "genus per component", "/genus_per_component");
  add_if(rows, stats, "Theorem 6.1 applies", "/theorem_applies");
  add_if(rows, stats, "solver certified", "/solver_certified");
  add_if(rows, stats, "unsettled findings", "/unsettled/count");
  add_if(rows, stats, "seconds", "/seconds");
  add_if(rows, stats, "threads", "/threads");
  if (const std::optional<std::string> memory = peak_memory_text(stats)) rows.emplace_back("peak memory", *memory);
  out << "<div class=\"card\"><h2>Run (" << escape(page.statistics_name) << ")</h2>\n";
  write_table(out, rows);
  if (bounds.angle || bounds.ratio || bounds.roughness) {
    rows.clear();
    const auto bound_row = [&](const std::string& label, std::optional<double> bound, double value, bool at_least,
                               const std::string& unit) {
      if (!bound) return;
      const bool pass = nt > 0 && (at_least ? value >= *bound : value <= *bound);
      rows.emplace_back(label + (at_least ? " ≥ " : " ≤ ") + number(*bound, 6) + unit,
                        number(value, 6) + unit + " " + badge(pass ? "pass" : "fail"));
    };
    bound_row("min angle", bounds.angle, c.min_angle_deg, true, "°");
    bound_row("radius-edge ratio", bounds.ratio, c.max_radius_edge_ratio, false, "");
    bound_row("roughness", bounds.roughness, c.max_roughness_rad, false, " rad");
    out << "<h2 style=\"margin-top:14px\">Theorem 6.1's bounds, on this file</h2>\n";
    write_table(out, rows);
  }
  out << "</div>\n";
}

//! The card of the certificates: the distance (gradient flow) and, with --certify, the topology.
void write_certificate_card(std::ostream& out, const Json& stats) {
  std::vector<std::pair<std::string, std::string>> rows;
  if (const Json* d = find(stats, "/distance"); d && d->is_object()) {
    add_if(rows, *d, "status", "/status");
    add_if(rows, *d, "Hausdorff distance ≤", "/hausdorff_upper_bound");
    if (const Json* r = find(*d, "/hausdorff_relative"); r && r->is_number())
      rows.emplace_back("… relative to the box diagonal", number(100 * r->get<double>(), 3) + " %");
    add_if(rows, *d, "|E| on the mesh ≤ ε", "/epsilon");
    add_if(rows, *d, "tube |E| ≤", "/tube");
    add_if(rows, *d, "|∇E| on the tube ≥", "/min_gradient");
    add_if(rows, *d, "critical points", "/critical_points");
    add_if(rows, *d, "mesh components", "/mesh_components");
    add_if(rows, *d, "triangle pieces", "/triangle_pieces");
    add_if(rows, *d, "boxes", "/boxes");
    add_if(rows, *d, "seconds", "/seconds");
    if (const Json* r = find(*d, "/reason"); r && r->is_string() && !r->get<std::string>().empty())
      add_if(rows, *d, "reason", "/reason");
    add_if(rows, *d, "at", "/location");
    add_if(rows, *d, "max distance asked", "/max_distance");
  }
  std::vector<std::pair<std::string, std::string>> topology;
  if (const Json* t = find(stats, "/certificate"); t && t->is_object()) {
    if (const Json* v = find(*t, "/topology"); v && v->is_object()) {
      add_if(topology, *v, "topology", "/verdict");
      add_if(topology, *v, "by", "/method");
      add_if(topology, *v, "why", "/reason");
    }
    add_if(topology, *t, "restricted-Delaunay status", "/certificate/status");
    add_if(topology, *t, "Tri S|Σ = mesh", "/certificate/restricted_matches_mesh");
    add_if(topology, *t, "gradient-flow status", "/gradient_flow/status");
  }
  if (!rows.empty() || !topology.empty()) {
    out << "<div class=\"card\"><h2>Certificate</h2>\n";
    if (!rows.empty()) {
      out << "<div class=\"caption\" style=\"margin:0 0 6px\">Distance to the surface, proved by the gradient flow "
             "(the two-sided Hausdorff distance is at most the bound when the status is certified).</div>\n";
      write_table(out, rows);
    }
    if (!topology.empty()) {
      out << "<h2 style=\"margin-top:14px\">Topology (--certify)</h2>\n";
      write_table(out, topology);
    }
    out << "</div>\n";
  }

}

//! Every statistic, flattened: the top-level scalars, then one table per object.
void write_all_statistics(std::ostream& out, const Json& stats) {
  std::vector<std::pair<std::string, std::string>> rows;
  out << "<div class=\"card wide\"><h2>All statistics</h2>\n";
  for (auto it = stats.begin(); it != stats.end(); ++it)
    if (is_scalar(it.value()) || (it.value().is_array() && std::all_of(it.value().begin(), it.value().end(), is_scalar)))
      flatten(it.value(), it.key(), rows);
  out << "<details><summary>general (" << rows.size() << ")</summary>\n";
  write_table(out, rows);
  out << "</details>\n";
  for (auto it = stats.begin(); it != stats.end(); ++it) {
    if (is_scalar(it.value()) || (it.value().is_array() && std::all_of(it.value().begin(), it.value().end(), is_scalar)))
      continue;
    rows.clear();
    flatten(it.value(), "", rows);
    out << "<details><summary>" << escape(it.key()) << " (" << rows.size() << ")</summary>\n";
    write_table(out, rows);
    out << "</details>\n";
  }
  out << "</div>\n";
}

//! The embedded data (normalised positions, triangles, measures, colour ranges and map) and the code.
void write_mesh_data(std::ostream& out, const ReportPage& page, const Bounds& box, const PageMeasures& m) {
  const TriangleSoup& soup = *page.soup;
  const std::size_t nt = soup.triangles.size();
  std::ostringstream data;
  data << "{\"name\":" << json_string(page.mesh_name) << ",\"color\":\"" << enum_name(page.color)
       << "\",\"positions\":[";
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const Vec3 x = normalised(soup.points[i], box);
    data << (i ? "," : "") << json_number(x[0], 7) << "," << json_number(x[1], 7) << "," << json_number(x[2], 7);
  }
  data << "],\"triangles\":[";
  for (std::size_t t = 0; t < nt; ++t)
    data << (t ? "," : "") << soup.triangles[t][0] << "," << soup.triangles[t][1] << "," << soup.triangles[t][2];
  data << "],\"measures\":{";
  const auto write_values = [&](const char* key, const std::vector<double>& values, int digits) {
    data << "\"" << key << "\":[";
    for (std::size_t t = 0; t < values.size(); ++t) data << (t ? "," : "") << json_number(values[t], digits);
    data << "]";
  };
  write_values("min-angle", m.min_angles, 6);
  data << ",";
  write_values("radius-edge", m.ratios, 6);
  data << ",";
  write_values("area", m.areas, 4);
  data << "},\"ranges\":{";
  const std::array<std::pair<const ColorRange*, std::string>, 3> ranges{
      {{&m.angle_range, (m.angle_range.lo > 0 ? "Darkest at " + number(m.angle_range.lo, 3) + "° and below" : std::string("Darkest at 0°")) +
                         "; yellow at 60°, the equilateral triangle."},
       {&m.ratio_range, "Yellow at 1/√3 ≈ 0.577, the equilateral triangle; darkest at " + number(m.ratio_range.hi, 3) + " and above."},
       {&m.area_range, "Relative to the mean triangle area."}}};
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const ColorRange& r = *ranges[i].first;
    data << (i ? "," : "") << "\"" << r.key << "\":{\"label\":" << json_string(r.label) << ",\"lo\":" << json_number(r.lo, 17)
         << ",\"hi\":" << json_number(r.hi, 17) << ",\"reversed\":" << (r.reversed ? "true" : "false")
         << ",\"note\":" << json_string(ranges[i].second) << "}";
  }
  data << "},\"colormap\":[";
  for (std::size_t i = 0; i < colormap.size(); ++i)
    data << (i ? "," : "") << "[" << colormap[i][0] << "," << colormap[i][1] << "," << colormap[i][2] << "]";
  data << "]}";
  out << "<script type=\"application/json\" id=\"mesh-data\">" << script_safe(data.str()) << "</script>\n";
  out << "<script type=\"text/plain\" id=\"three-js\">" << page.three_js << "</script>\n";
  out << "<script type=\"module\">" << script << "</script>\n</body>\n</html>\n";}

}  // namespace

void write_report_page(std::ostream& out, const ReportPage& page) {
  const Bounds box = bounds_of(*page.soup);
  const PageMeasures measures = measure_triangles(*page.soup, box);
  const Json* stats = page.statistics ? &*page.statistics : nullptr;
  const StatisticsBounds bounds = bounds_in(stats);
  const std::size_t nt = page.soup->triangles.size();

  write_head(out, page, nt, bounds.status);
  write_panel(out, page, stats, bounds, nt);
  write_histograms(out, page, measures, bounds);
  write_mesh_card(out, page, box);
  if (stats) {
    write_run_card(out, page, *stats, bounds);
    write_certificate_card(out, *stats);
    write_all_statistics(out, *stats);
  } else {
    out << "<div class=\"card\"><h2>Run</h2><p class=\"muted\">No statistics given. <code>delmesh report MESH --stats "
           "STATS.json</code> adds the run, the certificate and every statistic of <code>delmesh mesh</code>.</p></div>\n";
  }
  out << "</section>\n";
  out << "<footer>Written by " << escape(page.program_version) << " (<code>delmesh report</code>) with three.js "
      << escape(page.three_js_version)
      << " (MIT license), embedded: this file needs no network. Coordinates are shown centred and scaled to unit "
         "half-diagonal; measures are computed on the original coordinates.</footer>\n";

  write_mesh_data(out, page, box, measures);
}

}  // namespace delmesh::app
