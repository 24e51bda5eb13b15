// Avenues tests — independent readers of the drawings' files: DXF through dxflib's own
// reader, HPGL through a small parser (its labels, LB ... ETX, included).
#pragma once

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <cmath>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace avenues::testing {

/// Counts what dxflib reads back.
struct DxfCounter : DL_CreationAdapter {
  int lines = 0, polyline_vertices = 0, texts = 0;
  std::set<std::string> layers_used, layers_declared;
  std::set<int> weights;
  std::vector<DL_LineData> line_data;
  std::vector<std::string> text;
  void addLayer(const DL_LayerData& d) override { layers_declared.insert(d.name); }
  void addLine(const DL_LineData& d) override {
    ++lines;
    line_data.push_back(d);
    layers_used.insert(getAttributes().getLayer());
    weights.insert(getAttributes().getWidth());
  }
  void addText(const DL_TextData& d) override {
    ++texts;
    text.push_back(d.text);
    layers_used.insert(getAttributes().getLayer());
  }
  void addVertex(const DL_VertexData&) override { ++polyline_vertices; }
};

/// HPGL read back: pen-down segments, pen-up travel [plotter units], pens, labels.
struct Plot {
  int segments = 0;
  double travel = 0;
  std::set<int> pens;
  std::vector<std::string> labels;
  std::map<int, int> segments_of_pen;
};
inline Plot parse_hpgl(const std::string& text) {
  Plot p;
  double x = 0, y = 0;
  int pen = 0;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i + 2 > text.size()) break;
    const std::string op = text.substr(i, 2);
    i += 2;
    if (op == "LB") {  // a label runs to the terminator (ETX, as DT set it)
      const size_t end = text.find('\x03', i);
      p.labels.push_back(text.substr(i, end - i));
      i = end == std::string::npos ? text.size() : end + 1;
      continue;
    }
    const size_t end = text.find(';', i);
    const std::string argstr = text.substr(i, end - i);
    i = end == std::string::npos ? text.size() : end + 1;
    if (op == "DT") continue;
    std::vector<double> v;
    std::stringstream args(argstr);
    std::string num;
    while (std::getline(args, num, ',')) v.push_back(std::stod(num));
    if (op == "SP") p.pens.insert(pen = int(v.at(0)));
    for (size_t k = 0; k + 1 < v.size() && (op == "PU" || op == "PD"); k += 2) {
      if (op == "PU") p.travel += std::hypot(v[k] - x, v[k + 1] - y);
      else ++p.segments, ++p.segments_of_pen[pen];
      x = v[k], y = v[k + 1];
    }
  }
  return p;
}

}  // namespace avenues::testing
