// Avenues — what a DXF drawing's layer (or block) name says it holds: walls, doors or
// windows, by the names drawings use (AIA/ISO 13567 and the words of the languages plans
// are drawn in).
#pragma once

#include <string>

namespace avenues {

enum class LayerRole { None, Walls, Doors, Windows };

/// A name folded for comparing: lower case in ASCII, Latin-1, Latin Extended-A and
/// Cyrillic (UTF-8), with DXF's \U+XXXX escapes (R2000 and older) decoded first.
std::string fold_layer_name(const std::string& name);

/// The role a layer's name gives it, or None:
///  * AIA (A-WALL, A-DOOR, A-GLAZ) and the words of English, German, French, Spanish,
///    Italian, Portuguese, Dutch, the Nordic and Slavic languages, Turkish, Chinese and
///    Japanese for walls, partitions, doors and windows;
///  * a name for joinery (doors and windows together: menuiserie, carpintería, infissi,
///    kozijnen, 门窗, or both words) is a door layer: its swings place doors, its straight
///    lines close the walls;
///  * furniture, text, dimensions, grids, hatch layers named "hatch-", and AIA's
///    modifiers for what is not a wall in plan (IDEN tags, DEMO, ABOV, OVHD, ELEV, NPLT,
///    NOTE, SYMB) are None, whatever else the name says.
LayerRole layer_role_by_name(const std::string& name);

/// Whether a layer's name says it holds no part of the building in plan: the names
/// layer_role_by_name reads as None whatever else they say (furniture, text, dimensions,
/// grids, AIA's IDEN, DEMO, NOTE ...), and AutoCAD's Defpoints.
bool names_no_building(const std::string& name);

/// Whether a name speaks of doors or windows, whatever its role (A-DOOR-IDEN's door
/// numbers are no room names).
bool names_openings(const std::string& name);

/// Whether a block's name says it is a window (and not a door: a glazed door is a door).
bool names_a_window(const std::string& name);

/// Whether a block's name says it is a door (a door, a sliding, pocket or folding one).
bool names_a_door(const std::string& name);

/// Whether a drawing's title names a storey ("GROUND FLOOR PLAN", "1. Obergeschoss",
/// "Rez-de-chaussée", "Planta baja", "Level 2" ...): a drawing whose titles name two is
/// one of storeys drawn side by side.
bool names_a_storey(const std::string& text);

}  // namespace avenues
