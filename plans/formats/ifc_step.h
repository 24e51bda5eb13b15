// Avenues — what Assimp's IFC nodes do not carry, read straight from the STEP text.
//
// Assimp names each node "IfcType_Name_GlobalId" (with the Name's spaces dropped by its
// STEP reader) and keeps the element's property sets, but not the attributes of
// IfcSpatialStructureElement: an IfcSpace's LongName ("Foyer", where its Name is "A101")
// is lost. This reads the names from the STEP physical file (ISO 10303-21) itself: the
// records "#id=IFCSPACE('GlobalId',#owner,'Name',...,'LongName',...);", the Name being
// every IfcRoot's third attribute, the LongName a spatial element's eighth, in IFC2X3
// and IFC4 alike. Strings are decoded as ISO 10303-21 says
// ('' a quote, \\ a backslash, \S\c, \X\hh, \X2\...\X0\ and \X4\...\X0\) into UTF-8.
// Strict and small: a record it cannot read is skipped, never half-read.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avenues {

/// What the file itself names an IfcRoot entity: its Name ("Basic Wall:Interior - Partition
/// (92mm Stud)", spaces kept, where Assimp's node names drop them) and, for a spatial
/// structure element (IfcSpace, IfcBuildingStorey, IfcBuilding, IfcSite), its LongName
/// ("Foyer"); empty where the file has none ($).
struct IfcRootNames {
  std::string name, long_name;  ///< UTF-8
};

/// GlobalId -> names of every IfcRoot entity in the STEP text that has a Name or a LongName.
std::map<std::string, IfcRootNames> ifc_root_names(std::string_view step_text);

/// What makes a STEP file's DATA section unsafe to hand to Assimp 5.2, whose STEP reader
/// dereferences what it could not read (it crashes on a reference to a missing record):
/// a record that is not "#id=KEYWORD(...)" (or a complex "#id=(...)"), an id defined
/// twice, a reference "#n" to an id no record defines. `offset` is where in the text.
struct StepProblem {
  size_t offset = 0;
  std::string what;
};
std::optional<StepProblem> step_data_problem(std::string_view step_text);

/// One instance record of a STEP file, "#id=KEYWORD(attribute,...);".
struct StepRecord {
  unsigned long long id = 0;
  size_t offset = 0, size = 0;               ///< the record in the text, from its '#' to before its ';'
  std::string keyword;                       ///< upper case
  std::vector<std::string_view> attributes;  ///< top level, as written (views into the text)
};

/// Calls f for every instance record of the text, in order. Complex instances
/// ("#id=(A(...)B(...));"), header lines and records it cannot read are passed over.
void for_each_step_record(std::string_view step_text, const std::function<void(const StepRecord&)>& f);

/// An attribute without the white space around it (as a record's attributes are written).
std::string_view step_trimmed(std::string_view attribute);

/// The items of a STEP aggregate attribute "(a,b,(c,d))", as written, white space around
/// them trimmed; nullopt when the attribute is not one aggregate.
std::optional<std::vector<std::string_view>> step_list(std::string_view attribute);

/// The id of a reference attribute "#12"; nullopt for anything else.
std::optional<unsigned long long> step_reference(std::string_view attribute);

/// A reference to record `id` as STEP writes it: "#12".
std::string step_reference_text(unsigned long long id);

/// A STEP string's body (between its quotes, quotes still doubled) decoded to UTF-8;
/// `ok` is set false (and the result is not to be used) for a malformed escape.
std::string decode_step_string(std::string_view body, bool& ok);

}  // namespace avenues
