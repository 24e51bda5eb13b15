// Tests of ObjectsByCell (render/scene_objects.h): each cell's placed objects, in their
// order, found once for many pictures; and a walk's FrameStorage, which keeps them, makes
// them again when handed other objects.
#include <gtest/gtest.h>

#include <vector>

#include "cells/build_cells.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

std::vector<uint32_t> list(std::span<const uint32_t> s) { return {s.begin(), s.end()}; }

PlacedObject in_cell(CellId c) {
  PlacedObject o;
  o.cell = c;
  if (c != kNoCell) o.cells = {{c, true}};
  return o;
}

}  // namespace

// Objects in cells 2, 0, 2, none, 7 (of 3 cells), 0: each cell's in their order; none
// for an object in no cell or in a cell out of range, and none for such a cell.
TEST(ObjectsByCell, EachCellsObjectsInTheirOrder) {
  const std::vector<PlacedObject> objects{in_cell(2), in_cell(0), in_cell(2), in_cell(kNoCell), in_cell(7), in_cell(0)};
  const ObjectsByCell by = objects_by_cell(3, objects);
  EXPECT_EQ(list(by.of(0)), (std::vector<uint32_t>{1, 5}));
  EXPECT_TRUE(by.of(1).empty());
  EXPECT_EQ(list(by.of(2)), (std::vector<uint32_t>{0, 2}));
  EXPECT_TRUE(by.of(kNoCell).empty());
  EXPECT_TRUE(by.of(3).empty());
  EXPECT_TRUE(by.of(7).empty());
  EXPECT_TRUE(objects_by_cell(0, objects).of(0).empty());
  EXPECT_TRUE(objects_by_cell(3, {}).of(2).empty());
}

// An object meeting several cells is listed in each, marked where it reaches beyond that
// cell and must be cut to it (ObjectsByCell::kCut); an object wholly in a cell is not.
TEST(ObjectsByCell, AnObjectMeetingSeveralCellsIsInEachMarkedWhereItReachesBeyond) {
  PlacedObject across = in_cell(0);
  across.cells = {{0, false}, {1, false}, {2, true}};
  const std::vector<PlacedObject> objects{in_cell(1), across, in_cell(2)};
  const ObjectsByCell by = objects_by_cell(3, objects);
  EXPECT_EQ(list(by.of(0)), (std::vector<uint32_t>{1 | ObjectsByCell::kCut}));
  EXPECT_EQ(list(by.of(1)), (std::vector<uint32_t>{0, 1 | ObjectsByCell::kCut}));
  EXPECT_EQ(list(by.of(2)), (std::vector<uint32_t>{1, 2}));
}

// One FrameStorage renders the furnished room with its furniture, then without any, then
// with it again: each picture is the one a fresh render makes (the storage's objects by
// cell made for the objects it is handed, not kept from the picture before).
TEST(ObjectsByCell, AFrameStorageHandedOtherObjectsDrawsThem) {
  const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/furnished-room.toml"));
  const std::vector<PlacedObject> furniture = place_objects(c), none;
  ASSERT_FALSE(furniture.empty());
  const Viewpoint vp = default_viewpoint(c);
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 200, 120);
  const VisibleSet visible = find_visible(c, cam, c.locate(vp.eye).cell);
  HalftoneOptions o;
  o.threads = 1;
  FrameStorage storage;
  for (const std::vector<PlacedObject>* objects : {&furniture, &none, &furniture}) {
    Image kept, fresh;
    render_view(c, *objects, cam, visible, o, fresh);
    const SceneEffects effects = prepare_effects(c, *objects, o);
    render_view(c, *objects, effects, cam, visible, o, kept, storage);
    EXPECT_EQ(kept.data, fresh.data) << (objects == &none ? "without furniture" : "with furniture");
  }
  Image with, without;
  render_view(c, furniture, cam, visible, o, with);
  render_view(c, none, cam, visible, o, without);
  EXPECT_NE(with.data, without.data) << "the furniture shows in this view";
}
