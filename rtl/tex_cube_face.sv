// tex_cube_face: the face a direction selects and the face's coordinates (the model's
// stage::cube_face and cube_reciprocal, docs/numerics.md "Cube maps", bit for bit): the major axis
// (ties to rz, then ry) selects the face and (sc, tc, rc) by the specification's table;
// s = (sc / |rc| + 1) / 2 and t likewise are the exact quotients rounded to the nearest Q8.24 (a
// half up), reached by a reciprocal and one correction step rather than a divider. Shared by
// tex_cube (a request's direction) and tex_cube_seam (a probe beyond its face).
//   clock 1  face select, the table's picks, |rc| normalized by k to D in [2^31, 2^32), and
//            X = sc + |rc| (tc + |rc|) shifted alike (the quotient X / D is unchanged)
//   clock 2  R1: a 256-entry table of 10 bits, t = floor(2^18 / (257 + i)) for D's bits 30..23 = i
//            (R0 = t 2^21), and a Newton step R' = R + R (2^62 - D R) / 2^62, products truncated
//   clock 3  R2: the Newton step from R1's top 18 bits h = R1 >> 14: R2 <= 2^62 / D within 2^-25
//            (from below; the products D x t, t x delta1, D x h, h x delta2 are 7 DSP tiles)
//   clock 4  the estimate Q = (X R2 + 2^38) >> 39, at most 1 below the exact rounded quotient
//            floor((X 2^24 + D) / 2D), then the remainder against 2D (its low 36 bits: D Q in three
//            18-bit tiles, the fourth lies above them): s, t exact
// A direction (0, 0, 0) selects +Z at its centre.
// Handshake: stall-enable: the registers of clock n load when en is high and clock n - 1 holds a
//   direction (`valid` at the input); otherwise every register keeps its value (a simulator spends
//   nothing here on other requests).
// Latency: 4 clocks from the pins to face, s, t (registers). Throughput: 1 per clock.
// Ports:
//   valid                 : a direction on the pins (gates the registers)
//   rx, ry, rz            : the direction, signed Q8.24 (any length, REQ_COORD_W bits)
//   face                  : 0..5 = +X, -X, +Y, -Y, +Z, -Z (clock 4)
//   s, t                  : the face's coordinates, signed Q8.24 in [0, 1] (clock 4)
//   zero                  : the direction was (0, 0, 0) (clock 4)
//   recip, k              : R2 >> 15 (unsigned, (2^15, 2^16]) and the normalizing shift (0..31),
//                           for tex_cube's derivatives (clock 4)
//   face_1, rc_negative_1 : clock 1's face and sign of rc (the table's picks of the derivatives)
module tex_cube_face (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic                                   valid,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] rx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] ry,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] rz,
  output logic [2:0]                             face,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] s,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] t,
  output logic                                   zero,
  output logic [16:0]                            recip,
  output logic [4:0]                             k,
  output logic [2:0]                             face_1,
  output logic                                   rc_negative_1
);
  localparam int CW = tex_pkg::REQ_COORD_W;  // 32
  localparam int EW = CW + 1;                // a table pick: -INT32_MIN fits
  localparam int FRAC = tex_pkg::COORD_FRAC; // 24

  function automatic logic [256*10-1:0] recip_table();
    for (int i = 0; i < 256; i++) recip_table[i*10 +: 10] = 10'(262144 / (257 + i));
  endfunction
  localparam logic [256*10-1:0] RECIP = recip_table();

  // Which clocks hold a direction (bit n-1: clock n's registers).
  logic [3:1] held;
  always_ff @(posedge clk) if (en) held <= {held[2:1], valid};

  // ---------------------------------------------------------------- clock 1: face, normalize
  logic                 zero_1;          // (0, 0, 0)
  logic [CW-1:0]        d_1;             // |rc| << k: [2^31, 2^32)
  logic [CW+1:0]        xs_1, xt_1;      // (sc + |rc|) << k, (tc + |rc|) << k: <= 2^33
  logic [4:0]           k_1;
  always_ff @(posedge clk) begin
    if (en && valid) begin
      logic [EW-1:0]        ax, ay, az;
      logic signed [EW-1:0] x, y, z, sc, tc, rc;
      logic [CW-1:0]        arc;
      logic [4:0]           shift;
      x = EW'(rx);
      y = EW'(ry);
      z = EW'(rz);
      ax = x[EW-1] ? EW'(-x) : EW'(x);
      ay = y[EW-1] ? EW'(-y) : EW'(y);
      az = z[EW-1] ? EW'(-z) : EW'(z);
      if (az >= ax && az >= ay) begin
        face_1 <= z[EW-1] ? 3'd5 : 3'd4;
        sc = z[EW-1] ? -x : x;
        tc = -y;
        rc = z;
      end else if (ay >= ax) begin
        face_1 <= y[EW-1] ? 3'd3 : 3'd2;
        sc = x;
        tc = y[EW-1] ? -z : z;
        rc = y;
      end else begin
        face_1 <= x[EW-1] ? 3'd1 : 3'd0;
        sc = x[EW-1] ? z : -z;
        tc = -y;
        rc = x;
      end
      rc_negative_1 <= rc[EW-1];
      arc = CW'(rc[EW-1] ? -rc : rc);  // <= 2^31
      // The shift: 31 - the leading one of |rc|, so that D = |rc| << k has its top bit set.
      shift = '0;
      for (int b = 0; b < CW; b++) if (arc[b]) shift = 5'(CW - 1 - b);
      zero_1 <= arc == '0;
      k_1    <= shift;
      d_1    <= arc << shift;
      xs_1   <= (CW+2)'(sc + EW'(arc)) << shift;
      xt_1   <= (CW+2)'(tc + EW'(arc)) << shift;
    end
  end

  // ---------------------------------------------------------------- clock 2: R1
  // 2^62 - D R >= 0 since R never passes 1/D; it is below 2^62 * 2^-7 here (2^-14 in clock 3):
  // delta1 = (2^62 - D R0) >> 30 = (2^41 - D t) >> 9 < 2^25, delta2 < 2^18.
  logic [CW-1:0] d_2, r_2;
  logic [CW+1:0] xs_2, xt_2;
  logic [4:0]    k_2;
  logic [2:0]    face_2;
  logic          zero_2;
  always_ff @(posedge clk) begin
    if (en && held[1]) begin
      logic [9:0]  r0;     // R0 = r0 2^21
      logic [41:0] dt;
      logic [24:0] delta1;
      logic [34:0] td;
      r0     = RECIP[32'(d_1[30:23]) * 10 +: 10];
      dt     = 42'(d_1) * 42'(r0);
      delta1 = 25'(((42'd1 << 41) - dt) >> 9);
      td     = 35'(r0) * 35'(delta1);
      r_2    <= (CW'(r0) << 21) + CW'(td >> 11);
      d_2   <= d_1;
      xs_2  <= xs_1;
      xt_2  <= xt_1;
      k_2   <= k_1;
      face_2 <= face_1;
      zero_2 <= zero_1;
    end
  end

  // ---------------------------------------------------------------- clock 3: R2
  logic [CW-1:0] d_3, r_3;
  logic [CW+1:0] xs_3, xt_3;
  logic [4:0]    k_3;
  logic [2:0]    face_3;
  logic          zero_3;
  always_ff @(posedge clk) begin
    if (en && held[2]) begin
      logic [17:0] h;
      logic [49:0] dh;
      logic [17:0] delta2;
      logic [35:0] hd;
      h      = 18'(r_2 >> 14);
      dh     = 50'(d_2) * 50'(h);
      delta2 = 18'(((50'd1 << 48) - dh) >> 16);
      hd     = 36'(h) * 36'(delta2);
      r_3    <= (CW'(h) << 14) + CW'(hd >> 18);
      d_3   <= d_2;
      xs_3  <= xs_2;
      xt_3  <= xt_2;
      k_3   <= k_2;
      face_3 <= face_2;
      zero_3 <= zero_2;
    end
  end

  // ---------------------------------------------------------------- clock 4: s, t
  // floor((X 2^24 + D) / 2D) from the estimate and the remainder (36 bits hold it: below 4D).
  always_ff @(posedge clk) begin
    if (en && held[3]) begin
      logic [65:0] prod;
      logic [FRAC:0] est;
      logic [35:0] rem, two_d, dq;
      for (int c = 0; c < 2; c++) begin
        prod  = ((c == 0) ? 66'(xs_3) : 66'(xt_3)) * 66'(r_3) + (66'd1 << 38);
        est   = (FRAC+1)'(prod >> 39);
        two_d = 36'(d_3) << 1;
        // D Q mod 2^36 = Dl Ql + (Dl Qh + Dh Ql) 2^18 (Dh Qh 2^36 vanishes)
        dq    = 36'(d_3[17:0]) * 36'(est[17:0])
              + ((36'(d_3[17:0]) * 36'(est[FRAC:18]) + 36'(d_3[31:18]) * 36'(est[17:0])) << 18);
        rem   = (((c == 0) ? 36'(xs_3) : 36'(xt_3)) << FRAC) + 36'(d_3) - (dq << 1);
        est   = est + (FRAC+1)'(rem >= two_d);
        if (c == 0) s <= zero_3 ? CW'(1 << (FRAC - 1)) : CW'(est);
        else        t <= zero_3 ? CW'(1 << (FRAC - 1)) : CW'(est);
      end
      face  <= zero_3 ? 3'd4 : face_3;
      zero  <= zero_3;
      recip <= 17'(r_3 >> 15);
      k     <= k_3;
    end
  end
endmodule
