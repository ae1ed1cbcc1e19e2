// The scene loader's reading of one JSON object (scene_loader.cpp, scene_solids.cpp): every key used is
// remembered, the rest rejected, and every error names the file and the key's dotted path. Internal to the
// loader.
#pragma once

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene.h"

namespace sph {
namespace scene_reading {

using json = nlohmann::json;
namespace fs = std::filesystem;

[[noreturn]] inline void fail(const std::string& source, const std::string& key, const std::string& what) {
  throw SceneError(source + ": " + (key.empty() ? std::string() : key + ": ") + what);
}

// Reads the keys of one JSON object, remembers which were used, and rejects the rest.
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string source, std::string path)
      : j_(j), source_(std::move(source)), path_(std::move(path)) {
    if (!j_.is_object()) fail(source_, path_.empty() ? "scene" : path_, "expected a JSON object");
  }

  bool has(const std::string& key) const { return j_.contains(key); }
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const json& raw(const std::string& key) {
    used_.insert(key);
    return j_.at(key);
  }

  double number(const std::string& key, double def, double lo, double hi, bool lo_open = false) {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_number()) fail(source_, key_path(key), "expected a number, got " + std::string(v.type_name()));
    const double x = v.get<double>();
    check_range(key, x, lo, hi, lo_open);
    return x;
  }

  void check_range(const std::string& key, double x, double lo, double hi, bool lo_open) const {
    if (!std::isfinite(x)) fail(source_, key_path(key), "must be a finite number");
    if (x < lo || (lo_open && x == lo) || x > hi) {
      std::ostringstream os;
      os << "value " << x << " is out of range: allowed " << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
      fail(source_, key_path(key), os.str());
    }
  }

  bool boolean(const std::string& key, bool def) {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_boolean()) fail(source_, key_path(key), "expected true or false");
    return v.get<bool>();
  }

  std::string string(const std::string& key, const std::string& def) {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_string()) fail(source_, key_path(key), "expected a string");
    return v.get<std::string>();
  }

  template <class E>
  E choice(const std::string& key, E def, const std::vector<std::pair<std::string, E>>& names) {
    if (!has(key)) return def;
    const std::string s = string(key, "");
    std::string allowed;
    for (const auto& [name, value] : names) {
      if (name == s) return value;
      allowed += (allowed.empty() ? "" : ", ") + ("\"" + name + "\"");
    }
    fail(source_, key_path(key), "unknown name \"" + s + "\"; allowed: " + allowed);
  }

  Vec3d vec3(const std::string& key, Vec3d def, double limit = 1e6) {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_array() || v.size() != 3) fail(source_, key_path(key), "expected an array of 3 numbers");
    Vec3d out{};
    for (int i = 0; i < 3; ++i) {
      if (!v[i].is_number()) fail(source_, key_path(key), "expected an array of 3 numbers");
      out[i] = v[i].get<double>();
      check_range(key, out[i], -limit, limit, false);
    }
    return out;
  }

  // A whole number in [lo, hi].
  long integer(const std::string& key, long def, long lo, long hi) {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_number_integer()) fail(source_, key_path(key), "expected a whole number");
    const long x = v.get<long>();
    if (x < lo || x > hi)
      fail(source_, key_path(key),
           "value " + std::to_string(x) + " is out of range: allowed [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return x;
  }

  Vec3d required_vec3(const std::string& key) {
    if (!has(key)) missing(key, "is required");
    return vec3(key, {});
  }

  // Rejects keys that were never read: a typo must not be silently ignored.
  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (used_.count(it.key()) || it.key() == "comment") continue;
      std::string allowed;
      for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      fail(source_, key_path(it.key()), "unknown key; allowed here: " + allowed);
    }
  }

  void allow(std::initializer_list<const char*> keys) {
    for (const char* k : keys) known_.insert(k);
  }

  // Fails for a required key (or choice of keys) that is missing, naming the keys of this object that are
  // not allowed here: a misspelt required key must be reported as the typo it is.
  [[noreturn]] void missing(const std::string& key, const std::string& what) const {
    std::string unknown;
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!known_.count(it.key()) && it.key() != "comment") unknown += (unknown.empty() ? "\"" : ", \"") + it.key() + "\"";
    fail(source_, key.empty() ? path_ : key_path(key),
         what + (unknown.empty() || known_.empty() ? "" : " (this object has the unknown key " + unknown + ": misspelt?)"));
  }

  const std::string& source() const { return source_; }

 private:
  const json& j_;
  std::string source_;
  std::string path_;
  std::set<std::string> used_;
  std::set<std::string> known_;
};

constexpr double kHuge = 1e6;  // metres, m/s, ...: larger values are taken as mistakes

inline Vec3d normalised(const Vec3d& v, const std::string& source, const std::string& key) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0)) fail(source, key, "must not be the zero vector");
  return {v[0] / n, v[1] / n, v[2] / n};
}

inline void check_box(const Vec3d& lo, const Vec3d& hi, const std::string& source, const std::string& key) {
  for (int i = 0; i < 3; ++i)
    if (!(hi[i] > lo[i])) fail(source, key, "max must be larger than min on every axis");
}

// "solver" and its block, read in scene_solver.cpp: a block for another solver than the one chosen is an
// error (r: the scene's top-level object).
void read_solver(ObjectReader& r, Scene& s);

// The parts of a scene read in scene_solids.cpp: the meshes, the rigid bodies and the probes (r: the scene's
// top-level object).
void read_meshes(ObjectReader& r, Scene& s);
void read_bodies(ObjectReader& r, Scene& s);
void read_probes(ObjectReader& r, Scene& s);

}  // namespace scene_reading
}  // namespace sph
