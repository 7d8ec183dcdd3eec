// PNG pictures with Cairo. Layout, top to bottom: a title line (scenario, field), the time; the
// bodies in true proportion (zones filled by the field's colour, body outlines, particles as discs;
// in axisymmetric geometry also the mirror image below the axis when settings.mirror); a scale bar.
// The colour bar with its range and unit is on the right. Colours: viridis (perceptually uniform);
// bodies by a categorical palette.
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "pictures.hpp"

namespace krug::app {

namespace {

struct Colour {
  double r, g, b;
};

// matplotlib's viridis at 0, 0.1, ..., 1.
constexpr std::array<Colour, 11> viridis = {{{0.267, 0.004, 0.329}, {0.282, 0.141, 0.459}, {0.255, 0.267, 0.529},
                                             {0.208, 0.373, 0.553}, {0.165, 0.471, 0.557}, {0.129, 0.569, 0.549},
                                             {0.133, 0.659, 0.518}, {0.267, 0.749, 0.439}, {0.478, 0.820, 0.318},
                                             {0.741, 0.875, 0.149}, {0.992, 0.906, 0.145}}};

// A categorical palette for bodies (matplotlib's tab10).
constexpr std::array<Colour, 10> categories = {{{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173},
                                                {0.839, 0.153, 0.157}, {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                                {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498}, {0.737, 0.741, 0.133},
                                                {0.090, 0.745, 0.812}}};

Colour colour_map(double fraction) {
  if (!std::isfinite(fraction)) return {0.85, 0.85, 0.85};
  const double f = std::clamp(fraction, 0.0, 1.0) * 10.0;
  const auto i = static_cast<std::size_t>(std::min(9.0, std::floor(f)));
  const double t = f - static_cast<double>(i);
  const Colour& a = viridis[i];
  const Colour& b = viridis[i + 1];
  return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

const char* unit_of(const std::string& field) {
  if (field == "density") return "kg/m\u00b3";
  if (field == "pressure") return "Pa";
  if (field == "specific_internal_energy") return "J/kg";
  if (field == "sound_speed" || field == "speed") return "m/s";
  return "";
}

double zone_value(const Mesh& mesh, const ZoneState& state, Index z, const std::string& field) {
  if (field == "density") return mesh.zones.density[z];
  if (field == "pressure") return state.hydro.pressure[z];
  if (field == "specific_internal_energy") return mesh.zones.specific_energy[z];
  if (field == "equivalent_plastic_strain") return state.strength.plastic_strain[z];
  if (field == "damaged") return state.fracture.damaged[z];
  if (field == "sound_speed") return state.hydro.sound_speed[z];
  if (field == "body") return mesh.zones.body[z];
  double speed = 0.0;  // "speed": mean of the corner speeds
  for (Index n : mesh.zones.corners[z]) speed += 0.25 * std::hypot(mesh.nodes.u[n], mesh.nodes.v[n]);
  return speed;
}

// Particles carry some of the fields; the others are drawn grey.
bool particle_value(const Particles& p, Index i, const std::string& field, double& value) {
  if (field == "speed") value = std::hypot(p.u[i], p.v[i]);
  else if (field == "body") value = p.body[i];
  else if (field == "damaged") value = 1.0;  // made of fully fractured material
  else return false;
  return true;
}

// A round length near `target`: 1, 2 or 5 x 10^k.
double round_length(double target) {
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= target) return m * decade;
  }
  return decade;
}

std::string length_label(double metres) {
  if (metres >= 1.0) return fmt::format("{:g} m", metres);
  if (metres >= 1e-3) return fmt::format("{:g} mm", metres * 1e3);
  return fmt::format("{:g} \u00b5m", metres * 1e6);
}

std::string time_label(double t) {
  if (t == 0.0) return "t = 0";
  const double a = std::abs(t);
  if (a < 1e-6) return fmt::format("t = {:.4g} ns", t * 1e9);
  if (a < 1e-3) return fmt::format("t = {:.4g} \u00b5s", t * 1e6);
  if (a < 1.0) return fmt::format("t = {:.4g} ms", t * 1e3);
  return fmt::format("t = {:.4g} s", t);
}

// Enough significant digits to tell the colour bar's ticks apart.
std::string value_label(double v, double low, double high) {
  const double magnitude = std::max(std::abs(low), std::abs(high));
  const double digits = std::ceil(std::log10(std::max(magnitude / (high - low), 1.0))) + 3.0;
  return fmt::format("{:.{}g}", v, static_cast<int>(std::clamp(digits, 3.0, 12.0)));
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size, bool bold = false, bool right = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  double offset = 0.0;
  if (right) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, s.c_str(), &extents);
    offset = extents.x_advance;
  }
  cairo_move_to(cr, x - offset, y);
  cairo_show_text(cr, s.c_str());
}

}  // namespace

bool pictures_available() { return true; }

// Fontconfig (under Cairo's text) keeps its configuration for the life of the process; under
// AddressSanitizer that reads as a leak at exit. Tell LeakSanitizer it is not ours.
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
#endif

bool write_picture(const Simulation& simulation, const scenario::PictureSettings& settings, const std::string& title,
                   const std::filesystem::path& directory, const std::string& name) {
  const Mesh& mesh = simulation.mesh();
  const Particles& particles = simulation.particles();
  const std::string& field = settings.field;
  const bool mirror = settings.mirror && simulation.geometry() == GeometryKind::axisymmetric;

  // Extent of what is drawn, and the field's range.
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  auto include = [&](double x, double y, double r) {
    x0 = std::min(x0, x - r);
    x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r);
    y1 = std::max(y1, y + r);
    if (mirror) y0 = std::min(y0, -(y + r));
  };
  long active = 0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (!mesh.zones.active[z]) continue;
    ++active;
    for (Index n : mesh.zones.corners[z]) include(mesh.nodes.x[n], mesh.nodes.y[n], 0.0);
    const double v = zone_value(mesh, simulation.zone_state(), z, field);
    if (std::isfinite(v)) {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  for (Index i = 0; i < particles.size(); ++i) {
    include(particles.x[i], particles.y[i], particles.radius[i]);
    double v = 0.0;
    if (particle_value(particles, i, field, v)) {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  if (active == 0 && particles.size() == 0) return false;
  if (settings.window) {
    const auto& w = *settings.window;
    x0 = w[0];
    x1 = w[1];
    y0 = mirror ? -w[3] : w[2];
    y1 = w[3];
  }
  if (!(x1 > x0) || !(y1 > y0) || !std::isfinite(x1 - x0) || !std::isfinite(y1 - y0)) return false;
  if (field == "damaged") {
    low = 0.0;
    high = 1.0;
  }
  if (field == "body") {
    low = 0.0;
    high = std::max(1.0, static_cast<double>(simulation.bodies().size()) - 1.0);
  }
  if (settings.range) {
    low = settings.range->first;
    high = settings.range->second;
  }
  if (!(high > low)) {  // a uniform field: zero shows as the bottom of [0, 1]
    if (low == 0.0) {
      high = 1.0;
    } else {
      const double pad = std::abs(low) * 1e-3;
      low -= pad;
      high += pad;
    }
  }

  // Layout (pixels): the bodies keep their proportions.
  const double width = settings.width;
  const double font = std::max(11.0, 14.0 * width / 1200.0);
  const double left = 0.08 * width, right = 0.17 * width, top = 5.4 * font, bottom = 5.4 * font;
  const double plot_width = width - left - right;
  double scale = plot_width / (x1 - x0);
  double plot_height = (y1 - y0) * scale;
  const double max_height = 1.2 * width, min_height = 0.25 * width;
  if (plot_height > max_height) {
    scale = max_height / (y1 - y0);
    plot_height = max_height;
  }
  const double box_height = std::max(plot_height, min_height);
  const double x_offset = left + 0.5 * (plot_width - (x1 - x0) * scale);
  const double y_offset = top + 0.5 * (box_height - plot_height);
  const int image_width = static_cast<int>(std::lround(width));
  const int image_height = static_cast<int>(std::lround(top + box_height + bottom));
  auto px = [&](double x) { return x_offset + (x - x0) * scale; };
  auto py = [&](double y) { return y_offset + (y1 - y) * scale; };

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, image_width, image_height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  const double fraction_scale = 1.0 / (high - low);
  auto set_colour = [&](double value) {
    Colour c;
    if (field == "body") {
      c = categories[static_cast<std::size_t>(std::max(0.0, value)) % categories.size()];
    } else {
      c = colour_map((value - low) * fraction_scale);
    }
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
  };

  // A fixed window may cut bodies: draw inside the plot box only.
  cairo_save(cr);
  cairo_rectangle(cr, x_offset, y_offset, (x1 - x0) * scale, plot_height);
  cairo_clip(cr);

  // Zones, with thin edges when they are large enough to show them.
  const double mean_size = std::sqrt((x1 - x0) * (y1 - y0) / static_cast<double>(std::max(1L, active))) * scale;
  const bool edges = mean_size > 7.0;
  cairo_set_line_width(cr, 0.5);
  for (int side = 0; side < (mirror ? 2 : 1); ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    for (Index z = 0; z < mesh.zones.size(); ++z) {
      if (!mesh.zones.active[z]) continue;
      const ZoneCorners& c = mesh.zones.corners[z];
      cairo_move_to(cr, px(mesh.nodes.x[c[0]]), py(sign * mesh.nodes.y[c[0]]));
      for (int k = 1; k < 4; ++k) cairo_line_to(cr, px(mesh.nodes.x[c[k]]), py(sign * mesh.nodes.y[c[k]]));
      cairo_close_path(cr);
      set_colour(zone_value(mesh, simulation.zone_state(), z, field));
      if (edges) {
        cairo_fill_preserve(cr);
        cairo_set_source_rgba(cr, 0, 0, 0, 0.3);
        cairo_stroke(cr);
      } else {
        cairo_fill_preserve(cr);
        cairo_set_line_width(cr, 0.4);
        cairo_stroke(cr);  // same colour: closes hairline gaps between zones
        cairo_set_line_width(cr, 0.5);
      }
    }
    // Body outlines.
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, std::max(1.0, 0.08 * font));
    for (const Body& body : simulation.bodies()) {
      for (const BoundarySegment& s : boundary_segments(mesh, body.zone_begin, body.zone_end)) {
        cairo_move_to(cr, px(mesh.nodes.x[s.a]), py(sign * mesh.nodes.y[s.a]));
        cairo_line_to(cr, px(mesh.nodes.x[s.b]), py(sign * mesh.nodes.y[s.b]));
      }
    }
    cairo_stroke(cr);
    // Particles.
    cairo_set_line_width(cr, 0.5);
    for (Index i = 0; i < particles.size(); ++i) {
      const double r = std::max(0.8, particles.radius[i] * scale);
      cairo_new_sub_path(cr);
      cairo_arc(cr, px(particles.x[i]), py(sign * particles.y[i]), r, 0.0, 2.0 * std::numbers::pi);
      double value = 0.0;
      if (particle_value(particles, i, field, value)) set_colour(value);
      else cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
      cairo_fill_preserve(cr);
      cairo_set_source_rgba(cr, 0, 0, 0, 0.6);
      cairo_stroke(cr);
    }
  }
  if (mirror) {  // the axis
    const double dash[] = {8.0, 4.0, 2.0, 4.0};
    cairo_set_dash(cr, dash, 4, 0.0);
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, left, py(0.0));
    cairo_line_to(cr, left + plot_width, py(0.0));
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }

  cairo_restore(cr);  // the clip

  // Axes: ticks and coordinates in mm along the bottom and the left of the drawing.
  {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    const double x_step = round_length(0.2 * (x1 - x0)), y_step = round_length(0.2 * (y1 - y0));
    const double base = y_offset + plot_height;
    cairo_move_to(cr, px(x0), base);
    cairo_line_to(cr, px(x1), base);
    cairo_move_to(cr, px(x0), y_offset);
    cairo_line_to(cr, px(x0), base);
    cairo_stroke(cr);
    for (double x = std::ceil(x0 / x_step) * x_step; x <= x1 + 1e-9 * x_step; x += x_step) {
      cairo_move_to(cr, px(x), base);
      cairo_line_to(cr, px(x), base + 0.4 * font);
      cairo_stroke(cr);
      text(cr, px(x) - 1.2 * font, base + 1.5 * font, fmt::format("{:g}", std::round(x * 1e6) / 1e3), 0.8 * font);
    }
    for (double y = std::ceil(y0 / y_step) * y_step; y <= y1 + 1e-9 * y_step; y += y_step) {
      cairo_move_to(cr, px(x0), py(y));
      cairo_line_to(cr, px(x0) - 0.4 * font, py(y));
      cairo_stroke(cr);
      text(cr, px(x0) - 0.6 * font, py(y) + 0.3 * font, fmt::format("{:g}", std::round(y * 1e6) / 1e3), 0.8 * font,
           false, true);
    }
    const GeometryKind g = simulation.geometry();
    text(cr, px(x1), base + 2.9 * font, fmt::format("{} (mm)", axis_name(g, 0)), 0.85 * font, false, true);
    text(cr, 0.3 * font, y_offset - 0.5 * font, fmt::format("{} (mm)", axis_name(g, 1)), 0.85 * font);
  }

  // Title, field and time, and the bodies with their materials.
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, left, 1.5 * font, title, 1.1 * font, true);
  const std::string unit = unit_of(field);
  text(cr, left, 3.0 * font, time_label(simulation.time()) + "    " + field + (unit[0] ? std::string(" (") + unit + ")" : ""),
       font);
  std::string legend = "bodies:";
  for (const Body& body : simulation.bodies()) {
    legend += fmt::format(" {} ({}){}", body.name, simulation.materials()[static_cast<std::size_t>(body.material)].name,
                          &body == &simulation.bodies().back() ? "" : ",");
  }
  if (particles.size() > 0) legend += fmt::format("; {} free elements", particles.size());
  text(cr, left, 4.4 * font, legend, 0.85 * font);

  // Scale bar.
  const double bar = round_length(0.25 * (x1 - x0));
  const double bar_y = top + box_height + 4.2 * font;
  cairo_set_line_width(cr, 2.0);
  cairo_move_to(cr, left, bar_y);
  cairo_line_to(cr, left + bar * scale, bar_y);
  cairo_move_to(cr, left, bar_y - 0.4 * font);
  cairo_line_to(cr, left, bar_y + 0.4 * font);
  cairo_move_to(cr, left + bar * scale, bar_y - 0.4 * font);
  cairo_line_to(cr, left + bar * scale, bar_y + 0.4 * font);
  cairo_stroke(cr);
  text(cr, left + bar * scale + 0.6 * font, bar_y + 0.35 * font, length_label(bar), 0.9 * font);

  // Colour bar.
  const double bar_left = width - right + 0.25 * right;
  const double bar_width = 0.14 * right;
  const double bar_top = top, bar_height = box_height;
  if (field == "body") {
    const std::size_t n = simulation.bodies().size();
    const double row = std::min(1.6 * font, bar_height / static_cast<double>(std::max<std::size_t>(n, 1)));
    for (std::size_t b = 0; b < n; ++b) {
      const Colour c = categories[b % categories.size()];
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      cairo_rectangle(cr, bar_left, bar_top + row * static_cast<double>(b), bar_width, 0.8 * row);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      text(cr, bar_left + bar_width + 0.4 * font, bar_top + row * static_cast<double>(b) + 0.7 * row,
           simulation.bodies()[b].name, 0.85 * font);
    }
  } else {
    const int steps = 256;
    for (int k = 0; k < steps; ++k) {
      const double f0 = static_cast<double>(k) / steps;
      const Colour c = colour_map(f0);
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      cairo_rectangle(cr, bar_left, bar_top + bar_height * (1.0 - f0 - 1.0 / steps), bar_width, bar_height / steps + 1.0);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, bar_left, bar_top, bar_width, bar_height);
    cairo_stroke(cr);
    for (int k = 0; k <= 4; ++k) {
      const double f = k / 4.0;
      const double y = bar_top + bar_height * (1.0 - f);
      cairo_move_to(cr, bar_left + bar_width, y);
      cairo_line_to(cr, bar_left + bar_width + 0.3 * font, y);
      cairo_stroke(cr);
      text(cr, bar_left + bar_width + 0.5 * font, y + 0.35 * font, value_label(low + f * (high - low), low, high), 0.85 * font);
    }
  }

  cairo_destroy(cr);
  std::error_code error;
  std::filesystem::create_directories(directory / "pictures", error);
  const std::filesystem::path file = directory / "pictures" / (name + ".png");
  const std::filesystem::path temporary = file.string() + ".partial";
  const cairo_status_t status = cairo_surface_write_to_png(surface, temporary.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) return false;
  std::filesystem::rename(temporary, file, error);
  return !error;
}

}  // namespace krug::app
