#include "workloads/camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "model/error.h"
#include "workloads/limits.h"
#include "workloads/text.h"

namespace tex {

namespace {

// The view direction must not be parallel to up = +y (gluLookAt has no defined roll there).
bool usable_view(const glm::dvec3& eye, const glm::dvec3& target) {
  const glm::dvec3 d = target - eye;
  const double len = glm::length(d);
  return len > 0 && std::isfinite(len) && glm::length(glm::cross(d / len, glm::dvec3(0, 1, 0))) > 1e-9;
}

}  // namespace

glm::dmat4 view_projection(const Camera& c, double aspect, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double radius = std::max(glm::length(hi - lo) * 0.5, 1e-9);
  const double dist = glm::length(centre - c.eye);
  const double far = (dist + radius) * 1.01;
  const double near = std::max(dist - radius, far / 10000.0);
  const glm::dmat4 view = glm::lookAt(c.eye, c.target, glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspective(glm::radians(c.fovy_deg), aspect, near, far);
  return proj * view;
}

Camera parse_camera(const std::string& text) {
  double v[7];
  std::string_view rest = text;
  for (int i = 0; i < 7; ++i) {
    const size_t comma = rest.find(',');
    const std::string_view field = rest.substr(0, comma);
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v[i]);
    if (field.empty() || ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v[i]))
      throw Error("--camera " + quote_clipped(text) + ": value " + std::to_string(i + 1) + " " +
                  quote_clipped(field) + " is not a finite number (ex,ey,ez,tx,ty,tz,fovy)");
    if ((comma == std::string_view::npos) != (i == 6))
      throw Error("--camera " + quote_clipped(text) + ": expected 7 values ex,ey,ez,tx,ty,tz,fovy");
    rest.remove_prefix(comma == std::string_view::npos ? rest.size() : comma + 1);
  }
  Camera c{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]};
  if (!(c.fovy_deg > 0 && c.fovy_deg < 180))
    throw Error("--camera " + quote_clipped(text) + ": fovy " + std::to_string(c.fovy_deg) + " is outside (0, 180) degrees");
  if (!usable_view(c.eye, c.target))
    throw Error("--camera " + quote_clipped(text) + ": the eye must differ from the target and not look straight up or down");
  return c;
}

Camera orbit_camera(const glm::dvec3& lo, const glm::dvec3& hi, double aspect, int frame, int frames) {
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double radius = std::max(glm::length(hi - lo) * 0.5, 1e-9);
  Camera c;
  c.fovy_deg = 45.0;
  // The bounding sphere fits the narrower of the two fields of view, with a 5% margin.
  const double half_y = glm::radians(c.fovy_deg) / 2, half_x = std::atan(std::tan(half_y) * aspect);
  const double dist = 1.05 * radius / std::sin(std::min(half_x, half_y));
  const double azimuth = glm::radians(30.0 + 360.0 * frame / std::max(frames, 1));
  const double elevation = glm::radians(20.0);
  c.target = centre;
  c.eye = centre + dist * glm::dvec3(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                     std::cos(elevation) * std::cos(azimuth));
  return c;
}

std::vector<Camera> read_camera_path(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open camera path");
  check_json_memory(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_object() || !j.contains("keyframes") || !j["keyframes"].is_array() || j["keyframes"].empty())
    throw Error(path + ": expected {\"keyframes\": [{\"eye\": [x,y,z], \"target\": [x,y,z], \"fovy\": deg}, ...]}");
  std::vector<Camera> keys;
  for (size_t i = 0; i < j["keyframes"].size(); ++i) {
    const nlohmann::json& k = j["keyframes"][i];
    const std::string at = path + ": keyframe " + std::to_string(i) + ": ";
    if (!k.is_object()) throw Error(at + "not an object");
    for (const auto& [key, value] : k.items())
      if (key != "eye" && key != "target" && key != "fovy") throw Error(at + "unknown key " + quote_clipped(key));
    auto vec3 = [&](const char* key) {
      if (!k.contains(key)) throw Error(at + "missing \"" + key + "\"");
      const nlohmann::json& a = k[key];
      if (!a.is_array() || a.size() != 3) throw Error(at + "\"" + key + "\" is not [x, y, z]");
      glm::dvec3 out;
      for (int c = 0; c < 3; ++c) {
        if (!a[c].is_number() || !std::isfinite(a[c].get<double>()))
          throw Error(at + "\"" + key + "\"[" + std::to_string(c) + "] is not a finite number");
        out[c] = a[c].get<double>();
      }
      return out;
    };
    Camera c;
    c.eye = vec3("eye");
    c.target = vec3("target");
    if (k.contains("fovy")) {
      if (!k["fovy"].is_number() || !(k["fovy"].get<double>() > 0 && k["fovy"].get<double>() < 180))
        throw Error(at + "\"fovy\" is not a number in (0, 180) degrees");
      c.fovy_deg = k["fovy"].get<double>();
    }
    if (!usable_view(c.eye, c.target))
      throw Error(at + "the eye must differ from the target and not look straight up or down");
    keys.push_back(c);
  }
  return keys;
}

Camera camera_on_path(const std::vector<Camera>& keys, int frame, int frames) {
  if (keys.size() == 1 || frames <= 1) return keys.front();
  const double t = double(frame) / (frames - 1) * double(keys.size() - 1);
  const size_t i = std::min(size_t(t), keys.size() - 2);
  const double f = t - double(i);
  const Camera &a = keys[i], &b = keys[i + 1];
  return Camera{a.eye + (b.eye - a.eye) * f, a.target + (b.target - a.target) * f,
                a.fovy_deg + (b.fovy_deg - a.fovy_deg) * f};
}

}  // namespace tex
