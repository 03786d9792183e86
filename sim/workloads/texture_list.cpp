#include "workloads/texture_list.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.h"
#include "model/formats.h"
#include "workloads/text.h"
#include "workloads/texture_io.h"

namespace tex {

std::vector<TextureListEntry> read_texture_list(const std::string& path, const SamplerConfig& cfg) {
  std::ifstream f(path, std::ios::binary);
  if (!f || std::filesystem::is_directory(path)) throw Error(path + ": cannot open texture list");
  const std::string form =
      "`id path [wrap_u [wrap_v]] [srgb] [depth] [unnormalized] [min=F] "
      "[mag=F] [mip=M] [border=C] [reduction=R] [compare=OP] [base=N] [max=N]`";
  std::vector<TextureListEntry> out;
  int line_no = 0;
  for (std::string text; read_text_line(f, text, kMaxTextureListLine, path, line_no);) {
    std::istringstream line(text);
    std::string id, file;
    line >> id;
    if (id.empty() || id[0] == '#') continue;
    line >> file;
    const std::string at = path + ":" + std::to_string(line_no) + ": ";
    if (id != std::to_string(out.size()))
      throw Error(at + "texture id " + quote_clipped(id) + ": expected " + std::to_string(out.size()) +
                  " (ids 0, 1, ... in order)");
    if (file.empty()) throw Error(at + "expected " + form);
    TextureListEntry e{file, cfg, false, {}, {}, at};
    // A file relative to the list's directory; a built-in pattern as it is
    // (unless such a file exists).
    const std::filesystem::path beside = std::filesystem::path(path).parent_path() / file;
    bool pattern = false;
    try {
      pattern = is_pattern_spec(file);
    } catch (const Error& e) {  // (a pattern's name with a bad size)
      throw Error(at + e.what());
    }
    if (std::filesystem::path(file).is_relative() && (!pattern || std::filesystem::exists(beside)))
      e.path = beside.string();
    int wraps = 0;
    for (std::string token; line >> token;) {
      const size_t eq = token.find('=');
      if (eq == std::string::npos) {
        if (token == "srgb" && !e.srgb) {
          e.srgb = true;
        } else if (token == "depth" && !e.depth) {
          e.depth = true;
        } else if (token == "unnormalized" && !e.sampler.unnormalized) {
          e.sampler.unnormalized = true;
        } else if (wraps < 2 && !e.srgb && !e.sampler.unnormalized) {
          Wrap& w = wraps == 0 ? e.sampler.wrap_u : e.sampler.wrap_v;
          if (!parse_wrap(token, w))
            throw Error(at + "unknown wrap mode " + quote_clipped(token) + " (" + kWrapNames + ")");
          if (wraps++ == 0) e.sampler.wrap_v = w;  // one mode: both axes
        } else {
          throw Error(at + "unexpected " + quote_clipped(token) + " (" + form + ")");
        }
        continue;
      }
      const std::string key = token.substr(0, eq), value = token.substr(eq + 1);
      Filter& fl = e.sampler.filter;
      if (key == "min") {
        std::optional<MipMode> mip;
        if (!parse_min_filter(value, fl.texel, mip))
          throw Error(at + "min=" + quote_clipped(value) +
                      ": not a minification filter (nearest, linear, or a GL name)");
        if (mip) fl.mip = *mip;
      } else if (key == "mag") {
        if (!parse_texel_filter(value, fl.mag))
          throw Error(at + "mag=" + quote_clipped(value) + ": not nearest or linear");
      } else if (key == "mip") {
        if (!parse_mip_mode(value, fl.mip))
          throw Error(at + "mip=" + quote_clipped(value) + ": not none, nearest or linear");
      } else if (key == "border") {
        if (!parse_border_color(value, e.sampler.border))
          throw Error(at + "border=" + quote_clipped(value) + ": not a border colour name (transparent-black, ...)");
      } else if (key == "reduction") {
        if (!parse_reduction(value, e.sampler.reduction))
          throw Error(at + "reduction=" + quote_clipped(value) + ": not weighted-average, min or max");
      } else if (key == "compare") {
        if (!parse_compare_op(value, e.sampler.compare_op))
          throw Error(at + "compare=" + quote_clipped(value) + ": not " + kCompareOpNames);
      } else if (key == "base" || key == "max") {
        int level = -1;
        size_t used = 0;
        try {
          level = std::stoi(value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != value.size() || level < 0 || level >= kMaxLevels)
          throw Error(at + key + "=" + quote_clipped(value) + ": not a level 0 to " + std::to_string(kMaxLevels - 1));
        (key == "base" ? e.base_level : e.max_level) = level;
      } else {
        throw Error(at + "unknown field " + quote_clipped(key) +
                    " (min, mag, mip, border, reduction, compare, base, max)");
      }
    }
    check_sampler(e.sampler, at);
    if (out.size() == size_t(kMaxTextures))
      throw Error(at + "more than " + std::to_string(kMaxTextures) + " textures: the descriptor table holds " +
                  std::to_string(kMaxTextures));
    out.push_back(e);
  }
  if (out.empty()) throw Error(path + ": no textures listed (one " + form + " per line)");
  return out;
}

}  // namespace tex
