// Avenues — IFC4 face sets and styles as IFC2X3 writes them (see ifc4_for_assimp.h).
#include "plans/formats/ifc4_for_assimp.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <unordered_map>
#include <unordered_set>

#include "plans/formats/ifc_step.h"

namespace avenues {
namespace {

// IfcTriangulatedFaceSet(Coordinates, Normals, Closed, CoordIndex, PnIndex);
// IfcPolygonalFaceSet(Coordinates, Closed, Faces, PnIndex), IFC4 ADD2 alike.
struct Layout {
  size_t closed, faces, pn_index;
};
constexpr Layout kTriangulated{2, 3, 4}, kPolygonal{1, 2, 3};

/// IFC4 solids that are IFC2X3 solids with more said: read as those, the rest left out.
struct Narrowing {
  const char* from;
  const char* to;
  size_t keep;       ///< attributes the IFC2X3 entity has (the first ones)
  const char* lost;  ///< what is left out
};
constexpr Narrowing kNarrowings[] = {
    {"IfcExtrudedAreaSolidTapered", "IfcExtrudedAreaSolid", 4, "its taper (the end profile)"},
    {"IfcRevolvedAreaSolidTapered", "IfcRevolvedAreaSolid", 4, "its taper (the end profile)"},
    {"IfcSweptDiskSolidPolygonal", "IfcSweptDiskSolid", 5, "its fillets"},
};

/// IFC4 geometry IFC2X3 has no form for (NURBS boundaries, sweeps along a fixed reference,
/// curved surfaces as items): left out, said.
constexpr const char* kUnreadable[] = {"IfcAdvancedBrep", "IfcAdvancedBrepWithVoids", "IfcFixedReferenceSweptAreaSolid",
                                      "IfcCylindricalSurface", "IfcSphericalSurface", "IfcToroidalSurface"};

/// CSG primitives Assimp reads in no form: left out, said. (IfcBlock and
/// IfcRightCircularCylinder are extrusions: see Rewriter::extrusion.)
constexpr const char* kPrimitivesLeftOut[] = {"IfcSphere", "IfcRectangularPyramid", "IfcRightCircularCone"};

/// The other solids rewritten here, by name for messages (their keywords are matched in
/// the code that rewrites them).
constexpr const char* kRewrittenSolids[] = {"IfcSweptDiskSolid", "IfcBlock", "IfcRightCircularCylinder", "IfcCsgSolid"};

/// IFC4's kinds of product that IFC2X3 knows under a more general name (its supertype, or a
/// proxy): read as that, every attribute kept (IFC2X3's reader reads what it knows of them).
/// The IFC4 names as IFC spells them; a keyword matches in upper case.
/// "StandardCase" and "ElementedCase" say how the geometry was made; the distribution
/// elements IFC4 split by function are IFC2X3's flow terminals, segments, fittings, ...
constexpr std::pair<const char*, const char*> kRenamed[] = {
    {"IfcBeamStandardCase", "IFCBEAM"}, {"IfcColumnStandardCase", "IFCCOLUMN"}, {"IfcDoorStandardCase", "IFCDOOR"},
    {"IfcMemberStandardCase", "IFCMEMBER"}, {"IfcOpeningStandardCase", "IFCOPENINGELEMENT"},
    {"IfcPlateStandardCase", "IFCPLATE"}, {"IfcSlabStandardCase", "IFCSLAB"}, {"IfcSlabElementedCase", "IFCSLAB"},
    {"IfcWallElementedCase", "IFCWALL"}, {"IfcWindowStandardCase", "IFCWINDOW"},
    {"IfcFurniture", "IFCFURNISHINGELEMENT"}, {"IfcSystemFurnitureElement", "IFCFURNISHINGELEMENT"},
    {"IfcChimney", "IFCBUILDINGELEMENTPROXY"}, {"IfcShadingDevice", "IFCBUILDINGELEMENTPROXY"},
    {"IfcCivilElement", "IFCBUILDINGELEMENTPROXY"}, {"IfcGeographicElement", "IFCBUILDINGELEMENTPROXY"},
    {"IfcVibrationIsolator", "IFCDISCRETEACCESSORY"},
    {"IfcAirTerminal", "IFCFLOWTERMINAL"}, {"IfcAudioVisualAppliance", "IFCFLOWTERMINAL"},
    {"IfcCommunicationsAppliance", "IFCFLOWTERMINAL"}, {"IfcElectricAppliance", "IFCFLOWTERMINAL"},
    {"IfcFireSuppressionTerminal", "IFCFLOWTERMINAL"}, {"IfcLamp", "IFCFLOWTERMINAL"},
    {"IfcLightFixture", "IFCFLOWTERMINAL"}, {"IfcMedicalDevice", "IFCFLOWTERMINAL"}, {"IfcOutlet", "IFCFLOWTERMINAL"},
    {"IfcSanitaryTerminal", "IFCFLOWTERMINAL"}, {"IfcSpaceHeater", "IFCFLOWTERMINAL"},
    {"IfcStackTerminal", "IFCFLOWTERMINAL"}, {"IfcWasteTerminal", "IFCFLOWTERMINAL"},
    {"IfcCableCarrierSegment", "IFCFLOWSEGMENT"}, {"IfcCableSegment", "IFCFLOWSEGMENT"},
    {"IfcDuctSegment", "IFCFLOWSEGMENT"}, {"IfcPipeSegment", "IFCFLOWSEGMENT"},
    {"IfcCableCarrierFitting", "IFCFLOWFITTING"}, {"IfcCableFitting", "IFCFLOWFITTING"},
    {"IfcDuctFitting", "IFCFLOWFITTING"}, {"IfcJunctionBox", "IFCFLOWFITTING"}, {"IfcPipeFitting", "IFCFLOWFITTING"},
    {"IfcAirTerminalBox", "IFCFLOWCONTROLLER"}, {"IfcDamper", "IFCFLOWCONTROLLER"},
    {"IfcElectricDistributionBoard", "IFCFLOWCONTROLLER"}, {"IfcElectricTimeControl", "IFCFLOWCONTROLLER"},
    {"IfcFlowMeter", "IFCFLOWCONTROLLER"}, {"IfcProtectiveDevice", "IFCFLOWCONTROLLER"},
    {"IfcSwitchingDevice", "IFCFLOWCONTROLLER"}, {"IfcValve", "IFCFLOWCONTROLLER"},
    {"IfcCompressor", "IFCFLOWMOVINGDEVICE"}, {"IfcFan", "IFCFLOWMOVINGDEVICE"}, {"IfcPump", "IFCFLOWMOVINGDEVICE"},
    {"IfcElectricFlowStorageDevice", "IFCFLOWSTORAGEDEVICE"}, {"IfcTank", "IFCFLOWSTORAGEDEVICE"},
    {"IfcDuctSilencer", "IFCFLOWTREATMENTDEVICE"}, {"IfcFilter", "IFCFLOWTREATMENTDEVICE"},
    {"IfcInterceptor", "IFCFLOWTREATMENTDEVICE"},
    {"IfcAirToAirHeatRecovery", "IFCENERGYCONVERSIONDEVICE"}, {"IfcBoiler", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcBurner", "IFCENERGYCONVERSIONDEVICE"}, {"IfcChiller", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcCoil", "IFCENERGYCONVERSIONDEVICE"}, {"IfcCondenser", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcCooledBeam", "IFCENERGYCONVERSIONDEVICE"}, {"IfcCoolingTower", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcElectricGenerator", "IFCENERGYCONVERSIONDEVICE"}, {"IfcElectricMotor", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcEngine", "IFCENERGYCONVERSIONDEVICE"}, {"IfcEvaporativeCooler", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcEvaporator", "IFCENERGYCONVERSIONDEVICE"}, {"IfcHeatExchanger", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcHumidifier", "IFCENERGYCONVERSIONDEVICE"}, {"IfcMotorConnection", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcSolarDevice", "IFCENERGYCONVERSIONDEVICE"}, {"IfcTransformer", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcTubeBundle", "IFCENERGYCONVERSIONDEVICE"}, {"IfcUnitaryEquipment", "IFCENERGYCONVERSIONDEVICE"},
    {"IfcActuator", "IFCDISTRIBUTIONCONTROLELEMENT"}, {"IfcAlarm", "IFCDISTRIBUTIONCONTROLELEMENT"},
    {"IfcController", "IFCDISTRIBUTIONCONTROLELEMENT"}, {"IfcFlowInstrument", "IFCDISTRIBUTIONCONTROLELEMENT"},
    {"IfcProtectiveDeviceTrippingUnit", "IFCDISTRIBUTIONCONTROLELEMENT"}, {"IfcSensor", "IFCDISTRIBUTIONCONTROLELEMENT"},
    {"IfcUnitaryControlElement", "IFCDISTRIBUTIONCONTROLELEMENT"},
    // Not geometry, but a unit Assimp cannot resolve fails the whole file.
    {"IfcConversionBasedUnitWithOffset", "IFCCONVERSIONBASEDUNIT"},
};

/// Parameterized profiles whose Position IFC4 made optional (their third attribute).
constexpr const char* kProfiles[] = {
    "IFCRECTANGLEPROFILEDEF", "IFCROUNDEDRECTANGLEPROFILEDEF", "IFCRECTANGLEHOLLOWPROFILEDEF", "IFCCIRCLEPROFILEDEF",
    "IFCCIRCLEHOLLOWPROFILEDEF", "IFCELLIPSEPROFILEDEF", "IFCISHAPEPROFILEDEF", "IFCASYMMETRICISHAPEPROFILEDEF",
    "IFCLSHAPEPROFILEDEF", "IFCTSHAPEPROFILEDEF", "IFCUSHAPEPROFILEDEF", "IFCCSHAPEPROFILEDEF", "IFCZSHAPEPROFILEDEF",
    "IFCTRAPEZIUMPROFILEDEF"};

/// Swept solids whose Position IFC4 made optional (IfcSweptAreaSolid's second attribute).
constexpr const char* kSweptAreaSolids[] = {"IFCEXTRUDEDAREASOLID", "IFCREVOLVEDAREASOLID",
                                            "IFCSURFACECURVESWEPTAREASOLID"};

/// How many warnings name their sets; the rest are counted.
constexpr size_t kWarningsListed = 10;

/// "head#1,#2,#3))": a record's body listing references.
std::string listing(const char* head, const std::vector<unsigned long long>& ids, const char* tail) {
  std::string s = head;
  for (size_t j = 0; j < ids.size(); ++j) {
    if (j) s += ',';
    s += step_reference_text(ids[j]);
  }
  return s + tail;
}

/// Whether an attribute is an IfcRoot's GlobalId: 128 bits in 22 characters of IFC's base 64,
/// the first holding the top 2 bits ('0' to '3'). A property's or quantity's Name, also first
/// and followed by an optional Description, is not one ('WarrantyGuarantorLabor').
bool is_global_id(std::string_view a) {
  a = step_trimmed(a);
  if (a.size() != 24 || a.front() != '\'' || a.back() != '\'' || a[1] < '0' || a[1] > '3') return false;
  for (char c : a.substr(1, 22))
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '$') return false;
  return true;
}

/// A STEP integer ("12"), else nullopt.
std::optional<long long> integer(std::string_view a) {
  if (a.empty() || a.size() > 18) return std::nullopt;
  long long n = 0;
  for (char c : a) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + (c - '0');
  }
  return n;
}

/// The coordinates of a point "(x,y)" or "(x,y,z)" of finite STEP reals; nullopt otherwise.
std::optional<std::vector<double>> coordinates(std::string_view item) {
  const auto xyz = step_list(item);
  if (!xyz || xyz->size() < 2 || xyz->size() > 3) return std::nullopt;
  std::vector<double> out;
  for (std::string_view v : *xyz) {
    const std::string s(v);
    char* end = nullptr;
    const double d = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size() || !std::isfinite(d)) return std::nullopt;
    out.push_back(d);
  }
  return out;
}

/// A STEP real: the shortest decimal that reads back as d, with its decimal point.
std::string step_real(double d) {
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*G", digits, d);
    if (std::strtod(buf, nullptr) == d) break;
  }
  std::string s = buf;
  const size_t e = s.find('E');
  if (s.find('.') == std::string::npos) s.insert(e == std::string::npos ? s.size() : e, ".");
  return s;
}

/// [rad] The widest turn an arc of an IfcIndexedPolyCurve makes between two points of the
/// polyline that stands for it: 5°, within a thousandth of its radius (a millimetre on a
/// metre's curve, as a plan's arcs).
constexpr double kArcStep = 5.0 * 3.14159265358979323846 / 180;

/// The points strictly inside the circular arc from a through m to b (2 or 3 coordinates
/// each), at most kArcStep apart in angle; none where the three are collinear.
std::vector<std::vector<double>> arc_between(const std::vector<double>& a, const std::vector<double>& m,
                                             const std::vector<double>& b) {
  const size_t n = a.size();
  auto sub = [&](const std::vector<double>& p, const std::vector<double>& q) {
    std::array<double, 3> r{0, 0, 0};
    for (size_t k = 0; k < n; ++k) r[k] = p[k] - q[k];
    return r;
  };
  auto dot = [](const std::array<double, 3>& p, const std::array<double, 3>& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  auto cross = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::array<double, 3>{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
  };
  // The circle through a, m, b, in the plane of u = m − a and v = b − a (normal w = u × v):
  // its centre is a + c, c = (|v|²·(w × u) + |u|²·(v × w)) / (2|w|²).
  const std::array<double, 3> u = sub(m, a), v = sub(b, a), w = cross(u, v);
  const double ww = dot(w, w);
  if (!(ww > 1e-18 * dot(u, u) * dot(v, v))) return {};  // collinear: a straight piece
  const std::array<double, 3> t1 = cross(w, u), t2 = cross(v, w);
  std::array<double, 3> c{};
  for (size_t k = 0; k < 3; ++k) c[k] = (dot(v, v) * t1[k] + dot(u, u) * t2[k]) / (2 * ww);
  // From a (at angle 0) towards m, about the normal w: the sweep to b, the way through m.
  const std::array<double, 3> ra{-c[0], -c[1], -c[2]};  // a − (a + c): from the centre to a
  const double r = std::sqrt(dot(ra, ra));
  const std::array<double, 3> nrm{w[0] / std::sqrt(ww), w[1] / std::sqrt(ww), w[2] / std::sqrt(ww)};
  const std::array<double, 3> e1{ra[0] / r, ra[1] / r, ra[2] / r}, e2 = cross(nrm, e1);
  auto angle_of = [&](const std::array<double, 3>& p) {  // p relative to a
    const std::array<double, 3> q{p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    double t = std::atan2(dot(q, e2), dot(q, e1));
    return t < 0 ? t + 2 * 3.14159265358979323846 : t;
  };
  const double sweep = angle_of(v);
  const int steps = std::max(1, int(std::ceil(sweep / kArcStep)));
  std::vector<std::vector<double>> out;
  for (int k = 1; k < steps; ++k) {
    const double t = sweep * k / steps;
    std::vector<double> p(n);
    for (size_t j = 0; j < n; ++j) p[j] = a[j] + c[j] + r * (std::cos(t) * e1[j] + std::sin(t) * e2[j]);
    out.push_back(std::move(p));
  }
  return out;
}

/// A list of STEP integers, else nullopt.
std::optional<std::vector<long long>> integers(std::string_view a) {
  const auto items = step_list(a);
  if (!items) return std::nullopt;
  std::vector<long long> out;
  out.reserve(items->size());
  for (std::string_view i : *items) {
    const auto n = integer(i);
    if (!n) return std::nullopt;
    out.push_back(*n);
  }
  return out;
}

/// Whether an upper-case keyword is IFC's name `name` ("IFCLAMP", "IfcLamp").
bool upper_is(std::string_view keyword, std::string_view name) {
  return keyword.size() == name.size() &&
         std::equal(keyword.begin(), keyword.end(), name.begin(),
                    [](char k, char n) { return k == std::toupper(static_cast<unsigned char>(n)); });
}

/// IFC's own spelling of a keyword named in the tables above ("IfcExtrudedAreaSolid" of
/// "IFCEXTRUDEDAREASOLID"), for messages; another keyword as it is.
std::string title_case(std::string_view keyword) {
  for (const Narrowing& n : kNarrowings)
    for (const char* name : {n.from, n.to})
      if (upper_is(keyword, name)) return name;
  using Names = std::span<const char* const>;
  for (Names names : {Names(kUnreadable), Names(kPrimitivesLeftOut), Names(kRewrittenSolids)})
    for (const char* name : names)
      if (upper_is(keyword, name)) return name;
  return std::string(keyword);
}

/// The STEP keyword of IFC's name for an entity: "IFCEXTRUDEDAREASOLID" of "IfcExtrudedAreaSolid".
std::string keyword_of(std::string_view name) {
  std::string k(name);
  for (char& c : k) c = char(std::toupper(static_cast<unsigned char>(c)));
  return k;
}

class Rewriter {
 public:
  explicit Rewriter(std::string_view text) : text_(text) {}

  std::optional<Ifc4Rewrite> run() {
    std::vector<StepRecord> sets, styled, curves, other;  // in the text's order, each
    std::unordered_set<unsigned long long> styles;  // IfcPresentationStyle records
    for_each_step_record(text_, [&](const StepRecord& r) {
      max_id_ = std::max(max_id_, r.id);
      if (needs_fixing(r)) other.push_back(r);
      if (r.keyword == "IFCPOLYLINE" && !r.attributes.empty())
        if (const auto corners = step_list(r.attributes[0])) polyline_points_[r.id] = corners->size();
      if (r.keyword == "IFCTRIANGULATEDFACESET" || r.keyword == "IFCPOLYGONALFACESET") sets.push_back(r);
      else if ((r.keyword == "IFCCARTESIANPOINTLIST3D" || r.keyword == "IFCCARTESIANPOINTLIST2D") && !r.attributes.empty()) {
        point_lists_[r.id] = r.attributes[0];
        point_dimension_[r.id] = r.keyword == "IFCCARTESIANPOINTLIST2D" ? 2 : 3;
      } else if (r.keyword == "IFCINDEXEDPOLYCURVE") curves.push_back(r);
      else if (r.keyword == "IFCINDEXEDPOLYGONALFACE" || r.keyword == "IFCINDEXEDPOLYGONALFACEWITHVOIDS")
        indexed_faces_[r.id] = r.attributes;
      else if (r.keyword == "IFCSTYLEDITEM") styled.push_back(r);
      else if (r.keyword == "IFCBLOCK" || r.keyword == "IFCRIGHTCIRCULARCYLINDER" || r.keyword == "IFCBOOLEANRESULT" ||
               r.keyword == "IFCBOOLEANCLIPPINGRESULT")
        csg_operands_[r.id] = r;
      else if (r.keyword == "IFCSURFACESTYLE" || r.keyword == "IFCCURVESTYLE" || r.keyword == "IFCFILLAREASTYLE" ||
               r.keyword == "IFCTEXTSTYLE")
        styles.insert(r.id);
    });
    next_id_ = max_id_;
    Ifc4Rewrite out;
    std::vector<std::pair<const StepRecord*, std::string>> changed;  // in the text's order, once sorted
    for (const StepRecord& r : sets) changed.push_back({&r, rewritten(r)});
    out.face_sets = sets.size();
    for (const StepRecord& r : curves) changed.push_back({&r, polyline(r)});
    out.curves = curves.size();
    for (const StepRecord& r : other)
      if (std::optional<std::string> f = fixed(r, out)) changed.push_back({&r, std::move(*f)});
    for (const StepRecord& r : styled) {
      std::optional<std::string> s = assigned(r, styles);
      if (!s) continue;
      changed.push_back({&r, std::move(*s)});
      ++out.styles;
    }
    if (changed.empty()) return std::nullopt;
    std::sort(changed.begin(), changed.end(), [](const auto& a, const auto& b) { return a.first->offset < b.first->offset; });
    out.text.reserve(text_.size() + text_.size() / 2);
    size_t copied = 0;
    for (const auto& [r, replacement] : changed) {
      out.text.append(text_.substr(copied, r->offset - copied));
      out.text += replacement;
      copied = r->offset + r->size;
    }
    out.text.append(text_.substr(copied));
    out.warnings = std::move(warnings_);
    out.left_out = std::move(left_out_);
    out.left_out_count = left_out_count_;
    if (unlisted_ > 0) out.warnings.push_back(std::to_string(unlisted_) + " more IFC4 records lost some of their geometry");
    return out;
  }

 private:
  /// The record "#id=..." that stands for face set r, and the new records it refers to,
  /// each ended by ";\n" but the last (the text's own ';' ends it).
  std::string rewritten(const StepRecord& r) {
    const bool triangulated = r.keyword == "IFCTRIANGULATEDFACESET";
    const Layout at = triangulated ? kTriangulated : kPolygonal;
    const char* type = triangulated ? "IfcTriangulatedFaceSet" : "IfcPolygonalFaceSet";
    records_.clear();
    auto give_up = [&](const std::string& why) {
      warn(r, type, why + ": its faces are dropped");
      const unsigned long long corner = add("IFCCARTESIANPOINT((0.,0.,0.))");
      return finish(r.id, listing("IFCBOUNDINGBOX(", {corner}, ",0.,0.,0.)"));
    };
    const std::vector<std::string_view>& a = r.attributes;
    if (a.size() <= at.faces) return give_up("it has only " + std::to_string(a.size()) + " attributes");
    const auto list = step_reference(a[0]);
    const auto found = list ? point_lists_.find(*list) : point_lists_.end();
    if (found == point_lists_.end()) return give_up("its Coordinates are no IfcCartesianPointList3D");
    const std::vector<std::string_view>* points = points_of(*list, found->second);
    if (!points) return give_up("its point list " + step_reference_text(*list) + " is not a list of three numbers each");
    std::optional<std::vector<long long>> pn;
    if (a.size() > at.pn_index && step_trimmed(a[at.pn_index]) != "$") {
      pn = integers(a[at.pn_index]);
      if (!pn) return give_up("its PnIndex is not a list of integers");
    }
    // The faces' loops, as 1-based indices of the faces' own numbering.
    std::vector<std::vector<std::vector<long long>>> faces;
    size_t unreadable = 0;
    if (triangulated) {
      const auto tris = step_list(a[at.faces]);
      if (!tris) return give_up("its CoordIndex is not a list");
      for (std::string_view t : *tris) {
        auto loop = integers(t);
        if (!loop) ++unreadable;
        else faces.push_back({std::move(*loop)});
      }
    } else {
      const auto refs = step_list(a[at.faces]);
      if (!refs) return give_up("its Faces are not a list");
      for (std::string_view f : *refs) {
        const auto id = step_reference(f);
        const auto face = id ? indexed_faces_.find(*id) : indexed_faces_.end();
        std::optional<std::vector<long long>> outer;
        if (face != indexed_faces_.end() && !face->second.empty()) outer = integers(face->second[0]);
        if (!outer) {
          ++unreadable;
          continue;
        }
        std::vector<std::vector<long long>> loops{std::move(*outer)};
        if (face->second.size() > 1) {  // IfcIndexedPolygonalFaceWithVoids: its inner loops
          const auto inner = step_list(face->second[1]);
          for (size_t k = 0; inner && k < inner->size(); ++k)
            if (auto loop = integers((*inner)[k])) loops.push_back(std::move(*loop));
        }
        faces.push_back(std::move(loops));
      }
    }
    // Indices into the point list; a loop with fewer than three distinct points bounds nothing.
    std::unordered_map<size_t, unsigned long long> point_id;
    std::vector<unsigned long long> face_ids;
    size_t dropped = 0;
    for (const auto& loops : faces) {
      std::vector<unsigned long long> bounds;
      bool outer_ok = true;
      for (size_t k = 0; k < loops.size() && outer_ok; ++k) {
        std::vector<size_t> idx;
        bool ok = true;
        for (long long i : loops[k]) {
          if (pn) i = i >= 1 && size_t(i) <= pn->size() ? (*pn)[size_t(i - 1)] : 0;
          if (i < 1 || size_t(i) > points->size()) {
            ok = false;
            break;
          }
          if (idx.empty() || idx.back() != size_t(i - 1)) idx.push_back(size_t(i - 1));
        }
        while (idx.size() > 1 && idx.front() == idx.back()) idx.pop_back();
        std::vector<size_t> distinct = idx;
        std::sort(distinct.begin(), distinct.end());
        ok = ok && std::unique(distinct.begin(), distinct.end()) - distinct.begin() >= 3;
        if (!ok) {
          outer_ok = k > 0;  // an inner loop that bounds nothing is left out; an outer one costs its face
          continue;
        }
        std::vector<unsigned long long> corners;
        for (size_t i : idx) {
          auto [it, fresh] = point_id.try_emplace(i, 0);
          if (fresh) it->second = add("IFCCARTESIANPOINT(" + std::string((*points)[i]) + ")");
          corners.push_back(it->second);
        }
        const unsigned long long l = add(listing("IFCPOLYLOOP((", corners, "))"));
        bounds.push_back(add(listing(k == 0 ? "IFCFACEOUTERBOUND(" : "IFCFACEBOUND(", {l}, ",.T.)")));
      }
      if (!outer_ok) {
        ++dropped;
        continue;
      }
      face_ids.push_back(add(listing("IFCFACE((", bounds, "))")));
    }
    if (unreadable + dropped > 0)
      warn(r, type, std::to_string(unreadable + dropped) + " of its " + std::to_string(unreadable + faces.size()) +
                        " faces cannot be used (not a list of indices, a point its list does not have, or fewer "
                        "than three points): dropped");
    if (face_ids.empty()) {
      records_.clear();
      return give_up("no face is left");
    }
    const bool closed = step_trimmed(a[at.closed]) == ".T." && unreadable + dropped == 0;
    const unsigned long long s = add(listing(closed ? "IFCCLOSEDSHELL((" : "IFCOPENSHELL((", face_ids, "))"));
    return finish(r.id, closed ? listing("IFCFACETEDBREP(", {s}, ")") : listing("IFCSHELLBASEDSURFACEMODEL((", {s}, "))"));
  }

  /// IfcStyledItem(Item, Styles, Name) with each style it names directly (IFC4) wrapped in a
  /// new IfcPresentationStyleAssignment; nullopt when it names none directly.
  std::optional<std::string> assigned(const StepRecord& r, const std::unordered_set<unsigned long long>& styles) {
    if (r.attributes.size() != 3) return std::nullopt;
    const auto items = step_list(r.attributes[1]);
    if (!items) return std::nullopt;
    records_.clear();
    std::vector<unsigned long long> ids;
    for (std::string_view item : *items) {
      const auto id = step_reference(item);
      if (!id) return std::nullopt;  // not a list of references: left for Assimp to judge
      ids.push_back(styles.count(*id) ? add(listing("IFCPRESENTATIONSTYLEASSIGNMENT((", {*id}, "))")) : *id);
    }
    if (records_.empty()) return std::nullopt;
    std::string body = "IFCSTYLEDITEM(";
    body += r.attributes[0];
    body += listing(",(", ids, "),");
    body += r.attributes[2];
    return finish(r.id, body + ")");
  }

  /// Whether fixed() has something to do with r.
  static bool needs_fixing(const StepRecord& r) {
    auto is = [&](const char* k) { return r.keyword == k; };
    return std::any_of(std::begin(kRenamed), std::end(kRenamed), [&](const auto& n) { return upper_is(r.keyword, n.first); }) ||
           std::any_of(std::begin(kNarrowings), std::end(kNarrowings), [&](const Narrowing& n) { return upper_is(r.keyword, n.from); }) ||
           std::any_of(std::begin(kUnreadable), std::end(kUnreadable), [&](const char* n) { return upper_is(r.keyword, n); }) ||
           std::any_of(std::begin(kSweptAreaSolids), std::end(kSweptAreaSolids), is) || is("IFCSWEPTDISKSOLID") ||
           std::any_of(std::begin(kProfiles), std::end(kProfiles), is) || is("IFCADVANCEDFACE") ||
           is("IFCBLOCK") || is("IFCRIGHTCIRCULARCYLINDER") || is("IFCCSGSOLID") ||
           std::any_of(std::begin(kPrimitivesLeftOut), std::end(kPrimitivesLeftOut), [&](const char* n) { return upper_is(r.keyword, n); }) ||
           (r.attributes.size() >= 2 && is_global_id(r.attributes[0]) && step_trimmed(r.attributes[1]) == "$");
  }

  /// Record r as IFC2X3 says it, or nullopt when it is that already:
  /// - an IFC4 kind of product (kRenamed) as the IFC2X3 kind it is one of;
  /// - a solid of kNarrowings as its IFC2X3 kind (said), one of kUnreadable as an empty
  ///   bounding box (said);
  /// - an IfcRoot without an OwnerHistory given one (the same for all, made once);
  /// - a swept area solid without a Position placed where its profile is (an identity
  ///   placement, made once);
  /// - an IfcSweptDiskSolid without StartParam or EndParam, along an IfcPolyline, given
  ///   its polyline's whole range (0 to the number of its sides); along another directrix,
  ///   left out (said);
  /// - an IfcBlock or IfcRightCircularCylinder as the extrusion it is (extrusion()), an
  ///   IfcCsgSolid as its tree's root (Assimp reads a boolean result whose first operand is
  ///   a swept solid or another boolean result); a sphere, cone or pyramid left out (said).
  std::optional<std::string> fixed(const StepRecord& r, Ifc4Rewrite& out) {
    records_.clear();
    std::string keyword = r.keyword;
    std::vector<std::string> a(r.attributes.begin(), r.attributes.end());
    bool changed = false;
    for (const auto& [from, to] : kRenamed) {
      if (!upper_is(keyword, from)) continue;
      if (!a.empty() && is_global_id(a[0])) out.kinds[std::string(step_trimmed(a[0]).substr(1, 22))] = from;
      keyword = to, changed = true, ++out.products;
    }
    const std::string type = title_case(keyword);
    for (const Narrowing& n : kNarrowings) {
      if (!upper_is(keyword, n.from) || a.size() < n.keep) continue;
      warn(r, type.c_str(), std::string("read as an ") + n.to + ", without " + n.lost);
      keyword = keyword_of(n.to), a.resize(n.keep), changed = true, ++out.solids;
    }
    auto left_out = [&](const std::string& why) {
      warn(r, type.c_str(), why + ": its geometry is left out", true);
      records_.clear();
      ++out.solids;
      const unsigned long long corner = add("IFCCARTESIANPOINT((0.,0.,0.))");
      return finish(r.id, listing("IFCBOUNDINGBOX(", {corner}, ",0.,0.,0.)"));
    };
    if (std::any_of(std::begin(kUnreadable), std::end(kUnreadable), [&](const char* n) { return upper_is(keyword, n); }))
      return left_out("IFC2X3, which Assimp reads, has no form for it");
    if (a.size() >= 2 && is_global_id(a[0]) && step_trimmed(a[1]) == "$") {
      if (!owner_) {
        const unsigned long long person = add("IFCPERSON($,$,'',$,$,$,$,$)");
        const unsigned long long org = add("IFCORGANIZATION($,'',$,$,$)");
        const unsigned long long user = add(listing("IFCPERSONANDORGANIZATION(", {person, org}, ",$)"));
        const unsigned long long app = add(listing("IFCAPPLICATION(", {org}, ",'','','')"));
        owner_ = add(listing("IFCOWNERHISTORY(", {user, app}, ",$,.NOCHANGE.,$,$,$,0)"));
      }
      a[1] = step_reference_text(owner_), changed = true, ++out.owners;
    }
    if (std::any_of(std::begin(kSweptAreaSolids), std::end(kSweptAreaSolids), [&](const char* k) { return keyword == k; }) &&
        a.size() >= 2 && step_trimmed(a[1]) == "$") {
      if (!placement_) {
        const unsigned long long origin = add("IFCCARTESIANPOINT((0.,0.,0.))");
        placement_ = add(listing("IFCAXIS2PLACEMENT3D(", {origin}, ",$,$)"));
      }
      a[1] = step_reference_text(placement_), changed = true;
    }
    if (std::any_of(std::begin(kProfiles), std::end(kProfiles), [&](const char* k) { return keyword == k; }) &&
        a.size() >= 3 && step_trimmed(a[2]) == "$") {
      a[2] = step_reference_text(identity_2d()), changed = true;
    }
    if (keyword == "IFCADVANCEDFACE") {  // IfcFaceSurface's attributes, bounded by edge loops Assimp passes over
      warn(r, "IfcAdvancedFace", "read as an IfcFaceSurface: its edge loops (curves, not polygons) are left out", true);
      keyword = "IFCFACESURFACE", changed = true, ++out.solids;
    }
    if (keyword == "IFCSWEPTDISKSOLID" && a.size() >= 5 && (step_trimmed(a[3]) == "$" || step_trimmed(a[4]) == "$")) {
      const auto directrix = step_reference(a[0]);
      const auto corners = directrix ? polyline_points_.find(*directrix) : polyline_points_.end();
      if (corners == polyline_points_.end() || corners->second < 2)
        return left_out("its sweep has no StartParam or EndParam, and its directrix is no polyline whose range is known");
      if (step_trimmed(a[3]) == "$") a[3] = "0.";
      if (step_trimmed(a[4]) == "$") a[4] = step_real(double(corners->second - 1));
      changed = true;
    }
    if (keyword == "IFCBLOCK" || keyword == "IFCRIGHTCIRCULARCYLINDER") {
      std::optional<std::string> body = extrusion(keyword, a);
      if (!body) return left_out("its Position and dimensions are not a placement and positive numbers");
      ++out.solids;
      return finish(r.id, *body);
    }
    if (std::any_of(std::begin(kPrimitivesLeftOut), std::end(kPrimitivesLeftOut), [&](const char* n) { return upper_is(keyword, n); }))
      return left_out("Assimp reads no " + type);
    if (keyword == "IFCCSGSOLID") {
      const auto root = a.empty() ? std::nullopt : step_reference(a[0]);
      const auto found = root ? csg_operands_.find(*root) : csg_operands_.end();
      if (found == csg_operands_.end())
        return left_out("its TreeRootExpression is no boolean result, block or cylinder");
      const StepRecord& t = found->second;
      std::optional<std::string> body;
      if (t.keyword == "IFCBLOCK" || t.keyword == "IFCRIGHTCIRCULARCYLINDER") {
        body = extrusion(t.keyword, {t.attributes.begin(), t.attributes.end()});
        if (!body) return left_out("its " + title_case(t.keyword) + " " + step_reference_text(t.id) +
                                   " has no placement and positive dimensions");
      } else {  // a boolean result, as written, under this solid's id
        body = t.keyword;
        for (size_t k = 0; k < t.attributes.size(); ++k) {
          *body += k ? ',' : '(';
          *body += t.attributes[k];
        }
        *body += ')';
      }
      ++out.solids;
      return finish(r.id, *body);
    }
    if (!changed) return std::nullopt;
    std::string body = keyword;
    for (size_t k = 0; k < a.size(); ++k) {
      body += k ? ',' : '(';
      body += a[k];
    }
    return finish(r.id, body + ")");
  }

  /// An IfcBlock (Position, XLength, YLength, ZLength: a box from its placement's origin
  /// along +x, +y, +z) or IfcRightCircularCylinder (Position, Height, Radius: its base
  /// centred on the origin, up +z) as the IfcExtrudedAreaSolid that is the same solid: a
  /// rectangle (centred at half its lengths) or circle (centred at the origin) swept up its
  /// placement's z. nullopt when the dimensions are not positive numbers.
  std::optional<std::string> extrusion(const std::string& keyword, const std::vector<std::string>& a) {
    const bool block = keyword == "IFCBLOCK";
    if (a.size() < (block ? 4u : 3u) || !step_reference(a[0])) return std::nullopt;
    std::vector<double> v;
    for (size_t k = 1; k < a.size(); ++k) {
      const std::string t(step_trimmed(a[k]));
      char* end = nullptr;
      const double x = std::strtod(t.c_str(), &end);
      if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(x) || !(x > 0)) return std::nullopt;
      v.push_back(x);
    }
    if (!up_) up_ = add("IFCDIRECTION((0.,0.,1.))");
    unsigned long long profile;
    if (block) {
      const unsigned long long middle =
          add("IFCCARTESIANPOINT((" + step_real(v[0] / 2) + "," + step_real(v[1] / 2) + "))");
      const unsigned long long at = add(listing("IFCAXIS2PLACEMENT2D(", {middle}, ",$)"));
      const std::string sides = "," + std::string(step_trimmed(a[1])) + "," + std::string(step_trimmed(a[2])) + ")";
      profile = add(listing("IFCRECTANGLEPROFILEDEF(.AREA.,$,", {at}, sides.c_str()));
    } else {
      const std::string radius = "," + std::string(step_trimmed(a[2])) + ")";
      profile = add(listing("IFCCIRCLEPROFILEDEF(.AREA.,$,", {identity_2d()}, radius.c_str()));
    }
    const std::string rest = "," + std::string(step_trimmed(a[0])) + "," + step_reference_text(up_) + "," +
                             std::string(step_trimmed(a[block ? 3 : 1])) + ")";
    return listing("IFCEXTRUDEDAREASOLID(", {profile}, rest.c_str());
  }

  /// The identity IfcAxis2Placement2D, made once for every profile that needs one.
  unsigned long long identity_2d() {
    if (!placement_2d_) {
      const unsigned long long origin = add("IFCCARTESIANPOINT((0.,0.))");
      placement_2d_ = add(listing("IFCAXIS2PLACEMENT2D(", {origin}, ",$)"));
    }
    return placement_2d_;
  }

  /// A new record with the next free id; returns the id.
  unsigned long long add(const std::string& body) {
    std::string rec = step_reference_text(++next_id_);
    rec += '=';
    rec += body;
    records_.push_back(std::move(rec));
    return next_id_;
  }

  /// The face set's own record, then the new ones.
  std::string finish(unsigned long long id, const std::string& body) {
    std::string s = step_reference_text(id);
    s += '=';
    s += body;
    for (const std::string& rec : records_) {
      s += ";\n";
      s += rec;
    }
    return s;
  }

  /// The points of list `id` (each "(x,y,z)", or "(x,y)" in a 2D list, as written), read
  /// once; nullptr when it is not a list of points of `dimension` coordinates.
  const std::vector<std::string_view>* points_of(unsigned long long id, std::string_view coords, size_t dimension = 3) {
    auto [it, fresh] = points_.try_emplace(id);
    if (fresh) {
      auto items = step_list(coords);
      bool ok = items.has_value();
      for (size_t k = 0; ok && k < items->size(); ++k) {
        const auto xyz = coordinates((*items)[k]);
        ok = xyz && xyz->size() == dimension;
      }
      it->second = ok ? std::move(items) : std::nullopt;
    }
    return it->second ? &*it->second : nullptr;
  }

  /// IfcIndexedPolyCurve(Points, Segments, SelfIntersect) as an IfcPolyline: its points in
  /// order (Segments $), or segment by segment, IfcLineIndex's points as they are and each
  /// IfcArcIndex (start, a point on it, end) as points along the circle (arc_between).
  /// Unusable: an empty IfcPolyline's stand-in, said (the profile it bounds is then empty).
  std::string polyline(const StepRecord& r) {
    records_.clear();
    const char* type = "IfcIndexedPolyCurve";
    std::vector<unsigned long long> corners;
    auto made = [&]() {
      polyline_points_[r.id] = corners.size();
      return finish(r.id, listing("IFCPOLYLINE((", corners, "))"));
    };
    auto give_up = [&](const std::string& why) {
      warn(r, type, why + ": the curve is left out", true);
      records_.clear();
      corners.clear();
      for (int k = 0; k < 2; ++k) corners.push_back(add("IFCCARTESIANPOINT((0.,0.))"));
      return made();
    };
    const std::vector<std::string_view>& a = r.attributes;
    if (a.empty()) return give_up("it has no Points");
    const auto list = step_reference(a[0]);
    const auto found = list ? point_lists_.find(*list) : point_lists_.end();
    if (found == point_lists_.end()) return give_up("its Points are no IfcCartesianPointList2D or 3D");
    const std::vector<std::string_view>* points = points_of(*list, found->second, point_dimension_[*list]);
    if (!points || points->empty()) return give_up("its point list " + step_reference_text(*list) + " is not a list of points");
    std::vector<size_t> order;  // indices into the list; arcs' own points as ~index into `computed`
    std::vector<std::vector<double>> computed;
    auto push = [&](size_t i) {
      if (order.empty() || order.back() != i) order.push_back(i);
    };
    auto in_range = [&](long long i) { return i >= 1 && size_t(i) <= points->size(); };
    if (a.size() < 2 || step_trimmed(a[1]) == "$") {
      for (size_t i = 0; i < points->size(); ++i) push(i);
    } else {
      const auto segments = step_list(a[1]);
      if (!segments) return give_up("its Segments are not a list");
      for (std::string_view seg : *segments) {
        const bool arc = seg.starts_with("IFCARCINDEX");
        if (!arc && !seg.starts_with("IFCLINEINDEX")) return give_up("a segment is neither IfcLineIndex nor IfcArcIndex");
        // A typed value: IFCLINEINDEX((1,2,3)), its one argument the list.
        const auto typed = step_list(seg.substr(std::min(seg.find('('), seg.size())));
        const auto idx = typed && typed->size() == 1 ? integers((*typed)[0]) : std::nullopt;
        if (!idx || idx->size() < 2 || (arc && idx->size() != 3) || !std::all_of(idx->begin(), idx->end(), in_range))
          return give_up("a segment names a point its list does not have");
        if (!arc) {
          for (long long i : *idx) push(size_t(i - 1));
          continue;
        }
        const auto p0 = coordinates((*points)[size_t((*idx)[0] - 1)]), p1 = coordinates((*points)[size_t((*idx)[1] - 1)]),
                   p2 = coordinates((*points)[size_t((*idx)[2] - 1)]);
        push(size_t((*idx)[0] - 1));
        if (arc_points_ > kMostArcPoints) {  // a file of millions of arcs: the rest straight, said once
          if (!arcs_cut_) warn(r, type, "more arcs than Avenues makes points for (" + std::to_string(kMostArcPoints) +
                                            "): this and later arcs are straight");
          arcs_cut_ = true;
        } else {
          arc_points_ += 72;
        }
        for (std::vector<double>& p : arcs_cut_ ? std::vector<std::vector<double>>{} : arc_between(*p0, *p1, *p2)) {
          computed.push_back(std::move(p));
          order.push_back(~(computed.size() - 1));
        }
        push(size_t((*idx)[2] - 1));
      }
    }
    if (order.size() < 2) return give_up("it has fewer than two points");
    std::unordered_map<size_t, unsigned long long> point_id;
    for (size_t i : order) {
      if (i > points->size()) {  // an arc's own point
        const std::vector<double>& p = computed[~i];
        std::string xyz = "IFCCARTESIANPOINT((";
        for (size_t k = 0; k < p.size(); ++k) xyz += (k ? "," : "") + step_real(p[k]);
        corners.push_back(add(xyz + "))"));
        continue;
      }
      auto [it, fresh] = point_id.try_emplace(i, 0);
      if (fresh) it->second = add("IFCCARTESIANPOINT(" + std::string((*points)[i]) + ")");
      corners.push_back(it->second);
    }
    return made();
  }

  /// Says what happened to record r; `whole` when its geometry is left out altogether.
  void warn(const StepRecord& r, const char* type, const std::string& what, bool whole = false) {
    left_out_count_ += whole;
    if (warnings_.size() >= kWarningsListed) {
      ++unlisted_;
      return;
    }
    const size_t line = 1 + size_t(std::count(text_.begin(), text_.begin() + std::ptrdiff_t(r.offset), '\n'));
    warnings_.push_back("line " + std::to_string(line) + ", " + step_reference_text(r.id) + " (" + type + "): " + what);
    if (whole) left_out_.push_back(warnings_.back());
  }

  /// Arcs' points made for the whole file, at most (72 for each arc): far beyond any
  /// building's curves, short of what a file of nothing but arcs could make memory hold.
  static constexpr size_t kMostArcPoints = 4'000'000;
  size_t arc_points_ = 0;
  bool arcs_cut_ = false;

  std::string_view text_;
  unsigned long long max_id_ = 0, next_id_ = 0;
  unsigned long long owner_ = 0, placement_ = 0, placement_2d_ = 0;  ///< made once, for all that lack them
  unsigned long long up_ = 0;  ///< IfcDirection (0, 0, 1), made once for the primitives' extrusions
  std::unordered_map<unsigned long long, StepRecord> csg_operands_;  ///< blocks, cylinders, boolean results by id
  std::unordered_map<unsigned long long, size_t> polyline_points_;  ///< IfcPolyline (also rewritten ones) -> its points
  std::unordered_map<unsigned long long, std::string_view> point_lists_;  ///< id -> its CoordList attribute
  std::unordered_map<unsigned long long, size_t> point_dimension_;       ///< id -> 2 or 3
  std::unordered_map<unsigned long long, std::vector<std::string_view>> indexed_faces_;
  std::unordered_map<unsigned long long, std::optional<std::vector<std::string_view>>> points_;
  std::vector<std::string> records_;  ///< the new records of the set being rewritten
  std::vector<std::string> warnings_;
  std::vector<std::string> left_out_;  ///< the listed warnings of records left out whole
  size_t unlisted_ = 0, left_out_count_ = 0;
};

}  // namespace

std::optional<Ifc4Rewrite> ifc4_for_assimp(std::string_view step_text) {
  return Rewriter(step_text).run();
}

}  // namespace avenues
