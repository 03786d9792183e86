// tex_astc: one texel of an ASTC LDR 2D block of any footprint (4x4 .. 12x12), as the model's
// astc_texel16 / astc_unorm8 (model/astc.h, docs/numerics.md "ASTC") decode it, bit for bit. The
// stages have the model's names: block mode, configuration, data size, integer sequence,
// unquantization, endpoints, infill, partition, weight application, void extent. Functions, as
// tex_etc2's, so that a caller spends nothing on them in the clocks that read no ASTC texel (also
// tested alone through rtl/synth/tex_astc_top.sv). A texel needs only its own: the 4 grid weights
// around it (8 with dual plane) and its partition's endpoint values (up to 8 of 18), each pulled
// out of its integer sequence at a variable bit position.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call.
// texel(block, fw, fh, x, y, srgb) -> rgba:
//   block  : 128 bits, byte i at bits 8i+7..8i
//   fw, fh : the footprint, 4..12 (one of the 14 of the LDR profile)
//   x, y   : the texel in the block, 0..fw-1, 0..fh-1
//   srgb   : the texture is sRGB (endpoints widened (c << 8) | 0x80, not by replication)
//   rgba   : unorm8 R (bits 7..0), G, B, A (31..24): the top 8 bits of the specification's C
//            (decode_unorm8; in sRGB mode the 8-bit code); the error colour is (255, 0, 255, 255)
package tex_astc;
  localparam logic [31:0] ERROR_RGBA = 32'hFF_FF_00_FF;  // A, B, G, R

  // a * b (b of 8 bits) as shifts and adds: the decoder's products are small, and as adders they
  // stay out of an FPGA's DSP blocks (Yosys maps every $mul of 2 bits or more to one).
  // (No loop: a loop variable in a function called under an `if` is a latch to Yosys.)
  function automatic logic [31:0] umul(input logic [23:0] a, input logic [7:0] b);
    logic [31:0] w;
    w = 32'(a);
    umul = (w & {32{b[0]}}) + ((w << 1) & {32{b[1]}}) + ((w << 2) & {32{b[2]}}) + ((w << 3) & {32{b[3]}}) +
           ((w << 4) & {32{b[4]}}) + ((w << 5) & {32{b[5]}}) + ((w << 6) & {32{b[6]}}) + ((w << 7) & {32{b[7]}});
  endfunction

  // ---- ranges of an integer sequence: {kind, n} with kind 0 bits (2^n), 1 trits (3 * 2^n), 2 quints
  // (5 * 2^n). Weights: range 0..11 = 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32 values; endpoint
  // values: 0..16 = 6, 8, 10, 12, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128, 160, 192, 256 values.
  function automatic logic [5:0] weight_range(input logic [3:0] r);
    case (r)
      4'd0: weight_range = {2'd0, 4'd1};  4'd1: weight_range = {2'd1, 4'd0};  4'd2: weight_range = {2'd0, 4'd2};
      4'd3: weight_range = {2'd2, 4'd0};  4'd4: weight_range = {2'd1, 4'd1};  4'd5: weight_range = {2'd0, 4'd3};
      4'd6: weight_range = {2'd2, 4'd1};  4'd7: weight_range = {2'd1, 4'd2};  4'd8: weight_range = {2'd0, 4'd4};
      4'd9: weight_range = {2'd2, 4'd2};  4'd10: weight_range = {2'd1, 4'd3}; default: weight_range = {2'd0, 4'd5};
    endcase
  endfunction
  function automatic logic [5:0] colour_range(input logic [4:0] r);
    case (r)
      5'd0: colour_range = {2'd1, 4'd1};   5'd1: colour_range = {2'd0, 4'd3};   5'd2: colour_range = {2'd2, 4'd1};
      5'd3: colour_range = {2'd1, 4'd2};   5'd4: colour_range = {2'd0, 4'd4};   5'd5: colour_range = {2'd2, 4'd2};
      5'd6: colour_range = {2'd1, 4'd3};   5'd7: colour_range = {2'd0, 4'd5};   5'd8: colour_range = {2'd2, 4'd3};
      5'd9: colour_range = {2'd1, 4'd4};   5'd10: colour_range = {2'd0, 4'd6};  5'd11: colour_range = {2'd2, 4'd4};
      5'd12: colour_range = {2'd1, 4'd5};  5'd13: colour_range = {2'd0, 4'd7};  5'd14: colour_range = {2'd2, 4'd5};
      5'd15: colour_range = {2'd1, 4'd6};  default: colour_range = {2'd0, 4'd8};
    endcase
  endfunction

  // Divisions by 5 and 3 as reciprocal multiplies, exact for the numerators they get (below 1024
  // and 512).
  function automatic logic [9:0] div5(input logic [9:0] v); div5 = 10'(umul(24'(v), 8'd205) >> 10); endfunction
  function automatic logic [8:0] div3(input logic [8:0] v); div3 = 9'(umul(24'(v), 8'd171) >> 9); endfunction

  // Bits of `count` values of a range (the specification's data size).
  function automatic logic [9:0] ise_bits(input logic [6:0] count, input logic [5:0] range);
    logic [9:0] low;
    low = 10'(umul(24'(count), 8'(range[3:0])));
    case (range[5:4])
      2'd1: ise_bits = low + div5((10'(count) << 3) + 10'd4);
      2'd2: ise_bits = low + 10'(div3((9'(count) << 3) - 9'(count) + 9'd2));
      default: ise_bits = low;
    endcase
  endfunction

  // ---- integer sequence: five trits from the 8 bits T, three quints from the 7 bits Q
  function automatic logic [9:0] trits_of(input logic [7:0] t);  // {t4, t3, t2, t1, t0}, 2 bits each
    logic [4:0] c;
    logic [1:0] t0, t1, t2, t3, t4;
    if (t[4:2] == 3'b111) begin
      c = {t[7:5], t[1:0]};
      t4 = 2'd2;
      t3 = 2'd2;
    end else begin
      c = t[4:0];
      if (t[6:5] == 2'b11) begin
        t4 = 2'd2;
        t3 = {1'b0, t[7]};
      end else begin
        t4 = {1'b0, t[7]};
        t3 = t[6:5];
      end
    end
    if (c[1:0] == 2'b11) begin
      t2 = 2'd2;
      t1 = {1'b0, c[4]};
      t0 = {c[3], c[2] & ~c[3]};
    end else if (c[3:2] == 2'b11) begin
      t2 = 2'd2;
      t1 = 2'd2;
      t0 = c[1:0];
    end else begin
      t2 = {1'b0, c[4]};
      t1 = c[3:2];
      t0 = {c[1], c[0] & ~c[1]};
    end
    trits_of = {t4, t3, t2, t1, t0};
  endfunction

  function automatic logic [8:0] quints_of(input logic [6:0] q);  // {q2, q1, q0}, 3 bits each
    logic [4:0] c;
    logic [2:0] q0, q1, q2;
    if (q[2:1] == 2'b11 && q[6:5] == 2'b00) begin
      q2 = {q[0], q[4] & ~q[0], q[3] & ~q[0]};
      q1 = 3'd4;
      q0 = 3'd4;
    end else begin
      if (q[2:1] == 2'b11) begin
        q2 = 3'd4;
        c = {q[4:3], ~q[6:5], q[0]};
      end else begin
        q2 = {1'b0, q[6:5]};
        c = q[4:0];
      end
      if (c[2:0] == 3'b101) begin
        q1 = 3'd4;
        q0 = {1'b0, c[4:3]};
      end else begin
        q1 = {1'b0, c[4:3]};
        q0 = c[2:0];
      end
    end
    quints_of = {q2, q1, q0};
  endfunction

  // A trit block's 8 bits T (low bits of n each at 0, n + 2, 2n + 4, 3n + 5, 4n + 7; T1:0 at n,
  // T3:2 at 2n + 2, T4 at 3n + 4, T6:5 at 4n + 5, T7 at 5n + 7) and a quint block's 7 bits Q (Q2:0
  // at n, Q4:3 at 2n + 3, Q6:5 at 3n + 5), from the block's first bits: fixed slices per n.
  function automatic logic [7:0] tbits(input logic [47:0] b, input logic [3:0] n);
    case (n)
      4'd0: tbits = {b[7], b[6:5], b[4], b[3:2], b[1:0]};
      4'd1: tbits = {b[12], b[10:9], b[7], b[5:4], b[2:1]};
      4'd2: tbits = {b[17], b[14:13], b[10], b[7:6], b[3:2]};
      4'd3: tbits = {b[22], b[18:17], b[13], b[9:8], b[4:3]};
      4'd4: tbits = {b[27], b[22:21], b[16], b[11:10], b[5:4]};
      4'd5: tbits = {b[32], b[26:25], b[19], b[13:12], b[6:5]};
      default: tbits = {b[37], b[30:29], b[22], b[15:14], b[7:6]};  // 6
    endcase
  endfunction
  function automatic logic [6:0] qbits(input logic [47:0] b, input logic [3:0] n);
    case (n)
      4'd0: qbits = {b[6:5], b[4:3], b[2:0]};
      4'd1: qbits = {b[9:8], b[6:5], b[3:1]};
      4'd2: qbits = {b[12:11], b[8:7], b[4:2]};
      4'd3: qbits = {b[15:14], b[10:9], b[5:3]};
      4'd4: qbits = {b[18:17], b[12:11], b[6:4]};
      default: qbits = {b[21:20], b[14:13], b[7:5]};  // 5
    endcase
  endfunction

  // Value i of a sequence of `count` values of `range` starting at bit 0 of `s`: {trit or quint
  // (3 bits), low bits (8)}. A trit (quint) block's bits that follow values past the end are 0.
  // Every kind's positions are computed and then chosen, two shifters in all, no shift under a
  // branch (Yosys's resource sharing explores every branch's shifters).
  function automatic logic [10:0] ise_value(input logic [127:0] s, input logic [6:0] i, input logic [6:0] count,
                                            input logic [5:0] range);
    /*verilator no_inline_task*/  // (one C++ function, not a copy at each call: 8 taps x 16 values)
    logic [3:0] n;
    logic trit, quint;
    logic [6:0] tb, tj, qb, qj, tfirst, qfirst;  // the trit (quint) block of value i, i's place, the block's first value
    logic [9:0] tbase, qbase, tat, qat, at, base;
    logic [7:0] low, t;
    logic [6:0] q;
    logic [47:0] from;
    logic [9:0] trits;
    logic [8:0] quints;
    n = range[3:0];
    trit = range[5:4] == 2'd1;
    quint = range[5:4] == 2'd2;
    // Trits: 5 values in 8 + 5n bits, value j's low bits at 0, n+2, 2n+4, 3n+5, 4n+7 and the
    // block's T bits at n (T1:0), 2n+2 (T3:2), 3n+4 (T4), 4n+5 (T6:5), 5n+7 (T7).
    tb = 7'(div5(10'(i)));
    tfirst = (tb << 2) + tb;
    tj = i - tfirst;
    tbase = 10'(umul(24'(tb), 8'd8 + (8'(n) << 2) + 8'(n)));
    tat = tbase + (tj == 7'd0 ? 10'd0 : tj == 7'd1 ? 10'(n) + 10'd2 : tj == 7'd2 ? (10'(n) << 1) + 10'd4 :
                   tj == 7'd3 ? (10'(n) << 1) + 10'(n) + 10'd5 : (10'(n) << 2) + 10'd7);
    // Quints: 3 values in 7 + 3n bits, low bits at 0, n+3, 2n+5; Q bits at n (Q2:0), 2n+3 (Q4:3),
    // 3n+5 (Q6:5).
    qb = 7'(div3(9'(i)));
    qfirst = (qb << 1) + qb;
    qj = i - qfirst;
    qbase = 10'(umul(24'(qb), 8'd7 + (8'(n) << 1) + 8'(n)));
    qat = qbase + (qj == 7'd0 ? 10'd0 : qj == 7'd1 ? 10'(n) + 10'd3 : (10'(n) << 1) + 10'd5);
    at = trit ? tat : quint ? qat : 10'(umul(24'(i), 8'(n)));
    base = trit ? tbase : quint ? qbase : at;
    // One wide shift: the block's first 48 bits hold its T (Q) bits and value i's low bits (5n + 7
    // < 48 for trits, 3n + 7 for quints); a plain value starts the window.
    from = 48'(s >> base);
    low = 8'(from >> (at - base)) & 8'(({1'b0, 8'hFF} << n) ^ 9'h1FF);
    t = tbits(from, n) & {tfirst + 7'd5 <= count, {2{tfirst + 7'd4 <= count}}, tfirst + 7'd3 <= count,
                          {2{tfirst + 7'd2 <= count}}, {2{tfirst + 7'd1 <= count}}};
    q = qbits(from, n) & {{2{qfirst + 7'd3 <= count}}, {2{qfirst + 7'd2 <= count}}, {3{qfirst + 7'd1 <= count}}};
    // (each table only for its kind: a simulator skips the other; no `else`, which Verilator
    // would make a ?: with both calls before it)
    trits = '0;
    quints = '0;
    if (trit) trits = trits_of(t);
    if (quint) quints = quints_of(q);
    ise_value = {trit ? {1'b0, 2'(trits >> (2 * tj))} : quint ? 3'(quints >> (3 * qj)) : 3'd0, low};
  endfunction

  // ---- unquantization
  // The n-bit value v (n = 1..8) widened to 8 bits by replicating it from its top bit.
  function automatic logic [7:0] replicate8(input logic [7:0] v, input logic [3:0] n);
    case (n)
      4'd1: replicate8 = {8{v[0]}};
      4'd2: replicate8 = {4{v[1:0]}};
      4'd3: replicate8 = {v[2:0], v[2:0], v[2:1]};
      4'd4: replicate8 = {2{v[3:0]}};
      4'd5: replicate8 = {v[4:0], v[4:2]};
      4'd6: replicate8 = {v[5:0], v[5:4]};
      4'd7: replicate8 = {v[6:0], v[6]};
      default: replicate8 = v;
    endcase
  endfunction

  // An endpoint value to 0..255: bit replication, or the A, B, C, D procedure (9 bits).
  function automatic logic [7:0] unquantize_colour(input logic [4:0] r, input logic [2:0] d, input logic [7:0] low);
    logic [5:0] range;
    logic [8:0] a, b, c, unq;
    logic bb, cc, dd, ee, ff;
    range = colour_range(r);
    {ff, ee, dd, cc, bb} = low[5:1];
    a = low[0] ? 9'h1FF : 9'h000;
    b = 9'd0;
    c = 9'd0;
    case (r)
      5'd0: c = 9'd204;                                                                            // 6
      5'd2: c = 9'd113;                                                                            // 10
      5'd3: begin b = {bb, 3'b000, bb, 1'b0, bb, bb, 1'b0}; c = 9'd93; end                         // 12
      5'd5: begin b = {bb, 4'b0000, bb, bb, 2'b00}; c = 9'd54; end                                 // 20
      5'd6: begin b = {cc, bb, 3'b000, cc, bb, cc, bb}; c = 9'd44; end                             // 24
      5'd8: begin b = {cc, bb, 4'b0000, cc, bb, cc}; c = 9'd26; end                                // 40
      5'd9: begin b = {dd, cc, bb, 3'b000, dd, cc, bb}; c = 9'd22; end                             // 48
      5'd11: begin b = {dd, cc, bb, 4'b0000, dd, cc}; c = 9'd13; end                               // 80
      5'd12: begin b = {ee, dd, cc, bb, 3'b000, ee, dd}; c = 9'd11; end                            // 96
      5'd14: begin b = {ee, dd, cc, bb, 4'b0000, ee}; c = 9'd6; end                                // 160
      5'd15: begin b = {ff, ee, dd, cc, bb, 3'b000, ff}; c = 9'd5; end                             // 192
      default: ;
    endcase
    unq = (9'(umul(24'(c), 8'(d))) + b) ^ a;
    if (range[5:4] == 2'd0) unquantize_colour = replicate8(low, range[3:0]);
    else unquantize_colour = {a[7], 7'(unq >> 2)};
  endfunction

  // A weight to 0..64: replication to 6 bits or the trit / quint procedure (7 bits), then 33..63
  // up by one.
  function automatic logic [6:0] unquantize_weight(input logic [3:0] r, input logic [2:0] d, input logic [7:0] low);
    logic [5:0] range;
    logic [6:0] a, b, c, x, unq;
    logic [7:0] wide;  // the bits replicated to 8
    logic bb, cc;
    range = weight_range(r);
    wide = replicate8(low, range[3:0]);
    bb = low[1];
    cc = low[2];
    a = low[0] ? 7'h7F : 7'h00;
    b = 7'd0;
    c = 7'd0;
    case (r)
      4'd4: c = 7'd50;                                                   // 6
      4'd6: c = 7'd28;                                                   // 10
      4'd7: begin b = {bb, 3'b000, bb, 1'b0, bb}; c = 7'd23; end        // 12
      4'd9: begin b = {bb, 4'b0000, bb, 1'b0}; c = 7'd13; end           // 20
      4'd10: begin b = {cc, bb, 3'b000, cc, bb}; c = 7'd11; end         // 24
      default: ;
    endcase
    x = (7'(umul(24'(c), 8'(d))) + b) ^ a;
    if (range[5:4] == 2'd0) unq = {1'b0, 6'(wide >> 2)};
    else if (r == 4'd1) unq = d == 3'd0 ? 7'd0 : d == 3'd1 ? 7'd32 : 7'd63;               // 3: 0, 32, 63
    else if (r == 4'd3) unq = d == 3'd0 ? 7'd0 : d == 3'd1 ? 7'd16 : d == 3'd2 ? 7'd32 : d == 3'd3 ? 7'd47 : 7'd63;
    else unq = {1'b0, a[5], 5'(x >> 2)};
    unquantize_weight = unq > 7'd32 ? unq + 7'd1 : unq;
  endfunction

  // ---- block mode: {legal, dual plane, grid w (4), grid h (4), weight range (4)}
  function automatic logic [13:0] block_mode(input logic [10:0] m);
    logic [3:0] gw, gh;
    logic [2:0] rho;
    logic p, dual, legal;
    p = m[9];
    dual = m[10];
    legal = 1'b1;
    gw = 4'd0;
    gh = 4'd0;
    if (m[1:0] != 2'b00) begin
      rho = {m[1:0], m[4]};
      case (m[3:2])
        2'd0: begin gw = 4'(m[8:7]) + 4'd4; gh = 4'(m[6:5]) + 4'd2; end
        2'd1: begin gw = 4'(m[8:7]) + 4'd8; gh = 4'(m[6:5]) + 4'd2; end
        2'd2: begin gw = 4'(m[6:5]) + 4'd2; gh = 4'(m[8:7]) + 4'd8; end
        default:
          if (!m[8]) begin gw = 4'(m[6:5]) + 4'd2; gh = 4'(m[7]) + 4'd6; end
          else begin gw = 4'(m[7]) + 4'd2; gh = 4'(m[6:5]) + 4'd2; end
      endcase
    end else begin
      rho = {m[3:2], m[4]};
      if (m[3:2] == 2'b00) legal = 1'b0;
      case (m[8:7])
        2'd0: begin gw = 4'd12; gh = 4'(m[6:5]) + 4'd2; end
        2'd1: begin gw = 4'(m[6:5]) + 4'd2; gh = 4'd12; end
        2'd2: begin gw = 4'(m[6:5]) + 4'd6; gh = 4'(m[10:9]) + 4'd6; dual = 1'b0; p = 1'b0; end
        default:
          if (m[6:5] == 2'd0) begin gw = 4'd6; gh = 4'd10; end
          else if (m[6:5] == 2'd1) begin gw = 4'd10; gh = 4'd6; end
          else legal = 1'b0;
      endcase
    end
    if (rho < 3'd2) legal = 1'b0;
    block_mode = {legal, dual, gw, gh, 4'(rho - 3'd2) + (p ? 4'd6 : 4'd0)};
  endfunction

  // ---- endpoints: {e1, e0} (8 bits a channel, A B G R) of colour endpoint mode `cem` from its
  // values v (8 of 8 bits, v0 in the low byte); bit 64: an HDR mode.
  function automatic logic [7:0] clamp8(input logic signed [10:0] v);
    clamp8 = v < 0 ? 8'd0 : v > 11'sd255 ? 8'd255 : v[7:0];
  endfunction
  // bit_transfer_signed: a (0..255) gives -32..31 and its top bit to b.
  function automatic logic signed [10:0] transfer_a(input logic [7:0] a);
    transfer_a = $signed((11'(a) >> 1) & 11'h3F) - (a[6] ? 11'sd64 : 11'sd0);
  endfunction
  function automatic logic signed [10:0] transfer_b(input logic [7:0] a, input logic [7:0] b);
    transfer_b = $signed((11'(a) & 11'h80) | (11'(b) >> 1));
  endfunction

  // The endpoint values of a colour endpoint mode: 2 per class (cem >> 2) + 1.
  function automatic logic [6:0] values_of(input logic [3:0] cem);
    values_of = ((7'(cem) >> 2) + 7'd1) << 1;
  endfunction

  function automatic logic [64:0] endpoints(input logic [3:0] cem, input logic [63:0] vals);
    logic [7:0] v0, v1, v2, v3, v4, v5, v6, v7;
    logic [7:0] l0, l1, a0, a1;
    logic signed [10:0] s0, s1, s2, s3, s4, s5, s6, s7;  // base + offset after bit_transfer_signed
    logic [31:0] e0, e1;
    logic hdr;
    {v7, v6, v5, v4, v3, v2, v1, v0} = vals;
    hdr = 1'b0;
    e0 = 32'd0;
    e1 = 32'd0;
    s0 = transfer_b(v1, v0); s1 = transfer_a(v1);
    s2 = transfer_b(v3, v2); s3 = transfer_a(v3);
    s4 = transfer_b(v5, v4); s5 = transfer_a(v5);
    s6 = transfer_b(v7, v6); s7 = transfer_a(v7);
    case (cem)
      4'd0: begin e0 = {8'd255, v0, v0, v0}; e1 = {8'd255, v1, v1, v1}; end
      4'd1: begin
        l0 = {v1[7:6], v0[7:2]};
        l1 = 9'(l0) + 9'(v1[5:0]) > 9'd255 ? 8'd255 : l0 + 8'(v1[5:0]);
        e0 = {8'd255, l0, l0, l0};
        e1 = {8'd255, l1, l1, l1};
      end
      4'd4: begin e0 = {v2, v0, v0, v0}; e1 = {v3, v1, v1, v1}; end
      4'd5: begin
        l0 = clamp8(s0);
        l1 = clamp8(s0 + s1);
        e0 = {clamp8(s2), l0, l0, l0};
        e1 = {clamp8(s2 + s3), l1, l1, l1};
      end
      4'd6, 4'd10: begin
        a0 = cem == 4'd6 ? 8'd255 : v4;
        a1 = cem == 4'd6 ? 8'd255 : v5;
        e0 = {a0, 8'(umul(24'(v2), v3) >> 8), 8'(umul(24'(v1), v3) >> 8), 8'(umul(24'(v0), v3) >> 8)};
        e1 = {a1, v2, v1, v0};
      end
      4'd8, 4'd12: begin
        a0 = cem == 4'd8 ? 8'd255 : v6;
        a1 = cem == 4'd8 ? 8'd255 : v7;
        if (10'(v1) + 10'(v3) + 10'(v5) >= 10'(v0) + 10'(v2) + 10'(v4)) begin
          e0 = {a0, v4, v2, v0};
          e1 = {a1, v5, v3, v1};
        end else begin  // blue contraction
          e0 = {a1, v5, 8'((9'(v3) + 9'(v5)) >> 1), 8'((9'(v1) + 9'(v5)) >> 1)};
          e1 = {a0, v4, 8'((9'(v2) + 9'(v4)) >> 1), 8'((9'(v0) + 9'(v4)) >> 1)};
        end
      end
      4'd9, 4'd13: begin
        if (s1 + s3 + s5 >= 0) begin
          e0 = {cem == 4'd9 ? 8'd255 : clamp8(s6), clamp8(s4), clamp8(s2), clamp8(s0)};
          e1 = {cem == 4'd9 ? 8'd255 : clamp8(s6 + s7), clamp8(s4 + s5), clamp8(s2 + s3), clamp8(s0 + s1)};
        end else begin  // blue contraction
          e0 = {cem == 4'd9 ? 8'd255 : clamp8(s6 + s7), clamp8(s4 + s5),
                clamp8((s2 + s3 + s4 + s5) >>> 1), clamp8((s0 + s1 + s4 + s5) >>> 1)};
          e1 = {cem == 4'd9 ? 8'd255 : clamp8(s6), clamp8(s4), clamp8((s2 + s4) >>> 1), clamp8((s0 + s4) >>> 1)};
        end
      end
      default: hdr = 1'b1;  // 2, 3, 7, 11, 14, 15
    endcase
    endpoints = {hdr, e1, e0};
  endfunction

  // ---- partition (the specification's select_partition, 2D)
  function automatic logic [31:0] hash52(input logic [31:0] p0);
    logic [31:0] p;
    p = p0;
    p = p ^ (p >> 15);
    p = p - (p << 17);
    p = p + (p << 7);
    p = p + (p << 4);
    p = p ^ (p >> 5);
    p = p + (p << 16);
    p = p ^ (p >> 7);
    p = p ^ (p >> 3);
    p = p ^ (p << 6);
    p = p ^ (p >> 17);
    hash52 = p;
  endfunction
  function automatic logic [1:0] partition(input logic [9:0] seed10, input logic [2:0] partitions,
                                           input logic [4:0] x, input logic [4:0] y);
    /*verilator no_inline_task*/  // (one C++ function, not a copy at each call: 8 taps x 16 values)
    logic [11:0] seed;
    logic [31:0] rnum;
    logic [7:0] s1, s2, s3, s4, s5, s6, s7, s8;
    logic [2:0] sh1, sh2;
    logic [5:0] a, b, c, d;
    seed = 12'(seed10) + ((12'(partitions) - 12'd1) << 10);
    rnum = hash52(32'(seed));
    s1 = 8'(umul(24'(rnum[3:0]), 8'(rnum[3:0])));
    s2 = 8'(umul(24'(rnum[7:4]), 8'(rnum[7:4])));
    s3 = 8'(umul(24'(rnum[11:8]), 8'(rnum[11:8])));
    s4 = 8'(umul(24'(rnum[15:12]), 8'(rnum[15:12])));
    s5 = 8'(umul(24'(rnum[19:16]), 8'(rnum[19:16])));
    s6 = 8'(umul(24'(rnum[23:20]), 8'(rnum[23:20])));
    s7 = 8'(umul(24'(rnum[27:24]), 8'(rnum[27:24])));
    s8 = 8'(umul(24'(rnum[31:28]), 8'(rnum[31:28])));
    if (seed[0]) begin
      sh1 = seed[1] ? 3'd4 : 3'd5;
      sh2 = partitions == 3'd3 ? 3'd6 : 3'd5;
    end else begin
      sh1 = partitions == 3'd3 ? 3'd6 : 3'd5;
      sh2 = seed[1] ? 3'd4 : 3'd5;
    end
    a = 6'(umul(24'(s1) >> sh1, 8'(x)) + umul(24'(s2) >> sh2, 8'(y)) + 32'(rnum >> 14));
    b = 6'(umul(24'(s3) >> sh1, 8'(x)) + umul(24'(s4) >> sh2, 8'(y)) + 32'(rnum >> 10));
    c = 6'(umul(24'(s5) >> sh1, 8'(x)) + umul(24'(s6) >> sh2, 8'(y)) + 32'(rnum >> 6)) & {6{partitions >= 3'd3}};
    d = 6'(umul(24'(s7) >> sh1, 8'(x)) + umul(24'(s8) >> sh2, 8'(y)) + 32'(rnum >> 2)) & {6{partitions == 3'd4}};
    if (a >= b && a >= c && a >= d) partition = 2'd0;
    else if (b >= c && b >= d) partition = 2'd1;
    else if (c >= d) partition = 2'd2;
    else partition = 2'd3;
  endfunction

  // ---- infill: the texel's weight on `plane` from the grid (gw x gh, `weights` weights in the
  // stream `ws` read from bit 127 down, of range `wr`)
  function automatic logic [6:0] grid_weight(input logic [127:0] ws, input logic [6:0] index, input logic [6:0] count,
                                             input logic [3:0] wr);
    logic [10:0] v;
    if (index >= count) begin
      grid_weight = 7'd0;  // (weighted 0: past the grid)
    end else begin
      v = ise_value(ws, index, count, weight_range(wr));
      grid_weight = unquantize_weight(wr, v[10:8], v[7:0]);
    end
  endfunction
  function automatic logic [10:0] scale_d(input logic [3:0] b);  // (1024 + b / 2) / (b - 1)
    case (b)
      4'd4: scale_d = 11'd342;  4'd5: scale_d = 11'd256;  4'd6: scale_d = 11'd205;  4'd8: scale_d = 11'd146;
      4'd10: scale_d = 11'd114; default: scale_d = 11'd93;  // 12
    endcase
  endfunction
  function automatic logic [6:0] infill(input logic [127:0] ws, input logic [3:0] fw, input logic [3:0] fh,
                                        input logic [3:0] x, input logic [3:0] y, input logic [3:0] gw,
                                        input logic [3:0] gh, input logic dual, input logic plane, input logic [3:0] wr);
    /*verilator no_inline_task*/  // (one C++ function, not a copy at each call: 8 taps x 16 values)
    logic [17:0] gs, gt;
    logic [3:0] js, jt, fs, ft;
    logic [6:0] v0, count, planes;
    logic [7:0] w11, w10, w01, w00;
    logic [14:0] sum;
    gs = 18'((umul(24'(umul(24'(scale_d(fw)), 8'(x))), 8'(gw) - 8'd1) + 32'd32) >> 6);
    gt = 18'((umul(24'(umul(24'(scale_d(fh)), 8'(y))), 8'(gh) - 8'd1) + 32'd32) >> 6);
    js = 4'(gs >> 4);
    fs = gs[3:0];
    jt = 4'(gt >> 4);
    ft = gt[3:0];
    planes = dual ? 7'd2 : 7'd1;
    count = 7'(umul(24'(gw), 8'(gh))) << (planes - 7'd1);
    v0 = 7'(js) + 7'(umul(24'(jt), 8'(gw)));
    w11 = 8'((umul(24'(fs), 8'(ft)) + 32'd8) >> 4);
    w10 = 8'(ft) - w11;
    w01 = 8'(fs) - w11;
    w00 = 8'd16 - 8'(fs) - 8'(ft) + w11;
    sum = 15'(umul(24'(grid_weight(ws, (v0 << (planes - 7'd1)) + 7'(plane), count, wr)), w00) +
              umul(24'(grid_weight(ws, ((v0 + 7'd1) << (planes - 7'd1)) + 7'(plane), count, wr)), w01) +
              umul(24'(grid_weight(ws, ((v0 + 7'(gw)) << (planes - 7'd1)) + 7'(plane), count, wr)), w10) +
              umul(24'(grid_weight(ws, ((v0 + 7'(gw) + 7'd1) << (planes - 7'd1)) + 7'(plane), count, wr)), w11) + 32'd8);
    infill = 7'(sum >> 4);
  endfunction

  // ---- weight application: the top 8 bits of C = (C0 (64 - i) + C1 i + 32) >> 6 of endpoints
  // widened to 16 bits (replication, or sRGB's 0x80 below).
  function automatic logic [7:0] apply(input logic [7:0] e0, input logic [7:0] e1, input logic [6:0] i, input logic srgb);
    logic [15:0] c0, c1;
    logic [22:0] c;
    c0 = {e0, srgb ? 8'h80 : e0};
    c1 = {e1, srgb ? 8'h80 : e1};
    // C0 (64 - i) + C1 i = 64 C0 + (C1 - C0) i: one product a channel
    c = 23'(($signed({7'd0, c0} << 6) + $signed({7'd0, c1} - {7'd0, c0}) * $signed({16'd0, i}) + 23'sd32) >>> 6);
    apply = 8'(c >> 8);
  endfunction

  function automatic logic [31:0] texel(input logic [127:0] block, input logic [3:0] fw, input logic [3:0] fh,
                                        input logic [3:0] x, input logic [3:0] y, input logic srgb);
    /*verilator no_inline_task*/  // (one C++ function, not a copy at each call: 8 taps x 16 values)
    logic [13:0] mode;
    logic legal, dual;
    logic [3:0] gw, gh, wr;
    logic [2:0] partitions;
    logic [6:0] weight_count, colour_values, extra;
    logic [9:0] weight_bits, config_bits, remaining;
    logic [1:0] selector, ccs, p;
    logic [5:0] field_low;
    logic [13:0] field;
    logic [3:0] cem0, cem1, cem2, cem3, cem;
    logic [4:0] cr;
    logic [127:0] ws, cs;
    logic [6:0] off, w0, w1;
    logic [63:0] vals;
    logic [64:0] ep;
    logic [10:0] v;
    logic [31:0] e0, e1;
    logic error;
    // Every stage computed, the void extent's test last (no `if` around the loops: a loop variable
    // assigned under an `if` is a latch to Yosys).
    begin
      mode = block_mode(block[10:0]);
      {legal, dual, gw, gh, wr} = mode;
      partitions = 3'(block[12:11]) + 3'd1;
      weight_count = 7'(umul(24'(gw), 8'(gh))) << dual;
      weight_bits = ise_bits(weight_count, weight_range(wr));
      error = !legal || gw * gh * (dual ? 2 : 1) > 64 || weight_bits < 10'd24 || weight_bits > 10'd96 ||
              gw > fw || gh > fh || (dual && partitions == 3'd4);
      // Configuration: the endpoint modes and the dual plane's channel.
      selector = block[24:23];
      extra = (partitions == 3'd1 || selector == 2'd0) ? 7'd0 : 7'(3'd3 * partitions) - 7'd4;
      field_low = block[28:23];
      field = {8'(block >> (10'd128 - weight_bits - 10'(extra))) & 8'(({1'b0, 8'hFF} << extra) ^ 9'h1FF), field_low};
      if (partitions == 3'd1) begin
        {cem0, cem1, cem2, cem3} = {4{block[16:13]}};
        config_bits = 10'd17;
      end else if (selector == 2'd0) begin
        {cem0, cem1, cem2, cem3} = {4{block[28:25]}};
        config_bits = 10'd29;
      end else begin
        // class = selector - 1 + C_p (bits 2 + p), low bits M_p (bits 2 + partitions + 2p)
        cem0 = {2'(selector - 2'd1) + 2'(field[2]), 2'(field >> (5'd2 + 5'(partitions)))};
        cem1 = {2'(selector - 2'd1) + 2'(field[3]), 2'(field >> (5'd4 + 5'(partitions)))};
        cem2 = {2'(selector - 2'd1) + 2'(field[4]), 2'(field >> (5'd6 + 5'(partitions)))};
        cem3 = {2'(selector - 2'd1) + 2'(field[5]), 2'(field >> (5'd8 + 5'(partitions)))};
        config_bits = 10'd25 + 10'd3 * 10'(partitions);
      end
      ccs = 2'(block >> (10'd128 - weight_bits - 10'(extra) - 10'd2));
      if (dual) config_bits = config_bits + 10'd2;
      colour_values = values_of(cem0) + (partitions >= 3'd2 ? values_of(cem1) : 7'd0) +
                      (partitions >= 3'd3 ? values_of(cem2) : 7'd0) +
                      (partitions == 3'd4 ? values_of(cem3) : 7'd0);
      remaining = 10'd128 - config_bits - weight_bits;  // (wraps where they exceed 128: an error below)
      if (!error && (colour_values > 7'd18 || config_bits + weight_bits > 10'd128 ||
                     remaining < div5(10'd13 * 10'(colour_values) + 10'd4))) error = 1'b1;
      // The largest endpoint range that fits (no loop: a priority chain).
      if (ise_bits(colour_values, colour_range(5'd16)) <= remaining) cr = 5'd16;
      else if (ise_bits(colour_values, colour_range(5'd15)) <= remaining) cr = 5'd15;
      else if (ise_bits(colour_values, colour_range(5'd14)) <= remaining) cr = 5'd14;
      else if (ise_bits(colour_values, colour_range(5'd13)) <= remaining) cr = 5'd13;
      else if (ise_bits(colour_values, colour_range(5'd12)) <= remaining) cr = 5'd12;
      else if (ise_bits(colour_values, colour_range(5'd11)) <= remaining) cr = 5'd11;
      else if (ise_bits(colour_values, colour_range(5'd10)) <= remaining) cr = 5'd10;
      else if (ise_bits(colour_values, colour_range(5'd9)) <= remaining) cr = 5'd9;
      else if (ise_bits(colour_values, colour_range(5'd8)) <= remaining) cr = 5'd8;
      else if (ise_bits(colour_values, colour_range(5'd7)) <= remaining) cr = 5'd7;
      else if (ise_bits(colour_values, colour_range(5'd6)) <= remaining) cr = 5'd6;
      else if (ise_bits(colour_values, colour_range(5'd5)) <= remaining) cr = 5'd5;
      else if (ise_bits(colour_values, colour_range(5'd4)) <= remaining) cr = 5'd4;
      else if (ise_bits(colour_values, colour_range(5'd3)) <= remaining) cr = 5'd3;
      else if (ise_bits(colour_values, colour_range(5'd2)) <= remaining) cr = 5'd2;
      else if (ise_bits(colour_values, colour_range(5'd1)) <= remaining) cr = 5'd1;
      else cr = 5'd0;
      // The texel's partition, and its endpoint values (they follow the earlier partitions').
      // (the calls under an `if` of their own: Verilator hoists a call out of a ?: and makes it in
      // every case)
      p = '0;
      if (partitions != 3'd1)
        p = partition(block[22:13], partitions, fw * fh < 31 ? 5'(x) << 1 : 5'(x), fw * fh < 31 ? 5'(y) << 1 : 5'(y));
      case (p)
        2'd0: cem = cem0;
        2'd1: cem = cem1;
        2'd2: cem = cem2;
        default: cem = cem3;
      endcase
      off = (p >= 2'd1 ? values_of(cem0) : 7'd0) + (p >= 2'd2 ? values_of(cem1) : 7'd0) +
            (p == 2'd3 ? values_of(cem2) : 7'd0);
      cs = block >> (partitions == 3'd1 ? 7'd17 : 7'd29);
      vals = '0;
      for (int k = 0; k < 8; k++) begin
        v = '0;
        if (7'(k) < values_of(cem))  // (the mode's 2 to 8 values: a simulator skips the rest)
          v = ise_value(cs, off + 7'(k), colour_values, colour_range(cr));
        vals[8 * k +: 8] = unquantize_colour(cr, v[10:8], v[7:0]);
      end
      ep = endpoints(cem, vals);
      e0 = ep[31:0];
      e1 = ep[63:32];
      // The weights, and the endpoints interpolated.
      // The weights run from bit 127 down. (Verilator takes the stream operator, one call: the
      // loop is 128 steps of wide bit selects in its C++; Yosys 0.23 and Icarus 11 do not read it.)
`ifdef VERILATOR
      ws = {<<{block}};
`else
      for (int k = 0; k < 128; k++) ws[k] = block[127 - k];
`endif
      w0 = infill(ws, fw, fh, x, y, gw, gh, dual, 1'b0, wr);
      w1 = w0;
      if (dual) w1 = infill(ws, fw, fh, x, y, gw, gh, dual, 1'b1, wr);
      // Void extent (bits 8..0 = 1 1111 1100): one colour, its top 8 bits; the error colour for HDR
      // (bit 9), reserved bits 10, 11 not set, or an empty extent (min >= max, unless all ones).
      if (block[8:0] == 9'h1FC) begin
        if (block[9] || !block[10] || !block[11] ||
            (!(block[63:12] == {52{1'b1}}) && (block[24:12] >= block[37:25] || block[50:38] >= block[63:51])))
          texel = ERROR_RGBA;
        else
          texel = {block[127:120], block[111:104], block[95:88], block[79:72]};
      end else if (error || ep[64]) begin
        texel = ERROR_RGBA;
      end else begin
        texel = {apply(e0[31:24], e1[31:24], dual && ccs == 2'd3 ? w1 : w0, srgb),
                 apply(e0[23:16], e1[23:16], dual && ccs == 2'd2 ? w1 : w0, srgb),
                 apply(e0[15:8], e1[15:8], dual && ccs == 2'd1 ? w1 : w0, srgb),
                 apply(e0[7:0], e1[7:0], dual && ccs == 2'd0 ? w1 : w0, srgb)};
      end
    end
  endfunction
endpackage
