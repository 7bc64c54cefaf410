// Replay files: the little-endian float32 layout of the conventions page ("Replay files").
#include "physlab/replay.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "physlab/error.hpp"

namespace physlab {
namespace {

constexpr std::string_view kMagic = "PHYSLAB-REPLAY";
constexpr std::size_t kBodyFixedBytes = 32;
constexpr std::size_t kFrameFixedBytes = 24;
constexpr std::size_t kFrameFixedBytesV1 = 20;
constexpr std::uint32_t kContactsRecorded = 1u;  // bit 0 of a frame's flags
constexpr std::uint32_t kAsleepRecorded = 2u;    // bit 1: a byte per body follows the poses (version 3)
constexpr std::size_t kPoseBytes = 28;
constexpr std::size_t kParticleBytes = 12;
constexpr std::size_t kContactBytes = 40;

// Writes numbers byte by byte, least significant first, whatever the machine's byte order.
class ByteWriter {
 public:
  explicit ByteWriter(std::size_t capacity) { bytes_.reserve(capacity); }
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) {
    bytes_.push_back(static_cast<char>(v & 0xffu));
    bytes_.push_back(static_cast<char>(v >> 8));
  }
  void u32(std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8) bytes_.push_back(static_cast<char>((v >> shift) & 0xffu));
  }
  void f32(float v) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    u32(bits);
  }
  void raw(std::string_view s) { bytes_.append(s); }
  void text(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    raw(s);
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

// Reads the layout back, naming the byte where the data ran out. Every read of a field follows a
// need() that covers it.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, std::string_view what) : bytes_(bytes), what_(what) {}
  // Refuses when fewer than n bytes remain for `field`: checked before any allocation, so that a
  // corrupt count never allocates more than the file holds.
  void need(std::size_t n, const std::string& field) const {
    if (bytes_.size() - at_ < n) {
      throw InvalidInput("replay " + what_ + ": truncated at byte " + std::to_string(bytes_.size()) + ": " + field +
                         " (" + std::to_string(n) + " bytes from byte " + std::to_string(at_) + ") is missing");
    }
  }
  void skip(std::size_t n) { at_ += n; }
  std::uint8_t u8() { return static_cast<std::uint8_t>(bytes_[at_++]); }
  std::uint16_t u16() {
    const unsigned b0 = static_cast<unsigned char>(bytes_[at_]), b1 = static_cast<unsigned char>(bytes_[at_ + 1]);
    at_ += 2;
    return static_cast<std::uint16_t>(b0 | (b1 << 8));
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes_[at_ + k])) << (8 * k);
    at_ += 4;
    return v;
  }
  float f32() {
    const std::uint32_t bits = u32();
    float v = 0.0f;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  // A length-prefixed string
  std::string text(const std::string& field) {
    need(4, field + "'s length");
    const std::uint32_t n = u32();
    need(n, field);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  std::size_t at() const { return at_; }
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  std::string_view bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

void requireTriples(std::size_t n, const std::string& field) {
  if (n % 3 != 0) throw InvalidInput("replay " + field + " holds " + std::to_string(n) + " numbers, not whole triples");
}

}  // namespace

std::size_t replayHeaderBytes(const Replay& replay) { return 40 + replay.title.size() + replay.settings.size(); }

std::size_t replayBodyBytes(const ReplayBody& body) {
  return kBodyFixedBytes + 4 * body.vertices.size() + 4 * body.triangles.size();
}

std::size_t replayFrameBytes(std::size_t bodies, std::size_t particles, std::size_t contacts, bool asleep) {
  return kFrameFixedBytes + kPoseBytes * bodies + (asleep ? bodies : 0) + kParticleBytes * particles +
         kContactBytes * contacts;
}

std::string encodeReplay(const Replay& replay) {
  // Check every array against the counts the header will state, before writing a byte
  const std::size_t B = replay.bodies.size(), P = replay.particle_count;
  std::size_t total = replayHeaderBytes(replay) + 4 * replay.springs.size();
  for (std::size_t i = 0; i < B; ++i) {
    const ReplayBody& body = replay.bodies[i];
    const std::string name = "body " + std::to_string(i);
    requireTriples(body.vertices.size(), name + " vertices");
    requireTriples(body.triangles.size(), name + " triangles");
    for (std::uint32_t v : body.triangles) {
      if (3 * static_cast<std::size_t>(v) >= body.vertices.size()) {
        throw InvalidInput("replay " + name + ": triangle vertex " + std::to_string(v) + " is not a vertex");
      }
    }
    total += replayBodyBytes(body);
  }
  if (replay.springs.size() % 2 != 0) throw InvalidInput("replay springs hold an odd number of particle indices");
  for (std::uint32_t s : replay.springs) {
    if (s >= P) throw InvalidInput("replay spring end " + std::to_string(s) + " is not a particle");
  }
  for (std::size_t f = 0; f < replay.frames.size(); ++f) {
    const ReplayFrame& frame = replay.frames[f];
    const std::string name = "replay frame " + std::to_string(f);
    if (frame.poses.size() != 7 * B) {
      throw InvalidInput(name + " has " + std::to_string(frame.poses.size()) + " pose numbers, not 7 x " +
                         std::to_string(B) + " bodies");
    }
    if (frame.particles.size() != 3 * P) {
      throw InvalidInput(name + " has " + std::to_string(frame.particles.size()) + " particle numbers, not 3 x " +
                         std::to_string(P) + " particles");
    }
    if (!frame.contacts_recorded && !frame.contacts.empty()) {
      throw InvalidInput(name + " holds contacts but says they were not recorded");
    }
    for (const ReplayContact& c : frame.contacts) {
      if (c.a >= B || c.b >= B) throw InvalidInput(name + ": a contact names a body that is not there");
    }
    if (!frame.asleep.empty() && frame.asleep.size() != B) {
      throw InvalidInput(name + " says of " + std::to_string(frame.asleep.size()) + " bodies whether they sleep, not of " +
                         std::to_string(B));
    }
    for (std::uint8_t a : frame.asleep) {
      if (a > 1) throw InvalidInput(name + ": a body's asleep is " + std::to_string(a) + ", not 0 or 1");
    }
    total += replayFrameBytes(B, P, frame.contacts.size(), !frame.asleep.empty());
  }

  ByteWriter out(total);
  out.raw(kMagic);
  out.u16(kReplayVersion);
  out.u32(static_cast<std::uint32_t>(B));
  out.u32(static_cast<std::uint32_t>(P));
  out.u32(static_cast<std::uint32_t>(replay.springs.size() / 2));
  out.u32(static_cast<std::uint32_t>(replay.frames.size()));
  out.text(replay.title);
  out.text(replay.settings);
  for (const ReplayBody& body : replay.bodies) {
    out.u32(static_cast<std::uint32_t>(body.kind));
    out.u32(body.fixed ? 1u : 0u);
    for (float v : body.size) out.f32(v);
    out.u32(static_cast<std::uint32_t>(body.vertices.size() / 3));
    out.u32(static_cast<std::uint32_t>(body.triangles.size() / 3));
    for (float v : body.vertices) out.f32(v);
    for (std::uint32_t v : body.triangles) out.u32(v);
  }
  for (std::uint32_t s : replay.springs) out.u32(s);
  for (const ReplayFrame& frame : replay.frames) {
    out.f32(frame.time);
    out.f32(frame.kinetic_energy);
    out.f32(frame.potential_energy);
    out.u32(frame.iterations);
    out.u32(static_cast<std::uint32_t>(frame.contacts.size()));
    out.u32((frame.contacts_recorded ? kContactsRecorded : 0u) | (frame.asleep.empty() ? 0u : kAsleepRecorded));
    for (float v : frame.poses) out.f32(v);
    for (std::uint8_t a : frame.asleep) out.u8(a);
    for (float v : frame.particles) out.f32(v);
    for (const ReplayContact& c : frame.contacts) {
      out.u32(c.a);
      out.u32(c.b);
      for (float v : c.p) out.f32(v);
      for (float v : c.n) out.f32(v);
      out.f32(c.depth);
      out.f32(c.j);
    }
  }
  return out.take();
}

Replay decodeReplay(std::string_view bytes, std::string_view what) {
  ByteReader in(bytes, what);
  const std::string source = "replay " + std::string(what);
  if (bytes.substr(0, kMagic.size()) != kMagic) {
    throw InvalidInput(source + ": not a PhysLab replay: bytes 0-13 are not \"PHYSLAB-REPLAY\"");
  }
  in.skip(kMagic.size());
  in.need(2, "the version");
  const std::uint16_t version = in.u16();
  if (version == 0 || version > kReplayVersion) {
    throw InvalidInput(source + ": version " + std::to_string(version) + " at byte 14 is not one this reader knows (1-" +
                       std::to_string(kReplayVersion) + "): a newer one needs an updated PhysLab");
  }
  Replay replay;
  in.need(16, "the header's counts");
  const std::uint32_t B = in.u32(), P = in.u32(), S = in.u32(), F = in.u32();
  replay.title = in.text("the title");
  replay.settings = in.text("the settings");
  replay.particle_count = P;
  in.need(static_cast<std::size_t>(B) * kBodyFixedBytes, "the " + std::to_string(B) + " bodies");
  replay.bodies.resize(B);
  for (std::uint32_t i = 0; i < B; ++i) {
    ReplayBody& body = replay.bodies[i];
    const std::string name = "body " + std::to_string(i);
    in.need(kBodyFixedBytes, name);
    const std::uint32_t kind = in.u32();
    if (kind > static_cast<std::uint32_t>(ReplayShapeKind::Convex)) {
      throw InvalidInput(source + ": " + name + " has shape kind " + std::to_string(kind) + " at byte " +
                         std::to_string(in.at() - 4) + ", not 0-4");
    }
    body.kind = static_cast<ReplayShapeKind>(kind);
    body.fixed = in.u32() != 0;
    for (float& v : body.size) v = in.f32();
    const std::uint32_t V = in.u32(), K = in.u32();
    in.need(12 * (static_cast<std::size_t>(V) + K), name + "'s vertices and triangles");
    body.vertices.resize(3 * static_cast<std::size_t>(V));
    for (float& v : body.vertices) v = in.f32();
    body.triangles.resize(3 * static_cast<std::size_t>(K));
    for (std::uint32_t& v : body.triangles) v = in.u32();
  }
  in.need(8 * static_cast<std::size_t>(S), "the " + std::to_string(S) + " springs");
  replay.springs.resize(2 * static_cast<std::size_t>(S));
  for (std::uint32_t& s : replay.springs) s = in.u32();
  // Room for the frames the bytes can hold at most: a corrupt count allocates no more
  const std::size_t frame_fixed = version == 1 ? kFrameFixedBytesV1 : kFrameFixedBytes;
  replay.frames.reserve(std::min<std::size_t>(F, in.remaining() / (frame_fixed + kPoseBytes * B + kParticleBytes * P)));
  for (std::uint32_t f = 0; f < F; ++f) {
    ReplayFrame& frame = replay.frames.emplace_back();
    const std::string name = "frame " + std::to_string(f);
    in.need(frame_fixed, name + "'s time, energies and counts");
    frame.time = in.f32();
    frame.kinetic_energy = in.f32();
    frame.potential_energy = in.f32();
    frame.iterations = in.u32();
    const std::uint32_t C = in.u32();
    const std::uint32_t flags = version > 1 ? in.u32() : kContactsRecorded;
    frame.contacts_recorded = (flags & kContactsRecorded) != 0;
    const bool asleep = version > 2 && (flags & kAsleepRecorded) != 0;
    if (!frame.contacts_recorded && C != 0) {
      throw InvalidInput(source + ": " + name + " holds " + std::to_string(C) + " contacts but says they were not recorded");
    }
    in.need(kPoseBytes * B, name + "'s poses");
    frame.poses.resize(7 * static_cast<std::size_t>(B));
    for (float& v : frame.poses) v = in.f32();
    if (asleep) {
      in.need(B, name + "'s sleeping bodies");
      frame.asleep.resize(B);
      for (std::uint8_t& a : frame.asleep) {
        a = in.u8();
        if (a > 1) {
          throw InvalidInput(source + ": " + name + " says a body's asleep is " + std::to_string(a) + " at byte " +
                             std::to_string(in.at() - 1) + ", not 0 or 1");
        }
      }
    }
    in.need(kParticleBytes * P, name + "'s particles");
    frame.particles.resize(3 * static_cast<std::size_t>(P));
    for (float& v : frame.particles) v = in.f32();
    in.need(kContactBytes * C, name + "'s " + std::to_string(C) + " contacts");
    frame.contacts.resize(C);
    for (ReplayContact& c : frame.contacts) {
      c.a = in.u32();
      c.b = in.u32();
      for (float& v : c.p) v = in.f32();
      for (float& v : c.n) v = in.f32();
      c.depth = in.f32();
      c.j = in.f32();
    }
  }
  if (in.at() != bytes.size()) {
    throw InvalidInput(source + ": " + std::to_string(bytes.size() - in.at()) + " bytes after the last frame, at byte " +
                       std::to_string(in.at()));
  }
  return replay;
}

Replay thinReplay(const Replay& replay, std::size_t max_bytes) {
  const std::size_t F = replay.frames.size(), B = replay.bodies.size(), P = replay.particle_count;
  std::size_t fixed = replayHeaderBytes(replay) + 4 * replay.springs.size();
  for (const ReplayBody& body : replay.bodies) fixed += replayBodyBytes(body);
  const auto kept = [F](std::size_t f, std::size_t stride) { return f % stride == 0 || f + 1 == F; };
  // Bytes with every `stride`-th frame and the contacts of every `contacts_stride`-th kept one
  const auto bytes = [&](std::size_t stride, std::size_t contacts_stride) {
    std::size_t total = fixed, k = 0;
    for (std::size_t f = 0; f < F; ++f) {
      if (!kept(f, stride)) continue;
      total += replayFrameBytes(B, P, k++ % contacts_stride == 0 ? replay.frames[f].contacts.size() : 0,
                                !replay.frames[f].asleep.empty());
    }
    return total;
  };
  const auto thinned = [&](std::size_t stride, std::size_t contacts_stride) {
    Replay out = replay;
    out.frames.clear();
    std::size_t k = 0;
    for (std::size_t f = 0; f < F; ++f) {
      if (!kept(f, stride)) continue;
      ReplayFrame& frame = out.frames.emplace_back(replay.frames[f]);
      if (k++ % contacts_stride != 0) {
        frame.contacts.clear();
        frame.contacts_recorded = false;
      }
    }
    return out;
  };
  constexpr std::size_t kMaxContactsStride = 10;
  for (std::size_t stride = 1; stride <= std::max<std::size_t>(F, 1); ++stride) {
    for (std::size_t contacts_stride = 1; contacts_stride <= kMaxContactsStride; ++contacts_stride) {
      if (bytes(stride, contacts_stride) > max_bytes) continue;
      return stride == 1 && contacts_stride == 1 ? replay : thinned(stride, contacts_stride);
    }
  }
  return thinned(std::max<std::size_t>(F, 1), std::max<std::size_t>(F, 1));
}

void writeReplay(const Replay& replay, const std::string& path) {
  const std::string bytes = encodeReplay(replay);
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!file) throw InvalidInput("replay " + path + ": cannot be written");
}

Replay readReplay(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InvalidInput("replay " + path + ": cannot be read (no such file?)");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return decodeReplay(bytes, path);
}

void recordPoses(Replay& replay, double t, const std::vector<Vec3>& x, const std::vector<Quat>& q,
                 double kinetic_energy, double potential_energy) {
  if (x.size() != replay.bodies.size() || q.size() != replay.bodies.size()) {
    throw InvalidInput("recordPoses: " + std::to_string(x.size()) + " positions and " + std::to_string(q.size()) +
                       " orientations for a replay of " + std::to_string(replay.bodies.size()) + " bodies");
  }
  ReplayFrame& frame = replay.frames.emplace_back();
  frame.time = static_cast<float>(t);
  frame.kinetic_energy = static_cast<float>(kinetic_energy);
  frame.potential_energy = static_cast<float>(potential_energy);
  frame.poses.reserve(7 * x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (double v : {x[i].x(), x[i].y(), x[i].z(), q[i].w(), q[i].x(), q[i].y(), q[i].z()}) {
      frame.poses.push_back(static_cast<float>(v));
    }
  }
}

void recordParticles(Replay& replay, double t, const Mat3X& positions, double kinetic_energy,
                     double potential_energy) {
  if (static_cast<std::size_t>(positions.cols()) != replay.particle_count) {
    throw InvalidInput("recordParticles: " + std::to_string(positions.cols()) + " particles for a replay of " +
                       std::to_string(replay.particle_count));
  }
  ReplayFrame& frame = replay.frames.emplace_back();
  frame.time = static_cast<float>(t);
  frame.kinetic_energy = static_cast<float>(kinetic_energy);
  frame.potential_energy = static_cast<float>(potential_energy);
  frame.particles.resize(3 * replay.particle_count);
  for (Index j = 0; j < positions.cols(); ++j) {
    for (Index i = 0; i < 3; ++i) frame.particles[static_cast<std::size_t>(3 * j + i)] = static_cast<float>(positions(i, j));
  }
}

}  // namespace physlab
