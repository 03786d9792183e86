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

// Lower case, '-' as '_', without a GL_ or VK_..._ prefix: the key the names below are matched on.
static std::string name_key(std::string name, const char* vk_prefix) {
  for (char& c : name) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    if (c == '-') c = '_';
  }
  auto strip = [&](const std::string& prefix) {
    if (name.compare(0, prefix.size(), prefix) == 0) name.erase(0, prefix.size());
  };
  strip("gl_");
  strip(vk_prefix);
  return name;
}

bool parse_filter(const std::string& name, Filter& out) {
  const std::string key = name_key(name, "");
  for (const auto& f : kFilterNames)
    if (key == f.name) {
      out = f.filter;
      return true;
    }
  return false;
}

std::string filter_name(Filter f) {
  const TexelFilter mag = f.mag;
  f.mag = f.texel;
  std::string name = "?";
  for (const auto& n : kFilterNames)
    if (n.filter == f) {
      name = n.name;  // the first (short) name wins
      break;
    }
  return mag == f.texel ? name : name + "/mag-" + texel_filter_name(mag);
}

bool parse_texel_filter(const std::string& name, TexelFilter& out) {
  const std::string k = name_key(name, "vk_filter_");
  if (k == "nearest") out = TexelFilter::Nearest;
  else if (k == "linear") out = TexelFilter::Linear;
  else return false;
  return true;
}

std::string texel_filter_name(TexelFilter f) { return f == TexelFilter::Nearest ? "nearest" : "linear"; }

bool parse_min_filter(const std::string& name, TexelFilter& texel, std::optional<MipMode>& mip) {
  if (parse_texel_filter(name, texel)) return true;
  Filter gl;
  if (!parse_filter(name, gl) || name_key(name, "").find("mipmap") == std::string::npos) return false;
  texel = gl.texel;
  mip = gl.mip;
  return true;
}

std::string mip_mode_name(MipMode m) {
  return m == MipMode::None ? "none" : m == MipMode::Nearest ? "nearest" : "linear";
}

bool parse_mip_mode(const std::string& name, MipMode& out) {
  const std::string k = name_key(name, "vk_sampler_mipmap_mode_");
  if (k == "none") out = MipMode::None;
  else if (k == "nearest") out = MipMode::Nearest;
  else if (k == "linear") out = MipMode::Linear;
  else return false;
  return true;
}

bool parse_wrap(const std::string& name, Wrap& out) {
  const std::string k = name_key(name, "vk_sampler_address_mode_");
  if (k == "repeat") out = Wrap::Repeat;
  else if (k == "clamp" || k == "clamp_to_edge") out = Wrap::Clamp;
  else if (k == "mirror" || k == "mirrored_repeat") out = Wrap::Mirror;
  else if (k == "border" || k == "clamp_to_border") out = Wrap::Border;
  else if (k == "mirror_clamp" || k == "mirror_clamp_to_edge") out = Wrap::MirrorClamp;
  else return false;
  return true;
}

std::string wrap_name(Wrap w) {
  switch (w) {
    case Wrap::Repeat: return "repeat";
    case Wrap::Clamp: return "clamp";
    case Wrap::Mirror: return "mirror";
    case Wrap::Border: return "border";
    case Wrap::MirrorClamp: return "mirror-clamp";
  }
  return "?";
}

namespace {
constexpr const char* kBorderNames[kBorderColors] = {
    "transparent-black", "int-transparent-black", "opaque-black", "int-opaque-black",
    "opaque-white",      "int-opaque-white",      "custom"};
}

bool parse_border_color(const std::string& name, BorderColor& out) {
  std::string k = name_key(name, "vk_border_color_");
  if (k.compare(0, 6, "float_") == 0) k.erase(0, 6);
  for (int i = 0; i < kBorderColors - 1; ++i)  // (custom is given as r,g,b,a)
    if (k == name_key(kBorderNames[i], "")) {
      out = BorderColor(i);
      return true;
    }
  return false;
}

std::string border_color_name(BorderColor b) { return int(b) < kBorderColors ? kBorderNames[int(b)] : "?"; }

constexpr const char* kReductionNames[kReductions] = {"weighted-average", "min", "max"};

bool parse_reduction(const std::string& name, Reduction& out) {
  const std::string n = name_key(name, "vk_sampler_reduction_mode_");
  for (int i = 0; i < kReductions; ++i)
    if (n == name_key(kReductionNames[i], "")) {
      out = Reduction(i);
      return true;
    }
  return false;
}

std::string reduction_name(Reduction r) { return int(r) < kReductions ? kReductionNames[int(r)] : "?"; }

bool parse_op(const std::string& name, Op& out) {
  const std::string n = name_key(name, "");
  if (n == "sample") out = Op::Sample;
  else if (n == "gather" || n == "texturegather") out = Op::Gather;
  else if (n == "compare" || n == "dref") out = Op::Compare;
  else if (n == "fetch" || n == "texelfetch") out = Op::Fetch;
  else return false;
  return true;
}

std::string op_name(Op op) {
  switch (op) {
    case Op::Sample: return "sample";
    case Op::Gather: return "gather";
    case Op::Compare: return "compare";
    case Op::Fetch: return "fetch";
  }
  return "?";
}

namespace {
constexpr const char* kCompareNames[kCompareOps] = {"never",   "less",      "equal",            "less-or-equal",
                                                    "greater", "not-equal", "greater-or-equal", "always"};
constexpr const char* kGlCompareNames[kCompareOps] = {"never",   "less",     "equal",  "lequal",
                                                      "greater", "notequal", "gequal", "always"};
}  // namespace

bool parse_compare_op(const std::string& name, CompareOp& out) {
  const std::string n = name_key(name, "vk_compare_op_");
  for (int i = 0; i < kCompareOps; ++i)
    if (n == name_key(kCompareNames[i], "") || n == kGlCompareNames[i]) {
      out = CompareOp(i);
      return true;
    }
  return false;
}

std::string compare_op_name(CompareOp op) { return int(op) < kCompareOps ? kCompareNames[int(op)] : "?"; }

bool parse_pyramid_mode(const std::string& name, PyramidMode& out) {
  if (name == "exact") out = PyramidMode::Exact;
  else if (name == "cascade") out = PyramidMode::Cascade;
  else return false;
  return true;
}


}  // namespace tex
