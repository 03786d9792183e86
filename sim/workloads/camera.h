// The camera of real frames (docs/scenes.md): OpenGL conventions, right-handed, up = +y, the view of
// gluLookAt(eye, target, up) and the projection of gluPerspective(fovy, aspect, near, far).
#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace tex {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 1.0}, target{0.0};
  double fovy_deg = 45.0;  // vertical field of view, degrees, in (0, 180)
};

// The clip-space transform projection * view for a frame of `aspect` = width / height. near and far
// enclose the bounding box [lo, hi] (near at least far / 10000, so a camera inside the box works).
glm::dmat4 view_projection(const Camera& c, double aspect, const glm::dvec3& lo, const glm::dvec3& hi);

// "ex,ey,ez,tx,ty,tz,fovy": throws tex::Error naming the bad value (7 finite numbers, eye != target,
// the view direction not parallel to +y, 0 < fovy < 180).
Camera parse_camera(const std::string& text);

// The default camera: frame `frame` of `frames` positions on an orbit around the bounding box,
// 20 degrees above it, starting 30 degrees to the right of +z, framing the whole box.
Camera orbit_camera(const glm::dvec3& lo, const glm::dvec3& hi, double aspect, int frame, int frames);

// --camera-path: JSON {"keyframes": [{"eye": [x,y,z], "target": [x,y,z], "fovy": deg}, ...]}, at
// least one keyframe. Throws tex::Error naming the file and the bad key or value.
std::vector<Camera> read_camera_path(const std::string& path);
// Frame `frame` of `frames`: keyframes spread evenly over the frames, eye, target and fovy
// interpolated linearly between the two around it.
Camera camera_on_path(const std::vector<Camera>& keys, int frame, int frames);

}  // namespace tex
