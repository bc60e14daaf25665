// The log-log SVG plot: data coordinates map to pixels by
//   px = left + (log10 x - log10 x_min) / (log10 x_max - log10 x_min) * width
// (y likewise, upwards), with x_min, x_max the decades around the data.
#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "achd/error.hpp"

namespace achd::cli {
namespace {

constexpr double kWidth = 760, kPlotHeight = 440;
constexpr double kLeft = 80, kRight = 210, kTop = 40, kBottom = 60, kNoteLine = 16;
constexpr std::size_t kNoteChars = 120;

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// Notes broken at spaces into lines of at most kNoteChars characters (longer words stay whole).
std::vector<std::string> wrap(const std::vector<std::string>& notes) {
  std::vector<std::string> lines;
  for (const std::string& note : notes) {
    std::istringstream words(note);
    std::string word, line;
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > kNoteChars) {
        lines.push_back(line);
        line = "  ";
      }
      line += (line.empty() || line == "  " ? "" : " ") + word;
    }
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

std::string fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

struct Decades {
  int lo = 0, hi = 1;  // the axis spans 10^lo .. 10^hi
  void cover(const std::vector<double>& values) {
    double mn = INFINITY, mx = -INFINITY;
    for (double v : values) {
      mn = std::min(mn, std::log10(v));
      mx = std::max(mx, std::log10(v));
    }
    lo = static_cast<int>(std::floor(mn));
    hi = std::max(lo + 1, static_cast<int>(std::ceil(mx)));
  }
  double fraction(double v) const { return (std::log10(v) - lo) / (hi - lo); }
};

}  // namespace

std::string render_svg(const LogLogPlot& plot) {
  std::vector<double> xs, ys;
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points) {
      if (!(p.x > 0 && p.y > 0 && std::isfinite(p.x) && std::isfinite(p.y)))
        throw Error("svg plot: series '" + s.name + "' has a point that is not positive and finite");
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
  if (xs.empty()) throw Error("svg plot: nothing to plot");
  if (plot.x_marker > 0) xs.push_back(plot.x_marker);
  Decades dx, dy;
  dx.cover(xs);
  dy.cover(ys);
  const double w = kWidth - kLeft - kRight, h = kPlotHeight - kTop - kBottom;
  const std::vector<std::string> notes = wrap(plot.notes);
  const double height = kPlotHeight + kNoteLine * notes.size() + 8;
  auto px = [&](double x) { return kLeft + dx.fraction(x) * w; };
  auto py = [&](double y) { return kTop + (1 - dy.fraction(y)) * h; };

  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << fixed(height)
    << "\" viewBox=\"0 0 " << kWidth << ' ' << fixed(height) << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\" font-weight=\"bold\">" << escape(plot.title) << "</text>\n";
  // Decade grid and tick labels.
  for (int k = dx.lo; k <= dx.hi; ++k) {
    const double x = px(std::pow(10.0, k));
    o << "<line x1=\"" << fixed(x) << "\" y1=\"" << kTop << "\" x2=\"" << fixed(x) << "\" y2=\"" << kTop + h
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << fixed(x) << "\" y=\"" << kTop + h + 16
      << "\" text-anchor=\"middle\">1e" << k << "</text>\n";
  }
  for (int k = dy.lo; k <= dy.hi; ++k) {
    const double y = py(std::pow(10.0, k));
    o << "<line x1=\"" << kLeft << "\" y1=\"" << fixed(y) << "\" x2=\"" << kLeft + w << "\" y2=\"" << fixed(y)
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << kLeft - 6 << "\" y=\"" << fixed(y + 4)
      << "\" text-anchor=\"end\">1e" << k << "</text>\n";
  }
  o << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << w << "\" height=\"" << h
    << "\" fill=\"none\" stroke=\"#333\"/>\n"
    << "<text x=\"" << kLeft + w / 2 << "\" y=\"" << kTop + h + 38 << "\" text-anchor=\"middle\">"
    << escape(plot.x_label) << "</text>\n"
    << "<text transform=\"translate(18," << kTop + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << escape(plot.y_label) << "</text>\n";
  if (plot.x_marker > 0) {
    const double x = px(plot.x_marker);
    o << "<line x1=\"" << fixed(x) << "\" y1=\"" << kTop << "\" x2=\"" << fixed(x) << "\" y2=\"" << kTop + h
      << "\" stroke=\"#888\" stroke-dasharray=\"6 4\"/>\n<text x=\"" << fixed(x - 4) << "\" y=\"" << kTop + h - 6
      << "\" text-anchor=\"end\" fill=\"#555\">" << escape(plot.x_marker_label) << "</text>\n";
  }
  // Series: line, markers, Pareto rings, labels; then the legend entry.
  double legend_y = kTop + 10;
  for (const PlotSeries& s : plot.series) {
    if (!s.points.empty()) {
      o << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"2\" points=\"";
      for (const PlotPoint& p : s.points) o << fixed(px(p.x)) << ',' << fixed(py(p.y)) << ' ';
      o << "\"/>\n";
    }
    for (const PlotPoint& p : s.points) {
      const double x = px(p.x), y = py(p.y);
      o << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(y) << "\" r=\"3.5\" fill=\"" << s.color << "\"/>\n";
      if (p.pareto)
        o << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(y)
          << "\" r=\"7\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
      if (!p.label.empty())
        o << "<text x=\"" << fixed(x + 6) << "\" y=\"" << fixed(y - 6) << "\" font-size=\"9\" fill=\"#444\">"
          << escape(p.label) << "</text>\n";
    }
    const double lx = kLeft + w + 16;
    o << "<line x1=\"" << lx << "\" y1=\"" << legend_y << "\" x2=\"" << lx + 24 << "\" y2=\"" << legend_y
      << "\" stroke=\"" << s.color << "\" stroke-width=\"2\"/>\n<circle cx=\"" << lx + 12 << "\" cy=\"" << legend_y
      << "\" r=\"3.5\" fill=\"" << s.color << "\"/>\n<text x=\"" << lx + 30 << "\" y=\"" << legend_y + 4 << "\">"
      << escape(s.name) << "</text>\n";
    legend_y += 20;
  }
  const double lx = kLeft + w + 16;
  o << "<circle cx=\"" << lx + 12 << "\" cy=\"" << legend_y << "\" r=\"7\" fill=\"none\" stroke=\"black\" "
    << "stroke-width=\"1.5\"/>\n<text x=\"" << lx + 30 << "\" y=\"" << legend_y + 4 << "\">Pareto front</text>\n";
  for (std::size_t i = 0; i < notes.size(); ++i)
    o << "<text x=\"10\" y=\"" << fixed(kPlotHeight + kNoteLine * i + 4) << "\" font-size=\"11\" fill=\"#333\">"
      << escape(notes[i]) << "</text>\n";
  o << "</svg>\n";
  return o.str();
}

}  // namespace achd::cli
