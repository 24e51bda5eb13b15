// Avenues — a drawing as DXF (R2000), through dxflib (see drawing.h).
//
// Coordinates are paper millimetres ($INSUNITS = 4) with y up, as CAD expects. Each layer
// of the drawing is a named DXF layer; each stroke is a LINE carrying the standard DXF
// lineweight nearest its pen width (group 370, in hundredths of a millimetre). dxflib's
// writer goes to a file of its own and flushes it after every number (some 200 ms for
// 10,000 lines); its group-writing calls are virtual, so here they append to a string
// instead, in dxflib's own layout, and write_drawing() puts the bytes in place at once.
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "render/drawing_formats.h"

namespace avenues::detail {

namespace {

/// The lineweights DXF allows [1/100 mm].
constexpr int kLineweights[] = {0,  5,  9,  13, 15, 18, 20,  25,  30,  35,  40,  50,
                                53, 60, 70, 80, 90, 100, 106, 120, 140, 158, 200, 211};

int nearest_lineweight(double mm) {
  int best = kLineweights[0];
  for (int w : kLineweights)
    if (std::fabs(w - mm * 100) < std::fabs(best - mm * 100)) best = w;
  return best;
}

/// dxflib's ASCII writer, writing into `bytes`. It is given no file name, so the file it
/// would open is never created.
class StringWriter : public DL_WriterA {
 public:
  StringWriter() : DL_WriterA("", DL_Codes::AC1015) {}
  void dxfReal(int gc, double value) const override {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed);
    std::string s(buf, r.ptr);
    if (s.find('.') == std::string::npos) s += ".0";
    dxfString(gc, s);
  }
  void dxfInt(int gc, int value) const override { dxfString(gc, std::to_string(value)); }
  void dxfHex(int gc, int value) const override {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%X", static_cast<unsigned>(value));
    dxfString(gc, buf);
  }
  void dxfString(int gc, const char* value) const override { dxfString(gc, std::string(value)); }
  void dxfString(int gc, const std::string& value) const override {
    out_ += gc < 10 ? "  " : gc < 100 ? " " : "";
    out_ += std::to_string(gc);
    out_ += '\n';
    out_ += value;
    out_ += '\n';
  }
  std::string take() { return std::move(out_); }

 private:
  mutable std::string out_;
};

}  // namespace

std::string dxf_bytes(const Drawing& d, const Page& page) {
  StringWriter writer;
  {
    DL_Dxf dxf;  // writes R2000 (AC1015) unless told otherwise
    DL_WriterA& dw = writer;
    dxf.writeHeader(dw);
    dw.dxfString(9, "$INSUNITS");
    dw.dxfInt(70, 4);  // millimetres
    dw.dxfString(9, "$LWDISPLAY");
    dw.dxfInt(290, 1);  // show lineweights
    dw.sectionEnd();

    dw.sectionTables();
    dxf.writeVPort(dw);
    dw.tableLinetypes(3);
    dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
    dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
    dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
    dw.tableEnd();
    const std::vector<Layer> layers = layers_drawn(d);
    dw.tableLayers(int(layers.size()) + 1);
    dxf.writeLayer(dw, DL_LayerData("0", 0), DL_Attributes("", DL_Codes::black, -3, "CONTINUOUS", 1.0));
    for (Layer layer : layers)
      dxf.writeLayer(dw, DL_LayerData(to_string(layer), 0), DL_Attributes("", DL_Codes::black, -3, "CONTINUOUS", 1.0));
    dw.tableEnd();
    dw.tableStyle(1);
    dxf.writeStyle(dw, DL_StyleData("Standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
    dw.tableEnd();
    dxf.writeView(dw);
    dxf.writeUcs(dw);
    dw.tableAppid(1);
    dxf.writeAppid(dw, "ACAD");
    dw.tableEnd();
    dxf.writeDimStyle(dw, 2.5, 1.25, 0.625, 0.625, 2.5);
    dxf.writeBlockRecord(dw);
    dw.tableEnd();
    dw.sectionEnd();

    dw.sectionBlocks();
    for (const char* block : {"*Model_Space", "*Paper_Space", "*Paper_Space0"}) {
      dxf.writeBlock(dw, DL_BlockData(block, 0, 0.0, 0.0, 0.0));
      dxf.writeEndBlock(dw, block);
    }
    dw.sectionEnd();

    dw.sectionEntities();
    for (const Stroke& s : d.strokes) {
      const Vec2 a = page.from_raster_y_up(s.a), b = page.from_raster_y_up(s.b);
      dxf.writeLine(dw, DL_LineData(a.x, a.y, 0.0, b.x, b.y, 0.0),
                    DL_Attributes(to_string(s.layer), 256, nearest_lineweight(page.pen(s.weight)), "BYLAYER", 1.0));
    }
    for (const Label& l : d.labels) {  // middle-centred (72 = 1, 73 = 2)
      const Vec2 p = page.from_raster_y_up(l.at);
      const double h = page.mm(l.height);
      dxf.writeText(dw, DL_TextData(p.x, p.y, 0.0, p.x, p.y, 0.0, h, 1.0, 0, 1, 2, l.text, "Standard", 0.0),
                    DL_Attributes(to_string(Layer::Annotation), 256, nearest_lineweight(page.crease), "BYLAYER", 1.0));
    }
    dw.sectionEnd();
    dxf.writeObjects(dw);
    dxf.writeObjectsEnd(dw);
    dw.dxfEOF();
  }
  return writer.take();
}

}  // namespace avenues::detail
