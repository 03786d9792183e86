#include "workloads/astc_encode.h"

#include <astcenc.h>

#include <memory>
#include <string>

#include "model/error.h"

namespace tex {

std::vector<uint8_t> encode_astc_level(const Image& level, TexelFormat format, bool srgb) {
  if (!is_astc(format)) throw Error(std::string("encode_astc_level: ") + format_info(format).name + " is not ASTC");
  const FormatInfo& info = format_info(format);
  auto check = [&](astcenc_error e, const char* step) {
    if (e != ASTCENC_SUCCESS)
      throw Error(std::string("--format ") + info.name + ": astcenc " + step + ": " + astcenc_get_error_string(e));
  };
  astcenc_config config;
  check(astcenc_config_init(srgb ? ASTCENC_PRF_LDR_SRGB : ASTCENC_PRF_LDR, unsigned(info.block_w),
                            unsigned(info.block_h), 1, ASTCENC_PRE_FAST, 0, &config),
        "configuration");
  astcenc_context* raw = nullptr;
  check(astcenc_context_alloc(&config, 1, &raw), "context");
  const std::unique_ptr<astcenc_context, void (*)(astcenc_context*)> context(raw, astcenc_context_free);
  std::vector<uint8_t> rgba(size_t(level.width) * size_t(level.height) * 4);
  for (size_t i = 0; i < level.texels.size(); ++i)
    for (size_t c = 0; c < 4; ++c) rgba[i * 4 + c] = uint8_t(level.texels[i][c]);
  void* planes[1] = {rgba.data()};
  astcenc_image image{unsigned(level.width), unsigned(level.height), 1, ASTCENC_TYPE_U8, planes};
  const astcenc_swizzle identity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
  std::vector<uint8_t> blocks(level_bytes(format, level.width, level.height));
  check(astcenc_compress_image(context.get(), &image, &identity, blocks.data(), blocks.size(), 0), "compression");
  return blocks;
}

}  // namespace tex
