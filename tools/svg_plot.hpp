#pragma once
// A log-log line plot written as a standalone SVG file: one polyline per series with a
// marker per point, a ring around points on the Pareto front, decade ticks and grid,
// axis labels, a legend and lines of notes under the plot.
#include <string>
#include <vector>

namespace achd::cli {

struct PlotPoint {
  double x = 0, y = 0;  // both > 0 and finite (the caller leaves out anything else)
  std::string label;    // written small beside the marker ("" for none)
  bool pareto = false;
};

struct PlotSeries {
  std::string name;
  std::string color;  // any SVG colour
  std::vector<PlotPoint> points;
};

struct LogLogPlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  std::vector<std::string> notes;  // one line each, under the plot
  double x_marker = 0;             // > 0: a dashed vertical line at this x
  std::string x_marker_label;
};

std::string render_svg(const LogLogPlot& plot);

}  // namespace achd::cli
