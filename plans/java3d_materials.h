// Avenues — Java 3D's built-in OBJ materials, which Sweet Home 3D's OBJ loader knows by name.
//
// Java 3D's ObjectFile loader (com.sun.j3d.loaders.objectfile.DefaultMaterials) defines about
// 130 named materials, `white`, `flblonde`, `archwhite`, `default`, ..., and Sweet Home 3D's
// OBJLoader starts every model's material table from them before its own MTL libraries add
// to it (a library's definition of a name wins). Many models of Sweet Home's catalogue, and
// of homes made with it, use these names with no MTL file at all. Only the diffuse colour
// (Kd) is kept here: Avenues draws a material by its colour alone.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace avenues {

/// The diffuse colour Kd of Java 3D's built-in material `name` as written in its table
/// (sRGB-encoded, as every MTL Kd is read: plans/obj_materials.h); nullopt when Java 3D
/// defines no material of that name. Names are matched exactly (Java 3D's are lower case).
std::optional<std::array<double, 3>> java3d_material_colour(std::string_view name);

}  // namespace avenues
