// Recording a World: its shapes once (startReplay), then a frame per call (recordFrame).
#include "physlab/error.hpp"
#include "physlab/replay.hpp"
#include "physlab/world.hpp"

namespace physlab {
namespace {

std::array<float, 3> floats(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace

Replay startReplay(const World& world, std::string title) {
  Replay replay;
  replay.title = std::move(title);
  replay.settings = world.describe();
  replay.bodies.reserve(world.bodies().size());
  for (const BodyDescription& description : world.bodies()) replay.bodies.push_back(replayBody(description.shape, description.fixed));
  return replay;
}

void recordFrame(const World& world, Replay& replay, bool contacts) {
  const std::vector<BodyState>& states = world.states();
  if (states.size() != replay.bodies.size()) {
    throw InvalidInput("recordFrame: the World has " + std::to_string(states.size()) + " bodies, the replay " +
                       std::to_string(replay.bodies.size()));
  }
  const Diagnostics& diagnostics = world.diagnostics();
  ReplayFrame& frame = replay.frames.emplace_back();
  frame.time = static_cast<float>(world.time());
  frame.kinetic_energy = static_cast<float>(diagnostics.kinetic_energy);
  frame.potential_energy = static_cast<float>(diagnostics.potential_energy);
  frame.iterations = static_cast<std::uint32_t>(diagnostics.iterations);
  frame.poses.reserve(7 * states.size());
  for (const BodyState& s : states) {
    for (double v : {s.x.x(), s.x.y(), s.x.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z()}) {
      frame.poses.push_back(static_cast<float>(v));
    }
  }
  if (world.settings().sleeping) {
    frame.asleep.resize(states.size());
    for (std::size_t i = 0; i < states.size(); ++i) frame.asleep[i] = world.asleep(static_cast<int>(i)) ? 1 : 0;
  }
  frame.contacts_recorded = contacts;
  if (!contacts) return;
  frame.contacts.reserve(world.contacts().size());
  for (const Contact& c : world.contacts()) {
    ReplayContact& r = frame.contacts.emplace_back();
    r.a = static_cast<std::uint32_t>(c.a);
    r.b = static_cast<std::uint32_t>(c.b);
    r.p = floats(c.p);
    r.n = floats(c.n);
    r.depth = static_cast<float>(c.depth);
    r.j = static_cast<float>(c.j);
  }
}

}  // namespace physlab
