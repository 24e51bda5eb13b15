// Tests of the walkthrough's controls and of script replay, without a window
// (app/controls.h, app/script.h): what a person's keys, mouse and gamepad ask of the eye.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <GLFW/glfw3.h>

#include "app/controls.h"
#include "app/script.h"

namespace avenues::app {
namespace {

TEST(Controls, HeldKeyWalksAtWalkingSpeedAndShiftRuns) {
  ControlRates rates;
  Controls c(rates);
  c.key(key_code("W"), true);
  EXPECT_TRUE(c.active());
  Motion m = c.motion(0.5);
  EXPECT_DOUBLE_EQ(m.forward, rates.walk_speed * 0.5);
  EXPECT_DOUBLE_EQ(m.strafe, 0);
  c.key(key_code("LEFT_SHIFT"), true);
  m = c.motion(0.5);
  EXPECT_DOUBLE_EQ(m.forward, rates.walk_speed * rates.run_factor * 0.5);
  c.key(key_code("W"), false);
  c.key(key_code("LEFT_SHIFT"), false);
  EXPECT_FALSE(c.active());
  EXPECT_DOUBLE_EQ(c.motion(0.5).forward, 0);
}

TEST(Controls, OpposedKeysCancelAndFocusLossReleasesAll) {
  Controls c;
  c.key(key_code("W"), true);
  c.key(key_code("S"), true);
  EXPECT_DOUBLE_EQ(c.motion(1).forward, 0);
  c.release_all();
  c.key(key_code("S"), false);  // a release after focus loss is harmless
  EXPECT_FALSE(c.active());
}

TEST(Controls, ACommandIsTakenOncePerPressNotPerRepeat) {
  Controls c;
  c.key(key_code("F"), true);
  c.key(key_code("F"), true);  // auto-repeat: still held, no second press
  c.key(key_code("F"), false);
  const std::vector<Action> taken = c.take_commands();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0], Action::ToggleFly);
  EXPECT_TRUE(c.take_commands().empty());
}

TEST(Controls, SenseSwitchesLatchAndMoveAlongWorldAxes) {
  ControlRates rates;
  Controls c(rates);
  c.key(key_code("1"), true);
  c.key(key_code("1"), false);
  const std::vector<Action> taken = c.take_commands();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0], Action::Switch1);
  c.flip_switch(0);  // what the walkthrough does with Switch1
  c.flip_switch(6);  // scale+
  EXPECT_EQ(c.switches_on(), "x+ scale+");
  EXPECT_TRUE(c.active());  // a latched switch keeps moving the eye with no key held
  const Motion m = c.motion(2);
  EXPECT_DOUBLE_EQ(m.world_x, rates.sense_speed * 2);
  EXPECT_DOUBLE_EQ(m.world_y, 0);
  EXPECT_NEAR(m.zoom, std::pow(rates.scale_rate, 2), 1e-12);
  c.switches_off();
  EXPECT_EQ(c.switches_on(), "");
  EXPECT_FALSE(c.active());
}

TEST(Controls, MouseLookIsConsumedByOneFrame) {
  ControlRates rates;
  Controls c(rates);
  c.look(100, -20);
  Motion m = c.motion(1.0 / 60);
  EXPECT_DOUBLE_EQ(m.turn, -100 * rates.mouse_deg_per_px);
  EXPECT_DOUBLE_EQ(m.pitch, 20 * rates.mouse_deg_per_px);
  m = c.motion(1.0 / 60);
  EXPECT_DOUBLE_EQ(m.turn, 0);
}

TEST(Controls, GamepadStickWalksInsideItsDeadZoneNot) {
  Controls c;
  GamepadState pad;
  pad.present = true;
  pad.axes[GLFW_GAMEPAD_AXIS_LEFT_TRIGGER] = pad.axes[GLFW_GAMEPAD_AXIS_RIGHT_TRIGGER] = -1;
  pad.axes[GLFW_GAMEPAD_AXIS_LEFT_Y] = -0.1f;  // inside the dead zone
  c.gamepad(pad);
  EXPECT_DOUBLE_EQ(c.motion(1).forward, 0);
  pad.axes[GLFW_GAMEPAD_AXIS_LEFT_Y] = -1;  // full forward
  c.gamepad(pad);
  EXPECT_GT(c.motion(1).forward, 0);
  pad.buttons[GLFW_GAMEPAD_BUTTON_A] = 1;
  c.gamepad(pad);
  c.gamepad(pad);  // still held: one press
  const std::vector<Action> taken = c.take_commands();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0], Action::ToggleFly);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(ScriptPlayer, ReplaysKeysIntoTheControlsFrameByFrame) {
  const std::string path = write_temp("avenues-controls-test.script",
                                      "# walk for two frames, then look, then quit\n"
                                      "0 down W\n"
                                      "2 up W\n"
                                      "2 look 10 0\n"
                                      "3 resize 320 200\n"
                                      "3 screenshot a.png\n"
                                      "3 pose\n"
                                      "4 quit\n");
  ScriptPlayer player(read_script(path));
  Controls c;
  EXPECT_FALSE(player.empty());
  ScriptPlayer::Requests r = player.play(0, c);
  EXPECT_GT(c.motion(0.1).forward, 0);
  EXPECT_FALSE(r.quit);
  r = player.play(1, c);
  EXPECT_GT(c.motion(0.1).forward, 0);  // still held
  r = player.play(2, c);
  const Motion m = c.motion(0.1);
  EXPECT_DOUBLE_EQ(m.forward, 0);
  EXPECT_LT(m.turn, 0);  // looked right
  r = player.play(3, c);
  ASSERT_EQ(r.resizes.size(), 1u);
  EXPECT_EQ(r.resizes[0], std::make_pair(320, 200));
  ASSERT_EQ(r.screenshots.size(), 1u);
  EXPECT_EQ(r.screenshots[0], "a.png");
  EXPECT_EQ(r.poses, 1);
  EXPECT_FALSE(r.quit);
  EXPECT_TRUE(player.play(4, c).quit);
  std::filesystem::remove(path);
}

TEST(ScriptPlayer, AScriptedPadStandsInForARealOne) {
  const std::string path = write_temp("avenues-pad-test.script", "0 pad LEFT_Y -1\n1 pad A 1\n");
  ScriptPlayer player(read_script(path));
  Controls c;
  EXPECT_FALSE(player.pad().present);
  EXPECT_FLOAT_EQ(player.pad().axes[GLFW_GAMEPAD_AXIS_LEFT_TRIGGER], -1);  // triggers rest at -1
  player.play(0, c);
  ASSERT_TRUE(player.pad().present);
  c.gamepad(player.pad());
  EXPECT_GT(c.motion(1).forward, 0);
  player.play(1, c);
  c.gamepad(player.pad());
  const std::vector<Action> taken = c.take_commands();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0], Action::ToggleFly);
  std::filesystem::remove(path);
}

TEST(ScriptPlayer, ARandomScriptReplaysWithoutAWindow) {
  const std::string path = write_temp("avenues-random-test.script", random_script(7, 600));
  ScriptPlayer player(read_script(path));
  Controls c;
  for (long f = 0; f < 600; ++f) {
    const ScriptPlayer::Requests r = player.play(f, c);
    EXPECT_FALSE(r.quit);
    EXPECT_TRUE(r.screenshots.empty());  // random scripts export nothing
    c.gamepad(player.pad());
    c.take_commands();
    const Motion m = c.motion(1.0 / 60);
    EXPECT_TRUE(std::isfinite(m.forward) && std::isfinite(m.turn) && std::isfinite(m.zoom) && m.zoom > 0);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace avenues::app
