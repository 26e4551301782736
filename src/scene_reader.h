// The scene reader's tools (scene.cpp, scene_joints.cpp): JSON objects read field by
// field, each broken rule thrown as a SceneError that names the field and the limit.
#pragma once

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>

#include "scene.h"

namespace rigid::scene_reader {

using json = nlohmann::json;

inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
  throw SceneError(path + ": " + what);
}

inline std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

inline bool isIdentifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

// Reads the fields of one JSON object; every key it does not know is refused, so that
// a misspelt field is reported instead of silently taking its default (an empty list
// of known keys reads an object whose keys were checked before).
class Object {
 public:
  Object(const json& j, std::string path, std::initializer_list<const char*> known) : j_(j), path_(std::move(path)) {
    if (!j.is_object()) fail(path_.empty() ? "scene" : path_, "must be a JSON object");
    if (known.size() == 0) return;  // fields already checked by another reader
    std::set<std::string> allowed(known.begin(), known.end());
    for (const auto& item : j.items()) {
      if (!allowed.count(item.key())) {
        std::string list;
        for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
        fail(join(path_, item.key()), "unknown field (known: " + list + ")");
      }
    }
  }

  bool has(const char* key) const { return j_.contains(key); }
  const json& at(const char* key) const { return j_.at(key); }
  std::string path(const char* key) const { return join(path_, key); }

  double number(const char* key, const double* fallback = nullptr) const {
    if (!has(key)) {
      if (fallback) return *fallback;
      fail(path(key), "is required");
    }
    return toNumber(at(key), path(key));
  }
  double number(const char* key, double fallback) const { return number(key, &fallback); }

  std::string string(const char* key, const char* fallback = nullptr) const {
    if (!has(key)) {
      if (fallback) return fallback;
      fail(path(key), "is required");
    }
    if (!at(key).is_string()) fail(path(key), "must be a string");
    return at(key).get<std::string>();
  }

  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_boolean()) fail(path(key), "must be true or false");
    return at(key).get<bool>();
  }

  Eigen::VectorXd vector(const char* key, int n, const Eigen::VectorXd& fallback) const {
    if (!has(key)) return fallback;
    return toVector(at(key), path(key), n);
  }
  Vec3 vec3(const char* key, const Vec3& fallback) const { return vector(key, 3, fallback); }

  static double toNumber(const json& v, const std::string& path) {
    if (!v.is_number()) fail(path, "must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(path, "must be finite, got " + num(x));
    return x;
  }

  static Eigen::VectorXd toVector(const json& v, const std::string& path, int n) {
    if (!v.is_array() || static_cast<int>(v.size()) != n)
      fail(path, "must be an array of " + std::to_string(n) + " numbers");
    Eigen::VectorXd out(n);
    for (int i = 0; i < n; ++i) out[i] = toNumber(v[i], path + "[" + std::to_string(i) + "]");
    return out;
  }

 private:
  const json& j_;
  std::string path_;
};

inline double positive(const Object& o, const char* key, const double* fallback = nullptr) {
  const double v = o.number(key, fallback);
  if (!(v > 0.0)) fail(o.path(key), "must be > 0, got " + num(v));
  return v;
}

inline double inRange(const Object& o, const char* key, double fallback, double lo, double hi) {
  const double v = o.number(key, fallback);
  if (v < lo || v > hi) fail(o.path(key), "must be in [" + num(lo) + ", " + num(hi) + "], got " + num(v));
  return v;
}

inline std::string identifier(const Object& o, const char* key, const char* fallback = nullptr) {
  const std::string s = o.string(key, fallback);
  if (!isIdentifier(s)) fail(o.path(key), "must be a C identifier ([A-Za-z_][A-Za-z0-9_]*), got \"" + s + "\"");
  return s;
}

inline Quat unitQuaternion(const Object& o, const char* key) {
  const Eigen::VectorXd v = o.vector(key, 4, Eigen::Vector4d(1, 0, 0, 0));
  const double norm = v.norm();
  if (std::abs(norm - 1.0) > 1e-6)
    fail(o.path(key), "must be a unit quaternion (w, x, y, z) within 1e-6, got |q| = " + num(norm));
  return Quat(v[0], v[1], v[2], v[3]).normalized();
}

// The scene's "joints" (scene_joints.cpp), after its bodies: each joint's bodies by
// name, its anchors and axes at their start poses.
void readJoints(const Object& scene, Scene& out);

}  // namespace rigid::scene_reader
