#include "frame_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "frame_writer.h"

namespace sph {
namespace {

// The property list write_ply_frame writes, in order; anything else is another format.
const char* const kProperties[] = {
    "property float x",  "property float y",  "property float z",       "property float vx",
    "property float vy", "property float vz", "property float density", "property float pressure",
    "property uchar fluid", "property int id", "property float ax",     "property float ay",
    "property float az",  "property float age",     "property float near_pressure"};
constexpr std::size_t kMaxHeaderBytes = 1 << 20;  // bounds the read of a file that is no frame

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw SceneError(path + ": " + what);
}

double parse_double(const std::string& path, const std::string& key, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    refuse(path, "header line \"comment " + key + "\": \"" + text + "\" is not a finite number");
  return v;
}

long parse_long(const std::string& path, const std::string& key, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE || v < lo || v > hi) {
    std::ostringstream os;
    os << "header line \"" << key << "\": \"" << text << "\" is not a whole number in [" << lo << ", " << hi << "]";
    refuse(path, os.str());
  }
  return long(v);
}

// Header lines after "ply" up to "end_header", read from at most the first 1 MiB (so a large file that is
// no frame is not read whole); header_bytes is where the first record starts.
std::vector<std::string> header_lines(std::ifstream& in, std::uint64_t file_size, const std::string& path,
                                      std::uint64_t& header_bytes) {
  std::string head(std::size_t(std::min<std::uint64_t>(file_size, kMaxHeaderBytes)), '\0');
  if (!in.read(&head[0], std::streamsize(head.size()))) refuse(path, "error while reading the header");
  if (head.compare(0, 4, "ply\n") != 0) refuse(path, "not a PLY file (it does not start with the line \"ply\")");
  const std::size_t end = head.find("\nend_header\n");
  if (end == std::string::npos)
    refuse(path, file_size > kMaxHeaderBytes ? "no \"end_header\" in the first 1 MiB; not a frame written by sph_run"
                                             : "the PLY header ends before \"end_header\" (truncated file?)");
  header_bytes = end + 12;
  std::vector<std::string> lines;
  std::istringstream text(head.substr(4, end - 4 + 1));
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

// The header's fields, checked for presence and range; n is the number of particle records.
void parse_header(const std::vector<std::string>& lines, const std::string& path, double max_particles, FrameInfo& info,
                  std::size_t& n) {
  bool have_time = false, have_scene = false, have_step = false, have_frame = false, have_next = false,
       have_spacing = false, have_jets = false, have_count = false;
  std::size_t prop = 0, jets_seen = 0;
  for (const std::string& line : lines) {
    auto after = [&](const char* prefix, std::string& rest) {
      const std::size_t k = std::strlen(prefix);
      if (line.compare(0, k, prefix) != 0) return false;
      rest = line.substr(k);
      return true;
    };
    std::string v;
    if (line.rfind("format ", 0) == 0) {
      if (line != "format binary_little_endian 1.0")
        refuse(path, "\"" + line + "\": only binary_little_endian 1.0 frames written by sph_run can be read");
    } else if (after("comment sph frame, time ", v)) {
      if (v.size() < 2 || v.compare(v.size() - 2, 2, " s") != 0) refuse(path, "header line \"" + line + "\" has no unit s");
      info.time = parse_double(path, "time", v.substr(0, v.size() - 2));
      if (info.time < 0.0) refuse(path, "negative simulated time " + v);
      have_time = true;
    } else if (after("comment scene ", v)) {
      info.scene = v;
      have_scene = true;
    } else if (after("comment solver ", v)) {
      info.solver = v;
    } else if (after("comment step ", v)) {
      info.step = parse_long(path, "comment step", v, 0, 1L << 62);
      have_step = true;
    } else if (after("comment frame ", v)) {
      info.frame_index = int(parse_long(path, "comment frame", v, 0, 99999999L));  // frame_%05d grows to 8 digits
      have_frame = true;
    } else if (after("comment next_id ", v)) {
      info.next_id = int32_t(parse_long(path, "comment next_id", v, 0, 2147483647L));
      have_next = true;
    } else if (after("comment spacing ", v)) {
      info.spacing = parse_double(path, "spacing", v);
      if (!(info.spacing > 0.0)) refuse(path, "spacing " + v + " must be positive");
      have_spacing = true;
    } else if (after("comment jets ", v)) {
      info.jet_travelled.assign(std::size_t(parse_long(path, "comment jets", v, 0, 1024)), 0.0);
      have_jets = true;
    } else if (after("comment jet ", v)) {
      const std::size_t sp = v.find(" travelled ");
      const std::string expect = "comment jet " + std::to_string(jets_seen) + " travelled ";
      if (!have_jets || sp == std::string::npos || line.compare(0, expect.size(), expect) != 0 ||
          jets_seen >= info.jet_travelled.size())
        refuse(path, "header line \"" + line + "\": expected \"" + expect + "X\" after \"comment jets\"");
      info.jet_travelled[jets_seen++] = parse_double(path, "jet travelled", v.substr(sp + 11));
    } else if (after("comment energy_budget ", v)) {
      std::istringstream fields(v);
      std::string e, m, s, p;
      if (!(fields >> e >> m >> s >> p)) refuse(path, "header line \"" + line + "\": expected four numbers");
      info.energy_in = parse_double(path, "energy_budget", e);
      info.mass_in = parse_double(path, "energy_budget", m);
      info.max_specific_in = parse_double(path, "energy_budget", s);
      info.potential_reference = parse_double(path, "energy_budget", p);
      info.has_energy = true;
    } else if (after("element vertex ", v)) {
      const long count = parse_long(path, "element vertex", v, 0, 2147483647L);
      if (double(count) > max_particles) {
        std::ostringstream os;
        os << "the frame holds " << count << " particles, more than limits.max_particles = " << std::llround(max_particles)
           << "; raise the limit (--set limits.max_particles=N)";
        refuse(path, os.str());
      }
      n = std::size_t(count);
      have_count = true;
    } else if (line.rfind("property ", 0) == 0) {
      if (prop >= std::size(kProperties) || line != kProperties[prop])
        refuse(path, "unexpected \"" + line + "\": sph_run frames have the properties x y z vx vy vz density pressure "
                     "fluid id ax ay az age near_pressure (frames of older versions lack some and cannot be continued)");
      ++prop;
    } else if (line.rfind("element ", 0) == 0) {
      refuse(path, "unexpected \"" + line + "\": a frame has one element, vertex");
    }
  }
  if (prop != std::size(kProperties))
    refuse(path, "only " + std::to_string(prop) + " of the " + std::to_string(std::size(kProperties)) +
                     " properties x y z vx vy vz density pressure fluid id ax ay az age near_pressure (frames of older versions lack some and "
                     "cannot be continued)");
  const std::pair<bool, const char*> required[] = {
      {have_time, "comment sph frame, time T s"}, {have_scene, "comment scene NAME"}, {have_step, "comment step N"},
      {have_frame, "comment frame I"},            {have_next, "comment next_id K"},   {have_spacing, "comment spacing D"},
      {have_jets, "comment jets J"},              {have_count, "element vertex N"}};
  for (const auto& r : required)
    if (!r.first) refuse(path, std::string("header line \"") + r.second + "\" is missing; not a frame sph_run can continue");
  if (jets_seen != info.jet_travelled.size())
    refuse(path, "the header announces " + std::to_string(info.jet_travelled.size()) + " jets but has " +
                     std::to_string(jets_seen) + " \"comment jet j travelled X\" lines");
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_particles(const Frame& f, const std::string& path) {
  const ParticleState& ps = f.particles;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const char* bad = !finite(ps.pos[i])                                  ? "a non-finite position"
                      : !finite(ps.vel[i])                                ? "a non-finite velocity"
                      : !finite(ps.acc[i])                                ? "a non-finite acceleration"
                      : !(std::isfinite(ps.density[i]) && ps.density[i] > 0.0f) ? "a density that is not positive and finite"
                      : !std::isfinite(ps.pressure[i])                    ? "a non-finite pressure"
                      : !std::isfinite(ps.near_pressure[i])               ? "a non-finite near_pressure"
                      : !std::isfinite(ps.age[i])                         ? "a non-finite age"
                      : ps.id[i] < 0 || ps.id[i] >= f.info.next_id        ? "an id outside [0, next_id)"
                                                                          : nullptr;
    if (bad) refuse(path, "particle " + std::to_string(i) + " (id " + std::to_string(ps.id[i]) + ") has " + bad);
  }
  std::vector<int32_t> ids = ps.id;
  std::sort(ids.begin(), ids.end());
  const auto dup = std::adjacent_find(ids.begin(), ids.end());
  if (dup != ids.end()) refuse(path, "particle id " + std::to_string(*dup) + " occurs more than once");
}

}  // namespace

Frame read_ply_frame(const std::string& path, double max_particles) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) refuse(path, "no such frame file");
  if (!std::filesystem::is_regular_file(path, ec)) refuse(path, "not a regular file; a frame is a .ply file written by sph_run");
  const std::uint64_t file_size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) refuse(path, "cannot open the frame file for reading");
  Frame f;
  f.path = path;
  std::size_t n = 0;
  std::uint64_t start = 0;
  parse_header(header_lines(in, file_size, path, start), path, max_particles, f.info, n);
  const std::uint64_t expected = std::uint64_t(n) * kFrameRecordBytes;
  if (file_size - start != expected) {
    std::ostringstream os;
    os << "the header announces " << n << " particles (" << expected << " bytes) but " << file_size - start
       << " bytes follow it; the file is truncated or not a frame";
    refuse(path, os.str());
  }
  std::vector<char> buf(expected);
  in.seekg(std::streamoff(start));
  if (!in.read(buf.data(), std::streamsize(buf.size()))) refuse(path, "error while reading the particle records");
  ParticleState& ps = f.particles;
  ps.resize(n);
  const char* r = buf.data();
  for (std::size_t i = 0; i < n; ++i) {  // the layout of frame_writer.cpp
    float a[8], b[5];
    std::memcpy(a, r, sizeof a);
    r += sizeof a;
    ps.fluid[i] = uint8_t(*r++);
    std::memcpy(&ps.id[i], r, 4);
    r += 4;
    std::memcpy(b, r, sizeof b);
    r += sizeof b;
    ps.pos[i] = Vec3{a[0], a[1], a[2]};
    ps.vel[i] = ps.vel_force[i] = Vec3{a[3], a[4], a[5]};
    ps.density[i] = a[6];
    ps.pressure[i] = a[7];
    ps.acc[i] = Vec3{b[0], b[1], b[2]};
    ps.age[i] = b[3];
    ps.near_pressure[i] = b[4];
  }
  check_particles(f, path);
  return f;
}

void check_frame_fluids(const Frame& frame, const Scene& scene, const std::string& path) {
  const ParticleState& ps = frame.particles;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.fluid[i] >= scene.fluids.size())
      refuse(path, "particle id " + std::to_string(ps.id[i]) + " is of fluid " + std::to_string(int(ps.fluid[i])) +
                       " but the scene " + scene.source + " has " + std::to_string(scene.fluids.size()) +
                       " fluid(s), indexes 0 to " + std::to_string(scene.fluids.size() - 1));
}

ParticleState initial_state_particles(const Scene& scene, double spacing, int32_t& next_id) {
  const std::string& path = scene.initial_state;
  Frame f;
  try {
    f = read_ply_frame(path, scene.max_particles);
    check_frame_fluids(f, scene, path);
    if (std::fabs(f.info.spacing - spacing) > 1e-9 * spacing) {
      std::ostringstream os;
      os.precision(17);
      os << "written at particle spacing " << f.info.spacing << " m, but the scene's resolution gives " << spacing
         << " m; the particle masses depend on the spacing: make the resolution match";
      refuse(path, os.str());
    }
  } catch (const SceneError& e) {
    throw SceneError(scene.source + ": initial_state: " + e.what());
  }
  ParticleState out;
  for (std::size_t i = 0; i < f.particles.size(); ++i)
    if (f.particles.age[i] >= 0.0f) {
      const std::size_t k = out.size();
      out.resize(k + 1);
      out.copy_particle(k, f.particles, i);
    }
  next_id = std::max(next_id, f.info.next_id);
  return out;
}

}  // namespace sph
