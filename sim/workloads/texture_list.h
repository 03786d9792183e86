// Texture lists (texsim sample --textures FILE): one descriptor-table entry and its sampler per line.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "model/sampler.h"

namespace tex {

// One line of a texture list: `id path [wrap_u [wrap_v]] [srgb] [depth] [unnormalized] [min=F]
// [mag=F] [mip=M] [border=C] [reduction=R] [compare=OP] [base=N] [max=N]` (ids 0, 1, ... in order;
// paths relative to the list's folder, built-in patterns as they are; `srgb`: the texels are sRGB
// codes; `depth`: a depth texture, its R the depth (what --op compare reads); `unnormalized`: the
// sampler takes texel coordinates, the trace's u, v of this entry are texels). Line t is texture t
// of the descriptor table and sampler t of the sampler table: the options' sampler with the line's
// wrap modes and fields (min: nearest | linear | a GL minification name; mag: nearest | linear;
// mip: none | nearest | linear; border: a border colour name), the texture's view from
// --base-level and --max-level or the line's base= and max=.
struct TextureListEntry {
  std::string path;
  SamplerConfig sampler;
  bool srgb = false;
  std::optional<int> base_level, max_level;
  std::string at;  // "FILE:LINE: " of the line (errors of its fields found later)
  bool depth = false;  // a depth texture (the line's `depth`)
};

// Lines longer than this are refused (a list line is a path and a few fields).
constexpr size_t kMaxTextureListLine = 4096;

// Reads a texture list, each entry's sampler `sampler` with the line's fields. `#` lines are
// comments, blank lines are skipped. Throws tex::Error, one line naming the file, the line number
// and the bad field: an id out of order, an unknown word or field value, a sampler the unit does
// not take, more than kMaxTextures lines, a line longer than kMaxTextureListLine, a NUL byte, no
// entries at all.
std::vector<TextureListEntry> read_texture_list(const std::string& path, const SamplerConfig& sampler);

}  // namespace tex
