#include "formats.h"

#include <cmath>

namespace tex {

namespace {
struct FilterName {
  const char* name;
  Filter filter;
};
constexpr FilterName kFilterNames[] = {
    {"point", {TexelFilter::Nearest, MipMode::None}},
    {"bilinear", {TexelFilter::Linear, MipMode::None}},
    {"mip_nearest", {TexelFilter::Linear, MipMode::Nearest}},
    {"trilinear", {TexelFilter::Linear, MipMode::Linear}},
    {"anisotropic", {TexelFilter::Linear, MipMode::Linear, true}},
    {"nearest", {TexelFilter::Nearest, MipMode::None}},
    {"linear", {TexelFilter::Linear, MipMode::None}},
    {"nearest_mipmap_nearest", {TexelFilter::Nearest, MipMode::Nearest}},
    {"linear_mipmap_nearest", {TexelFilter::Linear, MipMode::Nearest}},
    {"nearest_mipmap_linear", {TexelFilter::Nearest, MipMode::Linear}},
    {"linear_mipmap_linear", {TexelFilter::Linear, MipMode::Linear}},
};

}  // namespace

bool parse_filter(const std::string& name, Filter& out) {
  for (const auto& f : kFilterNames)
    if (name == f.name) {
      out = f.filter;
      return true;
    }
  return false;
}

std::string filter_name(Filter f) {
  for (const auto& n : kFilterNames)
    if (n.filter == f) return n.name;  // the first (short) name wins
  return "?";
}

bool parse_wrap(const std::string& name, Wrap& out) {
  if (name == "repeat") out = Wrap::Repeat;
  else if (name == "clamp") out = Wrap::Clamp;
  else if (name == "mirror") out = Wrap::Mirror;
  else return false;
  return true;
}

std::string wrap_name(Wrap w) {
  switch (w) {
    case Wrap::Repeat: return "repeat";
    case Wrap::Clamp: return "clamp";
    case Wrap::Mirror: return "mirror";
  }
  return "?";
}

bool parse_pyramid_mode(const std::string& name, PyramidMode& out) {
  if (name == "exact") out = PyramidMode::Exact;
  else if (name == "cascade") out = PyramidMode::Cascade;
  else return false;
  return true;
}


}  // namespace tex
