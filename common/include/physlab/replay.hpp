#pragma once
/// \file
/// Replays: what a scene did, frame by frame, for the 3-D viewer (`./physlab view NN`).
///
/// A Replay holds the shapes once (one ReplayBody per body) and, per frame, the bodies' poses,
/// the particles' positions (Labs 1-2), the contact points with their normals, depths and normal
/// impulses, the energies and the solver's iterations. Every number is stored as float32: a
/// viewer needs no more (float32 keeps 7 significant digits: 0.1 um on a 1 m pose), and a frame of
/// Lab 6's 55-cube pyramid takes 14 kB, most of it its 320 contact points. The file layout is on the conventions page
/// ("Replay files"); writeReplay() and readReplay() are its only writer and reader in C++,
/// tools/view.py and the page read it too.
///
/// Recording costs nothing when off: nothing in World::step() or an integrator knows about
/// replays. The scene's driver calls recordFrame() after each step it wants to see, so a scene that
/// does not record runs exactly the code it ran before.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "physlab/collision.hpp"
#include "physlab/math.hpp"

namespace physlab {

class World;

/// What a recorded body is.
enum class ReplayShapeKind : std::uint32_t {
  Sphere = 0,   ///< size[0] = radius [m]
  Box = 1,      ///< size[0..2] = half extents, body frame [m]
  Capsule = 2,  ///< size[0] = radius, size[1] = half height of the core segment along body z [m]
  Plane = 3,    ///< size[0..2] = unit normal, size[3] = offset d of \f$\hat n \cdot p \le d\f$, world frame [m]
  Convex = 4,   ///< ReplayBody::vertices and ReplayBody::triangles, body frame [m]
};

/// One body's shape, recorded once.
struct ReplayBody {
  ReplayShapeKind kind = ReplayShapeKind::Sphere;  ///< which shape
  bool fixed = false;                              ///< never moves
  std::array<float, 4> size{};                     ///< sizes, as ReplayShapeKind says (unused entries 0)
  std::vector<float> vertices;                     ///< Convex: x, y, z per vertex, body frame [m] (3 V)
  std::vector<std::uint32_t> triangles;            ///< Convex: 3 vertex indices per triangle, counter-clockwise from outside (3 K)
};

/// One contact point of a frame (physlab::Contact, as the solver left it).
struct ReplayContact {
  std::uint32_t a = 0;               ///< body A (the normal points towards it)
  std::uint32_t b = 0;               ///< body B
  std::array<float, 3> p{};          ///< the point, world frame [m]
  std::array<float, 3> n{};          ///< unit normal from B to A, world frame
  float depth = 0.0f;                ///< penetration, > 0 overlapping [m]
  float j = 0.0f;                    ///< normal impulse over the step [N s]
};

/// One recorded frame.
struct ReplayFrame {
  float time = 0.0f;                   ///< simulated time [s]
  float kinetic_energy = 0.0f;         ///< [J]
  float potential_energy = 0.0f;       ///< [J]
  std::uint32_t iterations = 0;        ///< the solver's iterations (sweeps or pivots) in the step that ended here
  std::vector<float> poses;            ///< per body x, y, z [m], q_w, q_x, q_y, q_z: 7 per body, world frame
  std::vector<float> particles;        ///< per particle x, y, z, world frame [m]: 3 per particle
  std::vector<ReplayContact> contacts;  ///< this frame's contact points (none when not recorded)
  bool contacts_recorded = true;       ///< false: this frame's contacts were left out to keep a large scene's file small
  std::vector<std::uint8_t> asleep;    ///< per body 1 while it sleeps (Settings::sleeping), else 0; empty: not recorded (no sleeping)
};

/// A recorded scene: shapes once, then frames.
struct Replay {
  std::string title;                    ///< the scene's name, shown by the viewer
  std::string settings;                 ///< the settings string of the run (World::describe()), may be empty
  std::vector<ReplayBody> bodies;       ///< one per body
  std::uint32_t particle_count = 0;     ///< particles per frame (Labs 1-2; 0 for rigid bodies)
  std::vector<std::uint32_t> springs;   ///< particle index pairs: 2 per spring
  std::vector<ReplayFrame> frames;      ///< in time order
};

/// The format's version; readReplay() refuses a newer one.
/// Version 2 added a frame's flags (contacts recorded or not), version 3 the sleeping bodies (flag
/// bit 1: a byte per body after the poses); version 1 and 2 files still read (every frame's
/// contacts recorded in version 1, no body asleep in either).
constexpr std::uint16_t kReplayVersion = 3;

/// Bytes of the header: 40 plus the title's and the settings' bytes.
std::size_t replayHeaderBytes(const Replay& replay);
/// Bytes of one body's shape: 32 + 12 V + 12 K (V vertices, K triangles).
std::size_t replayBodyBytes(const ReplayBody& body);
/// Bytes of one frame: 24 + 28 B + 12 P + 40 C (B bodies, P particles, C contacts), and B more
/// when it records which bodies sleep.
std::size_t replayFrameBytes(std::size_t bodies, std::size_t particles, std::size_t contacts, bool asleep = false);

/// The file's bytes. InvalidInput, naming the frame and field, when a frame's poses, particles or
/// sleeping bodies (none or one per body, each 0 or 1) do not match the body and particle counts,
/// a contact or spring names no body or particle, or a Convex body's arrays are not whole triples.
std::string encodeReplay(const Replay& replay);
/// Reads the bytes of a replay file; `what` names the source in messages. InvalidInput naming the
/// byte offset when the magic is not "PHYSLAB-REPLAY", the version is newer than kReplayVersion,
/// the bytes end before the layout does ("truncated at byte N: frame 3's poses (56 bytes from byte M) is missing"),
/// or bytes are left after the last frame.
Replay decodeReplay(std::string_view bytes, std::string_view what);
/// A copy of `replay` whose file takes at most `max_bytes` (the reference's recorded runs that a
/// student copy ships, ./physlab publish): with every s-th frame (the first, then one in s, and the
/// last) and the contacts of every c-th kept frame (the others' left out, contacts_recorded false),
/// s the smallest stride, then c the smallest up to 10, that fit. A replay that fits is returned
/// whole; one whose first and last frames alone do not fit keeps those two. Frames keep their
/// times, so a viewer matches them with a full run's by time.
Replay thinReplay(const Replay& replay, std::size_t max_bytes);
/// encodeReplay() into the file `path` (InvalidInput when it cannot be written).
void writeReplay(const Replay& replay, const std::string& path);
/// decodeReplay() of the file `path` (InvalidInput when it cannot be read).
Replay readReplay(const std::string& path);

/// Appends a frame of rigid-body poses at time t [s] (x and q per body, in body order), no
/// contacts; for scenes outside a World (Lab 3). InvalidInput when the count is not the replay's.
void recordPoses(Replay& replay, double t, const std::vector<Vec3>& x, const std::vector<Quat>& q,
                 double kinetic_energy, double potential_energy);
/// Appends a frame of particle positions (one column per particle) at time t [s] (Labs 1-2).
/// InvalidInput when the count is not replay.particle_count.
void recordParticles(Replay& replay, double t, const Mat3X& positions, double kinetic_energy,
                     double potential_energy);

/// \name Recording shapes (defined with Lab 4's framework)
///@{

/// The recorded form of `shape`: its sizes, or (a ConvexPolyhedron, a Triangle) a mesh of
/// triangles, each face a fan from its first vertex; a Triangle gets both sides.
ReplayBody replayBody(const Shape& shape, bool fixed);
///@}

/// \name Recording a World (defined with Lab 5's framework)
///@{

/// A replay of `world` with its shapes and settings (World::describe()) and no frames yet.
Replay startReplay(const World& world, std::string title);
/// Appends the World's state now as a frame: every body's pose, the last step's contacts
/// (World::contacts(): point, normal, depth, normal impulse j), the energies and the solver
/// iterations of World::diagnostics(), and with Settings::sleeping which bodies sleep (World::asleep()).
/// Call it after a step (a World not yet stepped has no
/// diagnostics: zeros); a World that is not recorded pays nothing. With `contacts` false the frame
/// holds the poses and energies only (ReplayFrame::contacts_recorded false): a scene of hundreds
/// of bodies records its thousands of contact points on some frames only, and the viewer shows
/// the last recorded ones. InvalidInput when the replay's body count is not the World's.
void recordFrame(const World& world, Replay& replay, bool contacts = true);
///@}

}  // namespace physlab
