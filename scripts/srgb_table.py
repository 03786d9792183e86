#!/usr/bin/env python3
"""Writes rtl/tex_srgb_decode.sv, whose ROM is round(65535 * L(c / 255)) for c = 0..255 with GL 4.6
§8.24's sRGB decode L(x) = x / 12.92 for x <= 0.04045, else ((x + 0.055) / 1.055) ** 2.4: the
model's srgb_decode_table (model/srgb.h); the RTL test compares the two.

Usage: /usr/bin/python3 scripts/srgb_table.py > rtl/tex_srgb_decode.sv
"""
import math
import sys

HEAD = """// tex_srgb_decode: one channel of an sRGB texel to linear (docs/numerics.md "sRGB"): the model's
// 256-entry table srgb_decode_table() (model/srgb.h), round(65535 * L(code / 255)) with GL 4.6
// §8.24's L, as a ROM. R, G and B of each of a sample's 8 texels go through it before the filter;
// alpha is linear (widened as code * 257 beside it). The entries are the definition's values,
// written by scripts/srgb_table.py; tests/rtl/test_rtl_block_decode.cpp compares all 256 with the
// model's table. A function, not a module: tex_tap_select calls it only for sRGB textures' taps,
// so that a simulator spends nothing on it in the other clocks.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call (24 calls per clock).
// linear(code):
//   code   : unsigned 8 bits, an sRGB code value (0..255 = 0..1 encoded)
//   result : unsigned 16 bits, unorm16 linear value (0..65535 = 0..1)
package tex_srgb_decode;
  function automatic logic [15:0] linear(input logic [7:0] code);
    /*verilator no_inline_task*/  // (one C++ function: 24 channels call it)
    case (code)
"""
TAIL = """      default: linear = 16'd0;
    endcase
  endfunction
endpackage
"""


def linear(code):
    x = code / 255
    return x / 12.92 if x <= 0.04045 else ((x + 0.055) / 1.055) ** 2.4


def main():
    if len(sys.argv) > 1:
        print(__doc__)
        return
    sys.stdout.write(HEAD)
    for c in range(256):
        sys.stdout.write(f"      8'd{c}: linear = 16'd{math.floor(65535 * linear(c) + 0.5)};\n")
    sys.stdout.write(TAIL)


if __name__ == "__main__":
    main()
