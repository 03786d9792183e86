// tex_cube: a cube map lookup's face, its coordinates and their derivatives (the model's
// stage::cube_face and cube_derivatives, docs/numerics.md "Cube maps", bit for bit): tex_cube_face
// selects the face and makes the exact s, t (and the reciprocal of |rc|); beside it, the
// derivatives of s and t by the quotient rule in block floating point:
//   clock 1  the direction's six derivatives registered (tex_cube_face: face select)
//   clock 2  the face's (dsc, dtc, d|rc|) per screen axis by clock 1's face, shifted by a shared e
//            to 18 bits (tex_cube_face: R1)
//   clock 3  held (tex_cube_face: R2)      clock 4  held (tex_cube_face: s, t)
//   clock 5  g = a 2^16 - c b per derivative (c: 2s - 1 in 17 bits), normalized to 18 bits
//   clock 6  g (R2 >> 14), shifted by e + k + f - 41, rounded half up, saturated to 32 bits
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

  // Which clocks hold a cube lookup (bit n-1: clock n's registers).
  logic [5:1] held;
  always_ff @(posedge clk) if (en) held <= {held[4:1], cube};

  // ---------------------------------------------------------------- clocks 1-4: the face
  logic [2:0]           face_4, face_1;
  logic signed [CW-1:0] s_4, t_4;
  logic                 zero_4, rc_negative_1;
  logic [17:0]          rm_4;            // R2 >> 14: (2^16, 2^17]
  logic [4:0]           k_4;
  tex_cube_face u_face (
    .clk(clk), .en(en), .valid(cube), .rx(rx), .ry(ry), .rz(rz), .face(face_4), .s(s_4), .t(t_4), .zero(zero_4),
    .recip(rm_4), .k(k_4), .face_1(face_1), .rc_negative_1(rc_negative_1)
  );

  // ---------------------------------------------------------------- clock 1: the derivatives
  logic signed [CW-1:0] d_1 [6];  // dxdx, dydx, dzdx, dxdy, dydy, dzdy
  always_ff @(posedge clk) begin
    if (en && cube) begin
      d_1[0] <= dxdx;
      d_1[1] <= dydx;
      d_1[2] <= dzdx;
      d_1[3] <= dxdy;
      d_1[4] <= dydy;
      d_1[5] <= dzdy;
    end
  end

  // ---------------------------------------------------------------- clock 2: picks, shift
  // Per screen axis the face's (dsc, dtc, d|rc|) by the table, then e: the largest magnitude of
  // the three keeps 17 bits (|v| <= 2^31: e <= 15).
  logic signed [17:0] as_2 [2], at_2 [2], b_2 [2];
  logic [3:0]         e_2 [2];
  always_ff @(posedge clk) begin
    if (en && held[1]) begin
      logic signed [EW-1:0] dx, dy, dz, dsc, dtc, drc, darc;
      logic [EW-2:0] m, mag;
      logic [3:0] e;
      for (int a = 0; a < 2; a++) begin
        dx = EW'(d_1[a*3 + 0]);
        dy = EW'(d_1[a*3 + 1]);
        dz = EW'(d_1[a*3 + 2]);
        case (face_1)
          3'd0:    begin dsc = -dz; dtc = -dy; drc = dx; end
          3'd1:    begin dsc = dz;  dtc = -dy; drc = dx; end
          3'd2:    begin dsc = dx;  dtc = dz;  drc = dy; end
          3'd3:    begin dsc = dx;  dtc = -dz; drc = dy; end
          3'd4:    begin dsc = dx;  dtc = -dy; drc = dz; end
          default: begin dsc = -dx; dtc = -dy; drc = dz; end
        endcase
        darc = rc_negative_1 ? -drc : drc;
        m = '0;
        mag = (EW-1)'(dsc[EW-1] ? -dsc : dsc);
        if (mag > m) m = mag;
        mag = (EW-1)'(dtc[EW-1] ? -dtc : dtc);
        if (mag > m) m = mag;
        mag = (EW-1)'(darc[EW-1] ? -darc : darc);
        if (mag > m) m = mag;
        e = '0;
        for (int j = 17; j < EW - 1; j++) if (m[j]) e = 4'(j - 16);
        e_2[a]  <= e;
        as_2[a] <= 18'(dsc >>> e);
        at_2[a] <= 18'(dtc >>> e);
        b_2[a]  <= 18'(darc >>> e);
      end
    end
  end

  // ---------------------------------------------------------------- clocks 3-4: held
  logic signed [17:0] as_4 [2], at_4 [2], b_4 [2];
  logic [3:0]         e_4 [2];
  logic signed [17:0] as_3 [2], at_3 [2], b_3 [2];
  logic [3:0]         e_3 [2];
  always_ff @(posedge clk) begin
    if (en && held[2]) begin
      as_3 <= as_2;
      at_3 <= at_2;
      b_3  <= b_2;
      e_3  <= e_2;
    end
    if (en && held[3]) begin
      as_4 <= as_3;
      at_4 <= at_3;
      b_4  <= b_3;
      e_4  <= e_3;
    end
  end

  // ---------------------------------------------------------------- clock 5: g per derivative
  // Derivative i = axis * 2 + coordinate: ds/dx, dt/dx, ds/dy, dt/dy.
  logic signed [17:0]   gm_5 [4];
  logic [4:0]           f_5 [4];
  logic signed [CW-1:0] s_5, t_5;
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
        sc2 = (FRAC+2)'({(i % 2 == 0) ? s_4[FRAC:0] : t_4[FRAC:0], 1'b0}) - (FRAC+2)'(1 << FRAC);  // 2s - 1, Q.24
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
      face <= face_5;
      s    <= s_5;
      t    <= t_5;
    end
  end
  assign dsdx = deriv_6[0];
  assign dtdx = deriv_6[1];
  assign dsdy = deriv_6[2];
  assign dtdy = deriv_6[3];
endmodule
