// tex_cube: a cube map lookup's face and its coordinates (the model's stage::cube_face,
// cube_reciprocal and cube_derivatives, docs/numerics.md "Cube maps", bit for bit): the direction
// (rx, ry, rz) selects a face by its major axis (ties to rz, then ry) and (sc, tc, rc) by the
// specification's table; s = (sc / |rc| + 1) / 2 and t likewise are the exact quotients rounded
// to the nearest Q8.24 (a half up), reached by a reciprocal and a correction step rather than a
// divider; the derivatives of s and t by the quotient rule, in block floating point.
//   clock 1  face select, the table's picks, |rc| normalized by k to D in [2^31, 2^32), and
//            X = sc + |rc| (tc + |rc|) shifted alike (the quotient X / D is unchanged)
//   clock 2  R1: a 128-entry table of 9 bits and a Newton step; each screen axis' derivatives
//            (dsc, dtc, d|rc|) shifted by a shared e to 18 bits
//   clock 3  R2 = R1's Newton step: R2 <= 2^62 / D within 2^-25 (from below)
//   clock 4  the estimate Q = (X R2 + 2^38) >> 39, at most 1 below the exact rounded quotient
//            floor((X 2^24 + D) / 2D), then the remainder against 2D: s, t exact
//   clock 5  g = a 2^16 - c b per derivative (c: 2s - 1 in 17 bits), normalized to 18 bits
//   clock 6  g R2 >> 14, shifted by e + k + f - 41, rounded half up, saturated to 32 bits
// A direction (0, 0, 0) selects +Z at its centre, with derivatives 0.
// Handshake: stall-enable, like tex_lambda: the registers of clock n load when en is high and
//   clock n - 1 holds a cube lookup (`cube` at the input): a 2D request leaves every register as
//   it was (the top carries its own request beside this one and takes the outputs only for a
//   cube), so that a simulator spends nothing here on 2D texturing.
// Latency: 6 clocks from the pins to the outputs (registers). Throughput: 1 per clock.
// Ports:
//   cube                    : the request at the pins is a cube lookup (gates the registers)
//   rx, ry, rz              : the direction, signed Q8.24 (any length, REQ_COORD_W bits)
//   dxdx .. dzdy            : its derivatives per screen pixel, signed Q8.24 (d rx / dx, d ry / dx,
//                             d rz / dx, then / dy)
//   face                    : 0..5 = +X, -X, +Y, -Y, +Z, -Z (the cube's layer)
//   s, t                    : the face's coordinates, signed Q8.24 in [0, 1] (REQ_COORD_W bits)
//   dsdx, dtdx, dsdy, dtdy  : their derivatives, signed Q8.24 face widths per pixel (saturated)
module tex_cube (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic                                   cube,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] rx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] ry,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] rz,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dxdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dydx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dzdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dxdy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dydy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dzdy,
  output logic [2:0]                             face,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] s,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] t,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] dsdx,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] dtdx,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] dsdy,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] dtdy
);
  localparam int CW = tex_pkg::REQ_COORD_W;  // 32
  localparam int EW = CW + 1;                // a table pick: -INT32_MIN fits
  localparam int FRAC = tex_pkg::COORD_FRAC; // 24

  // The reciprocal's first 9 bits: floor(2^16 / (129 + i)) for D's bits 30..24 = i.
  function automatic logic [128*9-1:0] recip_table();
    for (int i = 0; i < 128; i++) recip_table[i*9 +: 9] = 9'(65536 / (129 + i));
  endfunction
  localparam logic [128*9-1:0] RECIP = recip_table();

  // Which clocks hold a cube lookup (bit n-1: clock n's registers).
  logic [5:1] held;
  always_ff @(posedge clk) if (en) held <= {held[4:1], cube};

  // ---------------------------------------------------------------- clock 1: face, normalize
  logic [2:0]           face_1;
  logic                 zero_1;          // (0, 0, 0)
  logic [CW-1:0]        d_1;             // |rc| << k: [2^31, 2^32)
  logic [CW+1:0]        xs_1, xt_1;      // (sc + |rc|) << k, (tc + |rc|) << k: <= 2^33
  logic [4:0]           k_1;
  logic signed [EW-1:0] dsc_1 [2], dtc_1 [2], darc_1 [2];  // per screen axis (0: x, 1: y)
  always_ff @(posedge clk) begin
    if (en && cube) begin
      logic [EW-1:0]        ax, ay, az;
      logic signed [EW-1:0] x, y, z, sc, tc, rc, dx, dy, dz, drc;
      logic [CW-1:0]        arc;
      logic [4:0]           k;
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
      arc = CW'(rc[EW-1] ? -rc : rc);  // <= 2^31
      // k = 31 - the leading one of |rc|: D = |rc| << k has its top bit set.
      k = '0;
      for (int b = 0; b < CW; b++) if (arc[b]) k = 5'(CW - 1 - b);
      zero_1 <= arc == '0;
      k_1    <= k;
      d_1    <= arc << k;
      xs_1   <= (CW+2)'(sc + EW'(arc)) << k;
      xt_1   <= (CW+2)'(tc + EW'(arc)) << k;
      // The face's derivatives of (sc, tc, |rc|) along each screen axis (the table's picks).
      for (int a = 0; a < 2; a++) begin
        dx = (a == 0) ? EW'(dxdx) : EW'(dxdy);
        dy = (a == 0) ? EW'(dydx) : EW'(dydy);
        dz = (a == 0) ? EW'(dzdx) : EW'(dzdy);
        if (az >= ax && az >= ay) begin
          dsc_1[a] <= z[EW-1] ? -dx : dx;
          dtc_1[a] <= -dy;
          drc = dz;
        end else if (ay >= ax) begin
          dsc_1[a] <= dx;
          dtc_1[a] <= y[EW-1] ? -dz : dz;
          drc = dy;
        end else begin
          dsc_1[a] <= x[EW-1] ? dz : -dz;
          dtc_1[a] <= -dy;
          drc = dx;
        end
        darc_1[a] <= rc[EW-1] ? -drc : drc;
      end
    end
  end

  // ---------------------------------------------------------------- clock 2: R1, derivative shift
  // A Newton step R' = R + R (2^62 - D R) / 2^62, its products truncated: 2^62 - D R >= 0 since R
  // never passes 1/D, and it is below 2^62 * 2^-7 here (2^-14 in clock 3): 32 bits after >> 30.
  logic [CW-1:0]        d_2, r_2;
  logic [CW+1:0]        xs_2, xt_2;
  logic [4:0]           k_2;
  logic [2:0]           face_2;
  logic                 zero_2;
  logic signed [17:0]   as_2 [2], at_2 [2], b_2 [2];  // dsc, dtc, d|rc| >> e per axis
  logic [3:0]           e_2 [2];
  always_ff @(posedge clk) begin
    if (en && held[1]) begin
      logic [63:0] r0, dr, rd;
      logic [31:0] delta;
      logic [EW-2:0] m, mag;
      logic [3:0] e;
      r0    = 64'(RECIP[32'(d_1[30:24]) * 9 +: 9]) << 22;
      dr    = 64'(d_1) * r0;
      delta = 32'(((64'd1 << 62) - dr) >> 30);
      rd    = r0 * 64'(delta);
      r_2   <= CW'(r0 + (rd >> 32));
      d_2   <= d_1;
      xs_2  <= xs_1;
      xt_2  <= xt_1;
      k_2   <= k_1;
      face_2 <= face_1;
      zero_2 <= zero_1;
      for (int a = 0; a < 2; a++) begin
        // e: the largest magnitude of the three keeps 17 bits (|v| <= 2^31: e <= 15).
        m = '0;
        mag = (EW-1)'(dsc_1[a][EW-1] ? -dsc_1[a] : dsc_1[a]);
        if (mag > m) m = mag;
        mag = (EW-1)'(dtc_1[a][EW-1] ? -dtc_1[a] : dtc_1[a]);
        if (mag > m) m = mag;
        mag = (EW-1)'(darc_1[a][EW-1] ? -darc_1[a] : darc_1[a]);
        if (mag > m) m = mag;
        e = '0;
        for (int j = 17; j < EW - 1; j++) if (m[j]) e = 4'(j - 16);
        e_2[a]  <= e;
        as_2[a] <= 18'(dsc_1[a] >>> e);
        at_2[a] <= 18'(dtc_1[a] >>> e);
        b_2[a]  <= 18'(darc_1[a] >>> e);
      end
    end
  end

  // ---------------------------------------------------------------- clock 3: R2
  logic [CW-1:0]        d_3, r_3;
  logic [CW+1:0]        xs_3, xt_3;
  logic [4:0]           k_3;
  logic [2:0]           face_3;
  logic                 zero_3;
  logic signed [17:0]   as_3 [2], at_3 [2], b_3 [2];
  logic [3:0]           e_3 [2];
  always_ff @(posedge clk) begin
    if (en && held[2]) begin
      logic [63:0] dr, rd;
      logic [31:0] delta;
      dr    = 64'(d_2) * 64'(r_2);
      delta = 32'(((64'd1 << 62) - dr) >> 30);
      rd    = 64'(r_2) * 64'(delta);
      r_3   <= r_2 + CW'(rd >> 32);
      d_3   <= d_2;
      xs_3  <= xs_2;
      xt_3  <= xt_2;
      k_3   <= k_2;
      face_3 <= face_2;
      zero_3 <= zero_2;
      as_3  <= as_2;
      at_3  <= at_2;
      b_3   <= b_2;
      e_3   <= e_2;
    end
  end

  // ---------------------------------------------------------------- clock 4: s, t
  // floor((X 2^24 + D) / 2D) from the estimate and the remainder (36 bits hold it: below 4D).
  logic [FRAC:0]        s_4, t_4;        // 0..2^24
  logic [17:0]          rm_4;            // R2 >> 14: (2^16, 2^17]
  logic [4:0]           k_4;
  logic [2:0]           face_4;
  logic                 zero_4;
  logic signed [17:0]   as_4 [2], at_4 [2], b_4 [2];
  logic [3:0]           e_4 [2];
  always_ff @(posedge clk) begin
    if (en && held[3]) begin
      logic [65:0] prod;
      logic [FRAC:0] est;
      logic [35:0] rem, two_d;
      for (int c = 0; c < 2; c++) begin
        prod  = ((c == 0) ? 66'(xs_3) : 66'(xt_3)) * 66'(r_3) + (66'd1 << 38);
        est   = (FRAC+1)'(prod >> 39);
        two_d = 36'(d_3) << 1;
        rem   = (((c == 0) ? 36'(xs_3) : 36'(xt_3)) << FRAC) + 36'(d_3) - 36'(two_d * 36'(est));
        est   = est + (FRAC+1)'(rem >= two_d);
        if (c == 0) s_4 <= est;
        else        t_4 <= est;
      end
      rm_4  <= 18'(r_3 >> 14);
      k_4   <= k_3;
      face_4 <= face_3;
      zero_4 <= zero_3;
      as_4  <= as_3;
      at_4  <= at_3;
      b_4   <= b_3;
      e_4   <= e_3;
    end
  end

  // ---------------------------------------------------------------- clock 5: g per derivative
  // Derivative i = axis * 2 + coordinate: ds/dx, dt/dx, ds/dy, dt/dy.
  logic signed [17:0]   gm_5 [4];
  logic [4:0]           f_5 [4];
  logic [FRAC:0]        s_5, t_5;
  logic [17:0]          rm_5;
  logic [4:0]           k_5;
  logic [2:0]           face_5;
  logic                 zero_5;
  logic [3:0]           e_5 [2];
  always_ff @(posedge clk) begin
    if (en && held[4]) begin
      logic signed [FRAC+1:0] sc2;
      logic signed [17:0] c, a;
      logic signed [35:0] g;
      logic [35:0] ag;
      logic [4:0] f;
      for (int i = 0; i < 4; i++) begin
        sc2 = (FRAC+2)'({(i % 2 == 0) ? s_4 : t_4, 1'b0}) - (FRAC+2)'(1 << FRAC);  // 2s - 1, Q.24
        c   = 18'(sc2 >>> 8);
        a   = (i % 2 == 0) ? as_4[i / 2] : at_4[i / 2];
        g   = (36'(a) <<< 16) - 36'(c) * 36'(b_4[i / 2]);
        ag  = g[35] ? 36'(-g) : 36'(g);
        f   = '0;
        for (int j = 17; j < 36; j++) if (ag[j]) f = 5'(j - 16);
        gm_5[i] <= 18'(g >>> f);
        f_5[i]  <= f;
      end
      s_5   <= s_4;
      t_5   <= t_4;
      rm_5  <= rm_4;
      k_5   <= k_4;
      face_5 <= face_4;
      zero_5 <= zero_4;
      e_5   <= e_4;
    end
  end

  // ---------------------------------------------------------------- clock 6: the derivatives
  logic signed [CW-1:0] deriv_6 [4];
  always_ff @(posedge clk) begin
    if (en && held[5]) begin
      logic signed [35:0] p;
      logic signed [63:0] q;
      logic signed [6:0]  sh;
      for (int i = 0; i < 4; i++) begin
        p  = 36'(gm_5[i]) * $signed({18'd0, rm_5});
        sh = 7'(e_5[i / 2]) + 7'(k_5) + 7'(f_5[i]) - 7'sd41;  // -41..23
        if (sh >= 0) q = 64'(p) <<< sh;
        else         q = (64'(p) + (64'sd1 <<< (-sh - 7'sd1))) >>> (-sh);
        if (zero_5) deriv_6[i] <= '0;
        else if (q > 64'sh7FFF_FFFF) deriv_6[i] <= 32'sh7FFF_FFFF;
        else if (q < -64'sh8000_0000) deriv_6[i] <= 32'sh8000_0000;
        else deriv_6[i] <= CW'(q);
      end
      face <= zero_5 ? 3'd4 : face_5;
      s    <= zero_5 ? CW'(1 << (FRAC - 1)) : CW'(s_5);
      t    <= zero_5 ? CW'(1 << (FRAC - 1)) : CW'(t_5);
    end
  end
  assign dsdx = deriv_6[0];
  assign dtdx = deriv_6[1];
  assign dsdy = deriv_6[2];
  assign dtdy = deriv_6[3];
endmodule
