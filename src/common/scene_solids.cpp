// The scene's solids and gauges: triangle meshes, rigid bodies and water-height probes (scene.h), read as
// the rest of the scene is (scene_reader.h).
#include <algorithm>
#include <cctype>

#include "scene_reader.h"

namespace sph {
namespace scene_reading {

namespace {

// A mesh's "file" (an OBJ, resolved against the scene file's folder), "scale" (a number or one per axis) and
// "translate", for the scene's meshes and for mesh bodies.
void read_mesh_placement(ObjectReader& mr, const std::string& source, std::string& file, Vec3d& scale, Vec3d& translate) {
  if (!mr.has("file")) mr.missing("file", "is required: the path of an OBJ file, relative to the scene file");
  const fs::path p = mr.string("file", "");
  std::string extension = p.extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (p.empty() || extension != ".obj")
    fail(source, mr.key_path("file"), "expected the path of a Wavefront OBJ file (.obj), not \"" + p.string() + "\"");
  file = (p.is_absolute() ? p : fs::path(source).parent_path() / p).string();
  if (mr.has("scale") && mr.raw("scale").is_number()) {
    const double k = mr.number("scale", 1.0, 0.0, 1e6, true);
    scale = {k, k, k};
  } else {
    scale = mr.vec3("scale", scale);
    for (const double k : scale)
      if (!(k > 0.0)) fail(source, mr.key_path("scale"), "expected a positive number or three positive numbers");
  }
  translate = mr.vec3("translate", translate);
}

}  // namespace

void read_meshes(ObjectReader& r, Scene& s) {
  const std::string& source = s.source;
  if (r.has("meshes")) {
    const json& ms = r.raw("meshes");
    if (!ms.is_array()) fail(source, "meshes", "expected a list of mesh objects ({\"file\": \"model.obj\", ...})");
    for (std::size_t i = 0; i < ms.size(); ++i) {
      ObjectReader mr(ms[i], source, "meshes." + std::to_string(i));
      mr.allow({"file", "inside", "scale", "translate", "slip"});
      MeshSpec m;
      read_mesh_placement(mr, source, m.file, m.scale, m.translate);
      m.inside = mr.boolean("inside", false);
      m.slip = mr.number("slip", 1.0, 0.0, 1.0);
      mr.finish();
      s.meshes.push_back(m);
    }
  }
}

void read_bodies(ObjectReader& r, Scene& s) {
  const std::string& source = s.source;
  if (r.has("bodies")) {
    const json& bs = r.raw("bodies");
    if (!bs.is_array()) fail(source, "bodies", "expected a list of body objects ({\"type\": \"box\", ...})");
    for (std::size_t i = 0; i < bs.size(); ++i) {
      ObjectReader br(bs[i], source, "bodies." + std::to_string(i));
      BodySpec b;
      const int shape = br.choice<int>("type", 0, {{"box", 0}, {"sphere", 1}, {"mesh", 2}});
      if (!br.has("type")) br.missing("type", "is required (\"box\", \"sphere\" or \"mesh\")");
      b.sphere = shape == 1;
      b.mesh = shape == 2;
      if (b.mesh) {
        br.allow({"type", "file", "scale", "translate", "density", "mass", "motion", "slip", "oscillation"});
        read_mesh_placement(br, source, b.file, b.scale, b.translate);
      } else if (b.sphere) {
        br.allow({"type", "center", "radius", "density", "mass", "motion", "slip", "oscillation"});
        b.center = br.required_vec3("center");
        if (!br.has("radius")) br.missing("radius", "is required");
        b.radius = br.number("radius", 0.0, 0.0, kHuge, true);
      } else {
        br.allow({"type", "min", "max", "density", "mass", "motion", "slip", "oscillation"});
        b.min = br.required_vec3("min");
        b.max = br.required_vec3("max");
        check_box(b.min, b.max, source, br.key_path("max"));
      }
      if (br.has("density") == br.has("mass")) br.missing("density", "give exactly one of density [kg/m^3] and mass [kg]");
      b.density = br.number("density", 0.0, 0.0, 1e6, true);
      b.mass = br.number("mass", 0.0, 0.0, 1e9, true);
      const int motion = br.choice<int>("motion", 0, {{"free", 0}, {"fixed", 1}, {"prescribed", 2}});
      b.free = motion == 0;
      b.prescribed = motion == 2;
      if (b.prescribed != br.has("oscillation"))
        br.missing("oscillation", "goes with \"motion\": \"prescribed\" and only with it: {\"amplitude\": [x, y, z] (m), "
                                  "\"period\": s} for a piston, {\"angle\": degrees, \"axis\": [x, y, z], \"pivot\": [x, y, z] (m), "
                                  "\"period\": s} for a flap, or both");
      if (b.prescribed) {
        ObjectReader orr(br.raw("oscillation"), source, br.key_path("oscillation"));
        orr.allow({"amplitude", "period", "angle", "axis", "pivot"});
        if (!orr.has("amplitude") && !orr.has("angle"))
          orr.missing("amplitude", "give a translation amplitude [x, y, z] (m), a rotation angle (degrees) with its axis and pivot, or both");
        b.amplitude = orr.vec3("amplitude", b.amplitude);
        if (!orr.has("period")) orr.missing("period", "is required (seconds)");
        b.period = orr.number("period", 1.0, 0.0, 1e6, true);
        if (orr.has("angle")) {
          b.angle = orr.number("angle", 0.0, -180.0, 180.0) * 3.14159265358979323846 / 180.0;
          if (!orr.has("axis") || !orr.has("pivot"))
            orr.missing(orr.has("axis") ? "pivot" : "axis", "a rotation needs its axis (a direction) and pivot (a point the axis runs through, m)");
          const Vec3d axis = orr.required_vec3("axis");
          const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
          if (!(len > 0.0)) fail(source, orr.key_path("axis"), "expected a non-zero direction");
          b.axis = {axis[0] / len, axis[1] / len, axis[2] / len};
          b.pivot = orr.required_vec3("pivot");
        } else if (orr.has("axis") || orr.has("pivot")) {
          orr.missing("angle", "axis and pivot describe a rotation: give its angle (degrees) too");
        }
        orr.finish();
      }
      b.slip = br.number("slip", 1.0, 0.0, 1.0);
      br.finish();
      s.bodies.push_back(b);
    }
  }
}

void read_probes(ObjectReader& r, Scene& s) {
  const std::string& source = s.source;
  if (r.has("probes")) {  // water-height gauges: columns depth_<name> of metrics.csv
    const json& ps = r.raw("probes");
    if (!ps.is_array() || ps.size() > 64)
      fail(source, "probes", "expected a list of at most 64 probes ({\"name\": \"H1\", \"position\": [x, y, z]})");
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ObjectReader pr(ps[i], source, "probes." + std::to_string(i));
      pr.allow({"name", "position"});
      ProbeSpec p;
      if (!pr.has("name")) pr.missing("name", "is required: letters, digits and '_' (the metrics.csv column is depth_<name>)");
      p.name = pr.string("name", "");
      const bool word = !p.name.empty() && p.name.size() <= 32 &&
                        std::all_of(p.name.begin(), p.name.end(), [](char ch) {
                          return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                        });
      if (!word) fail(source, pr.key_path("name"), "\"" + p.name + "\" is not a name: allowed 1 to 32 letters, digits and '_'");
      for (const ProbeSpec& q : s.probes)
        if (q.name == p.name) fail(source, pr.key_path("name"), "\"" + p.name + "\" names two probes");
      p.position = pr.required_vec3("position");
      pr.finish();
      s.probes.push_back(p);
    }
  }
}

}  // namespace scene_reading
}  // namespace sph
