// Framework tests of replay files (physlab/replay.hpp): a hand-made replay survives a write and a
// read field for field, the file's size is the documented formula, a truncated or foreign file is
// refused naming the byte, and recording a World gives its states. They grade nothing (the code
// lives in common/), so they carry [common].
#include <cstdio>
#include <string>

#include "impulse_support.hpp"
#include "physlab/error.hpp"
#include "physlab/replay.hpp"

using namespace physlab;

namespace {

// A replay with every kind of field: a box, a fixed plane, a tetrahedron, two particles and a
// spring, two frames, the second with a contact. Its numbers are exact in float32.
Replay handMadeReplay() {
  Replay replay;
  replay.title = "hand made";
  replay.settings = "method=sequential iterations=50";
  ReplayBody box;
  box.kind = ReplayShapeKind::Box;
  box.size = {0.5f, 0.25f, 0.125f, 0.0f};
  ReplayBody ground;
  ground.kind = ReplayShapeKind::Plane;
  ground.fixed = true;
  ground.size = {0.0f, 0.0f, 1.0f, 0.0f};
  ReplayBody tetrahedron;
  tetrahedron.kind = ReplayShapeKind::Convex;
  tetrahedron.vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  tetrahedron.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  replay.bodies = {box, ground, tetrahedron};
  replay.particle_count = 2;
  replay.springs = {0, 1};
  for (int f = 0; f < 2; ++f) {
    ReplayFrame frame;
    frame.time = 0.25f * static_cast<float>(f);
    frame.kinetic_energy = 1.5f + static_cast<float>(f);
    frame.potential_energy = -2.0f;
    frame.iterations = 7u + static_cast<std::uint32_t>(f);
    for (int k = 0; k < 21; ++k) frame.poses.push_back(0.125f * static_cast<float>(k + f));
    frame.particles = {1, 2, 3, 4, 5, 6.5f};
    if (f == 1) {
      ReplayContact c;
      c.a = 0;
      c.b = 1;
      c.p = {0.5f, -0.25f, 0.0f};
      c.n = {0.0f, 0.0f, 1.0f};
      c.depth = 0.001953125f;
      c.j = 3.75f;
      frame.contacts.push_back(c);
    }
    replay.frames.push_back(frame);
  }
  return replay;
}

// The InvalidInput message of decoding `bytes` ("" when it decodes).
std::string replayRefusal(const std::string& bytes) {
  try {
    decodeReplay(bytes, "test.replay");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("replay: a hand-made replay survives a write and a read, every field equal", "[common]") {
  const Replay original = handMadeReplay();
  const std::string path = "physlab_test_replay_round_trip.replay";
  writeReplay(original, path);
  const Replay back = readReplay(path);
  std::remove(path.c_str());
  // Every number of handMadeReplay() is a float32 already: the round trip must be exact
  CHECK(back.title == original.title);
  CHECK(back.settings == original.settings);
  CHECK(back.particle_count == original.particle_count);
  CHECK(back.springs == original.springs);
  REQUIRE(back.bodies.size() == original.bodies.size());
  for (std::size_t i = 0; i < back.bodies.size(); ++i) {
    CHECK(back.bodies[i].kind == original.bodies[i].kind);
    CHECK(back.bodies[i].fixed == original.bodies[i].fixed);
    CHECK(back.bodies[i].size == original.bodies[i].size);
    CHECK(back.bodies[i].vertices == original.bodies[i].vertices);
    CHECK(back.bodies[i].triangles == original.bodies[i].triangles);
  }
  REQUIRE(back.frames.size() == original.frames.size());
  for (std::size_t f = 0; f < back.frames.size(); ++f) {
    const ReplayFrame &a = back.frames[f], &b = original.frames[f];
    CHECK(a.time == b.time);
    CHECK(a.kinetic_energy == b.kinetic_energy);
    CHECK(a.potential_energy == b.potential_energy);
    CHECK(a.iterations == b.iterations);
    CHECK(a.poses == b.poses);
    CHECK(a.particles == b.particles);
    REQUIRE(a.contacts.size() == b.contacts.size());
    for (std::size_t k = 0; k < a.contacts.size(); ++k) {
      CHECK(a.contacts[k].a == b.contacts[k].a);
      CHECK(a.contacts[k].b == b.contacts[k].b);
      CHECK(a.contacts[k].p == b.contacts[k].p);
      CHECK(a.contacts[k].n == b.contacts[k].n);
      CHECK(a.contacts[k].depth == b.contacts[k].depth);
      CHECK(a.contacts[k].j == b.contacts[k].j);
    }
  }
}

TEST_CASE("replay: the file's size is header + shapes + springs + frames, exactly", "[common]") {
  const Replay replay = handMadeReplay();
  // Header 40 + title 9 + settings 31; box and plane 32 each, the tetrahedron 32 + 12 x 4 + 12 x 4;
  // one spring 8; frames 24 + 28 x 3 + 12 x 2 (+ 40 for the second's contact)
  const std::size_t expected = (40 + 9 + 31) + (32 + 32 + (32 + 48 + 48)) + 8 + (132 + 172);
  CHECK(replayHeaderBytes(replay) == 80);
  CHECK(replayFrameBytes(3, 2, 0) == 132);
  CHECK(replayFrameBytes(3, 2, 1) == 172);
  CHECK(encodeReplay(replay).size() == expected);
}

TEST_CASE("replay: thinReplay keeps the first and last frames and fits the bytes asked for", "[common]") {
  Replay replay = handMadeReplay();
  const ReplayFrame last = replay.frames.back();
  replay.frames.insert(replay.frames.end() - 1, 4, replay.frames.front());  // 6 frames, contacts on the last
  for (std::size_t f = 0; f < replay.frames.size(); ++f) replay.frames[f].time = 0.25f * static_cast<float>(f);
  const std::size_t whole = encodeReplay(replay).size();
  CHECK(encodeReplay(thinReplay(replay, whole)) == encodeReplay(replay));
  // 40 bytes short: the last frame's contact goes first (every second kept frame's contacts)
  const Replay no_contact = thinReplay(replay, whole - 40);
  REQUIRE(no_contact.frames.size() == 6);
  CHECK(no_contact.frames.back().contacts.empty());
  CHECK_FALSE(no_contact.frames.back().contacts_recorded);
  // A frame short: every second frame (0, 2, 4) and the last, times kept
  const Replay halved = thinReplay(replay, whole - 132);
  REQUIRE(halved.frames.size() == 4);
  CHECK(halved.frames[1].time == 0.5f);
  CHECK(halved.frames.back().time == 1.25f);
  CHECK(halved.frames.back().contacts.size() == last.contacts.size());
  CHECK(encodeReplay(halved).size() <= whole - 132);
  // Nothing fits: the first and last frames, the last's contacts left out
  const Replay smallest = thinReplay(replay, 0);
  REQUIRE(smallest.frames.size() == 2);
  CHECK(smallest.frames.back().contacts.empty());
}

TEST_CASE("replay: a truncated file is refused naming the byte where it ends", "[common]") {
  const std::string bytes = encodeReplay(handMadeReplay());
  REQUIRE(replayRefusal(bytes).empty());
  // Cuts in the version, the counts, the title, a body, the first frame's counts, and the second
  // frame's contact
  for (std::size_t cut : {std::size_t{15}, std::size_t{20}, std::size_t{45}, std::size_t{100}, std::size_t{290},
                          std::size_t{330}, bytes.size() - 1}) {
    const std::string message = replayRefusal(bytes.substr(0, cut));
    INFO("cut at byte " << cut << ": " << message);
    CHECK(message.find("truncated at byte " + std::to_string(cut)) != std::string::npos);
    CHECK(message.find("test.replay") != std::string::npos);
  }
  CHECK(replayRefusal(bytes.substr(0, 560)).find("frame 1's 1 contacts") != std::string::npos);
  CHECK(replayRefusal(bytes + "x").find("1 bytes after the last frame, at byte " + std::to_string(bytes.size())) !=
        std::string::npos);
}

TEST_CASE("replay: a wrong magic or an unknown version is refused, naming it", "[common]") {
  std::string bytes = encodeReplay(handMadeReplay());
  std::string foreign = bytes;
  foreign[0] = 'Q';
  CHECK(replayRefusal(foreign).find("not a PhysLab replay") != std::string::npos);
  CHECK(replayRefusal("").find("not a PhysLab replay") != std::string::npos);
  bytes[14] = 4;  // version 4, little-endian
  CHECK(replayRefusal(bytes).find("version 4 at byte 14 is not one this reader knows (1-3)") != std::string::npos);
  bytes[14] = 0;
  CHECK(replayRefusal(bytes).find("version 0 at byte 14") != std::string::npos);
  CHECK_THROWS_AS(readReplay("physlab_no_such_file.replay"), InvalidInput);
}

TEST_CASE("replay: a frame without its contacts survives a round trip; version 1 files still read", "[common]") {
  Replay replay = handMadeReplay();
  replay.frames[0].contacts_recorded = false;
  const Replay back = decodeReplay(encodeReplay(replay), "test.replay");
  CHECK_FALSE(back.frames[0].contacts_recorded);
  CHECK(back.frames[1].contacts_recorded);
  CHECK(back.frames[1].contacts.size() == 1);
  // A frame that says its contacts were left out but holds some is refused on both sides
  replay.frames[1].contacts_recorded = false;
  try {
    encodeReplay(replay);
    FAIL("a frame holding contacts it says were not recorded was written");
  } catch (const InvalidInput& e) {
    CHECK(std::string(e.what()).find("frame 1 holds contacts but says they were not recorded") != std::string::npos);
  }
  std::string bytes = encodeReplay(handMadeReplay());
  bytes[412 + 20] = 0;  // frame 1 (from byte 412): flags cleared, its contact count still 1
  CHECK(replayRefusal(bytes).find("frame 1 holds 1 contacts but says they were not recorded") != std::string::npos);
  // Version 1: frames of 20 fixed bytes, no flags (frames start at 280 and 412 in version 2)
  std::string v1 = encodeReplay(handMadeReplay());
  v1.erase(412 + 20, 4);
  v1.erase(280 + 20, 4);
  v1[14] = 1;
  const Replay old = decodeReplay(v1, "old.replay");
  REQUIRE(old.frames.size() == 2);
  CHECK(old.frames[0].contacts_recorded);
  CHECK(old.frames[1].contacts.size() == 1);
  CHECK(old.frames[1].poses == handMadeReplay().frames[1].poses);
}

TEST_CASE("replay: which bodies sleep survives a round trip and costs a byte a body; version 2 files still read", "[common]") {
  Replay replay = handMadeReplay();
  replay.frames[1].asleep = {0, 1, 0};
  const std::string bytes = encodeReplay(replay);
  CHECK(bytes.size() == encodeReplay(handMadeReplay()).size() + 3);
  CHECK(replayFrameBytes(3, 2, 1, true) == 175);
  const Replay back = decodeReplay(bytes, "test.replay");
  CHECK(back.frames[0].asleep.empty());
  CHECK(back.frames[1].asleep == std::vector<std::uint8_t>{0, 1, 0});
  CHECK(back.frames[1].poses == replay.frames[1].poses);
  CHECK(back.frames[1].contacts.size() == 1);
  // The mask follows frame 1's poses (frame 1 from byte 412: 24 fixed bytes, 3 poses of 28)
  std::string bad = bytes;
  bad[412 + 24 + 84 + 1] = 2;
  CHECK(replayRefusal(bad).find("frame 1 says a body's asleep is 2 at byte 521, not 0 or 1") != std::string::npos);
  CHECK(replayRefusal(bytes.substr(0, 412 + 24 + 84 + 2)).find("frame 1's sleeping bodies") != std::string::npos);
  // Written wrong: one entry per body, each 0 or 1, or none
  replay.frames[1].asleep = {0, 1};
  CHECK_THROWS_WITH(encodeReplay(replay), Catch::Matchers::Contains("says of 2 bodies whether they sleep, not of 3"));
  replay.frames[1].asleep = {0, 7, 0};
  CHECK_THROWS_WITH(encodeReplay(replay), Catch::Matchers::Contains("a body's asleep is 7, not 0 or 1"));
  // A version 2 file (no mask, flag bit 1 unknown to it) reads as before
  std::string v2 = encodeReplay(handMadeReplay());
  v2[14] = 2;
  CHECK(decodeReplay(v2, "v2.replay").frames[1].asleep.empty());
}

TEST_CASE("replay: a World with sleeping on records which bodies sleep", "[common]") {
  Settings settings;
  settings.sleeping = true;
  World world(bouncingBall(0.0, 0.0), settings);
  Replay replay = startReplay(world, "a ball at rest");
  // A ball at rest on the ground: still from the first step, asleep once still for sleep_time
  for (int n = 0; n < 60; ++n) {
    world.step(1.0 / 60.0);
    recordFrame(world, replay, false);
  }
  REQUIRE(replay.frames.back().asleep.size() == 2);
  CHECK(replay.frames.back().asleep[1] == (world.asleep(1) ? 1 : 0));
  CHECK(world.asleep(1));
  CHECK(replay.frames.front().asleep == std::vector<std::uint8_t>{0, 0});
  // Without sleeping nothing is recorded, and the file is as before
  World awake(bouncingBall(0.0, 0.0));
  Replay plain = startReplay(awake, "awake");
  awake.step(1.0 / 60.0);
  recordFrame(awake, plain);
  CHECK(plain.frames.back().asleep.empty());
}

TEST_CASE("replay: a recorded box rain holds a frame per step with the World's poses", "[common]") {
  World world(boxRain(12, 3));
  Replay replay = startReplay(world, "box rain");
  REQUIRE(replay.bodies.size() == world.states().size());
  CHECK(replay.bodies[0].kind == ReplayShapeKind::Plane);
  CHECK(replay.bodies[0].fixed);
  CHECK(replay.settings == world.describe());
  const int steps = 40;
  bool touched = false;
  for (int n = 0; n < steps; ++n) {
    world.step(0.01);
    recordFrame(world, replay);
    const ReplayFrame& frame = replay.frames.back();
    REQUIRE(frame.contacts.size() == world.contacts().size());
    touched = touched || !frame.contacts.empty();
    for (std::size_t i = 0; i < world.states().size(); ++i) {
      const BodyState& s = world.states()[i];
      const double expected[7] = {s.x.x(), s.x.y(), s.x.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z()};
      for (int k = 0; k < 7; ++k) {
        // Stored as float32: equal to the double rounded to float
        CHECK(frame.poses[7 * i + static_cast<std::size_t>(k)] == static_cast<float>(expected[k]));
      }
    }
    CHECK(frame.time == static_cast<float>(world.time()));
    CHECK(frame.iterations == static_cast<std::uint32_t>(world.diagnostics().iterations));
  }
  CHECK(replay.frames.size() == static_cast<std::size_t>(steps));
  CHECK(touched);  // the rain lands on the walls or the ground within 0.4 s
  recordFrame(world, replay, false);
  CHECK_FALSE(replay.frames.back().contacts_recorded);
  CHECK(replay.frames.back().contacts.empty());
  CHECK(replay.frames.back().poses == replay.frames[replay.frames.size() - 2].poses);  // no step between the two
  const Replay back = decodeReplay(encodeReplay(replay), "box rain");
  CHECK(back.frames.size() == replay.frames.size());
  CHECK(back.frames.back().poses == replay.frames.back().poses);
}
