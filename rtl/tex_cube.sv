// tex_cube: a cube map lookup's face, its coordinates and their derivatives (the model's
// stage::cube_face and cube_derivatives, docs/numerics.md "Cube maps", bit for bit): tex_cube_face
// selects the face and makes the exact s, t (and the reciprocal of |rc|); beside it, the
// derivatives of s and t by the quotient rule in block floating point:
//   clock 1  the direction's six derivatives registered (tex_cube_face: face select)
//   clock 2  the face's (dsc, dtc, d|rc|) per screen axis by clock 1's face, shifted by a shared e
//            to 18 bits (tex_cube_face: R1)
//   clock 3  held (tex_cube_face: R2)      clock 4  held (tex_cube_face: s, t)
//   clock 5  g = a 2^16 - c b per derivative (c: 2s - 1 in 17 bits), normalized to 18 bits
//   clock 6  g (R2 >> 15), shifted by e + k + f - 40, rounded half up, saturated to 32 bits
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
  logic [16:0]          rm_4;            // R2 >> 15: (2^15, 2^16]
  logic [4:0]           k_4;
  tex_cube_face u_face (
    .clk(clk), .en(en), .valid(cube), .rx(rx), .ry(ry), .rz(rz), .face(face_4), .s(s_4), .t(t_4), .zero(zero_4),
    .recip(rm_4), .k(k_4), .face_1(face_1), .rc_negative_1(rc_negative_1)
  );

  // ---------------------------------------------------------------- clock 1: the derivatives
  // (flat vectors for the arrays here: Yosys 0.23 copies no unpacked arrays and has no 2D packed ones)
  logic [6*CW-1:0] d_1;  // dxdx, dydx, dzdx, dxdy, dydy, dzdy at [i*CW +: CW]
  always_ff @(posedge clk) begin
    if (en && cube) begin
      d_1 <= {dzdy, dydy, dxdy, dzdx, dydx, dxdx};
    end
  end

  // ---------------------------------------------------------------- clock 2: picks, shift
  // Per screen axis the face's (dsc, dtc, d|rc|) by the table, then e: the largest magnitude of
  // the three keeps 17 bits (|v| <= 2^31: e <= 15).
  logic [2*18-1:0] as_2, at_2, b_2;  // axis a at [a*18 +: 18], signed
  logic [2*4-1:0]  e_2;
  always_ff @(posedge clk) begin
    if (en && held[1]) begin
      logic signed [EW-1:0] dx, dy, dz, dsc, dtc, drc, darc;
      logic [EW-2:0] m, mag;
      logic [3:0] e;
      for (int a = 0; a < 2; a++) begin
        dx = EW'($signed(d_1[(a*3 + 0)*CW +: CW]));
        dy = EW'($signed(d_1[(a*3 + 1)*CW +: CW]));
        dz = EW'($signed(d_1[(a*3 + 2)*CW +: CW]));
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
        e_2[a*4 +: 4]   <= e;
        as_2[a*18 +: 18] <= 18'(dsc >>> e);
        at_2[a*18 +: 18] <= 18'(dtc >>> e);
        b_2[a*18 +: 18]  <= 18'(darc >>> e);
      end
    end
  end

  // ---------------------------------------------------------------- clocks 3-4: held
  logic [2*18-1:0] as_4, at_4, b_4, as_3, at_3, b_3;
  logic [2*4-1:0]  e_4, e_3;
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
  logic [4*18-1:0]      gm_5;  // derivative i at [i*18 +: 18], signed
  logic [4*5-1:0]       f_5;
  logic signed [CW-1:0] s_5, t_5;
  logic [16:0]          rm_5;
  logic [4:0]           k_5;
  logic [2:0]           face_5;
  logic                 zero_5;
  logic [2*4-1:0]       e_5;
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
        a   = $signed((i % 2 == 0) ? as_4[(i / 2)*18 +: 18] : at_4[(i / 2)*18 +: 18]);
        g   = (36'(a) <<< 16) - 36'(c) * 36'($signed(b_4[(i / 2)*18 +: 18]));
        ag  = g[35] ? 36'(-g) : 36'(g);
        f   = '0;
        for (int j = 17; j < 36; j++) if (ag[j]) f = 5'(j - 16);
        gm_5[i*18 +: 18] <= 18'(g >>> f);
        f_5[i*5 +: 5]    <= f;
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
  logic [4*CW-1:0]      deriv_6;
  always_ff @(posedge clk) begin
    if (en && held[5]) begin
      logic signed [35:0] p;
      logic signed [63:0] q;
      logic signed [6:0]  sh;
      for (int i = 0; i < 4; i++) begin
        p  = 36'($signed(gm_5[i*18 +: 18])) * 36'($signed({1'b0, rm_5}));  // (18 x 18 signed)
        sh = 7'(e_5[(i / 2)*4 +: 4]) + 7'(k_5) + 7'(f_5[i*5 +: 5]) - 7'sd40;  // -40..24
        if (sh >= 0) q = 64'(p) <<< sh;
        else         q = (64'(p) + (64'sd1 <<< (-sh - 7'sd1))) >>> (-sh);
        if (zero_5) deriv_6[i*CW +: CW] <= '0;
        else if (q > 64'sh7FFF_FFFF) deriv_6[i*CW +: CW] <= 32'sh7FFF_FFFF;
        else if (q < -64'sh8000_0000) deriv_6[i*CW +: CW] <= 32'sh8000_0000;
        else deriv_6[i*CW +: CW] <= CW'(q);
      end
      face <= face_5;
      s    <= s_5;
      t    <= t_5;
    end
  end
  assign {dtdy, dsdy, dtdx, dsdx} = deriv_6;
endmodule
