// Avenues — a Sweet Home 3D home as both of its entries describe it, before it is a Plan.
//
// A .sh3d holds a home as Home.xml (Sweet Home 3D 5.3 and later), as a serialized Java
// `Home` object (every version; the only entry before 5.3), or both. Both readers fill
// this one tree, in Home.xml's vocabulary (HomeXMLHandler's element and attribute names:
// <level id elevation floorThickness height elevationIndex>, <wall id level wallAtStart
// wallAtEnd xStart yStart xEnd yEnd thickness height heightAtEnd arcExtent leftSideColor
// rightSideColor>, <room level name><point x y/>…, <pieceOfFurniture>, <doorOrWindow>,
// <light power><lightSource x y z color diameter/>…, <furnitureGroup>…, <observerCamera
// attribute="observerCamera" x y z yaw pitch fieldOfView>), so that one builder
// (sweet_home.cpp) turns either into a Plan the same way. Numbers are kept as the text
// Home.xml would hold (a Java float as its shortest round-trip decimal).
//
// The tree is flat (children are indices), so that neither building it nor destroying
// it recurses over the input's nesting.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace avenues {

struct HomeElement {
  std::string kind;  ///< "home", "level", "wall", "room", "point", "pieceOfFurniture", ...
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<size_t> children;  ///< indices into HomeTree::elements, in order
  int line = 0, column = 0;      ///< where it starts in Home.xml (1-based; 0 when not from XML)
  size_t offset = 0;             ///< where its object starts in the serialized Home entry

  /// The attribute's text; nullptr when the element has no such attribute.
  const std::string* attribute(std::string_view name) const {
    for (const auto& [k, v] : attributes)
      if (k == name) return &v;
    return nullptr;
  }
  /// The attribute's text, "" when absent.
  std::string text(std::string_view name) const {
    const std::string* v = attribute(name);
    return v ? *v : std::string();
  }
  void set(std::string name, std::string value) { attributes.emplace_back(std::move(name), std::move(value)); }
};

struct HomeTree {
  std::string file;  ///< named in messages: "home.sh3d:Home.xml", "home.sh3d:Home", "Home.xml"
  bool serialized = false;
  std::vector<HomeElement> elements;  ///< elements[0] is the <home>

  const HomeElement& root() const { return elements.front(); }
  /// The element's children of one kind, in order.
  std::vector<const HomeElement*> children(const HomeElement& e, std::string_view kind) const {
    std::vector<const HomeElement*> out;
    for (size_t c : e.children)
      if (elements[c].kind == kind) out.push_back(&elements[c]);
    return out;
  }
  /// Appends an element as the last child of parent (or as the root when the tree is
  /// empty); returns its index.
  size_t add(size_t parent, std::string kind) {
    elements.emplace_back();
    elements.back().kind = std::move(kind);
    const size_t i = elements.size() - 1;
    if (i > 0) elements[parent].children.push_back(i);
    return i;
  }
};

/// The serialized Java `Home` entry of a .sh3d (bytes of the entry; file names it in
/// messages) as a home tree. Throws PlanError naming the file and the byte offset.
HomeTree home_tree_of_serialized(std::string_view bytes, const std::string& file);

}  // namespace avenues
