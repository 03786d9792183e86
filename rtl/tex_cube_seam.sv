// tex_cube_seam: a cube map probe that lies beyond its face (an anisotropic probe near a seam,
// laid along the face's axes by tex_probe) moved onto the face it lies over (the model's
// stage::cube_reproject and cube_probe, bit for bit): its (s, t) on the unit cube's plane of its
// face (sc = 2s - 1, tc = 2t - 1, |rc| = 1, the table inverted, each saturated to 32 bits) is a
// direction, whose face and exact coordinates tex_cube_face makes. A probe inside its face
// (0 <= s, t <= 1) and any other probe pass unchanged; every probe takes the same 4 clocks, with
// its side data beside it.
// Handshake: stall-enable: the probe advances when en is high (tex_cube_face's registers only
//   while a probe to move is in them; the rest wait in a tex_delay line). Latency: 4 clocks.
//   Throughput: 1 probe per clock.
// Ports:
//   in_valid        : a probe on the pins (out_valid: 4 clocks later)
//   in_cube         : the probe is a cube map lookup's (not a texel fetch's)
//   in_u, in_v      : its coordinates, signed Q8.24 (a cube probe: its face's s, t, any value)
//   in_face         : its face, 0..5 (+X .. -Z)
//   in_side         : SIDE_W bits carried beside it (valid, level fields, tags)
//   out_valid, out_u, out_v, out_face, out_side : 4 clocks later; a cube probe's on the face it lies over
module tex_cube_seam #(
  parameter int SIDE_W = 1
) (
  input  logic                                   clk,
  input  logic                                   rst,
  input  logic                                   en,
  input  logic                                   in_valid,
  input  logic                                   in_cube,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] in_u,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] in_v,
  input  logic [2:0]                             in_face,
  input  logic [SIDE_W-1:0]                      in_side,
  output logic                                   out_valid,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] out_u,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] out_v,
  output logic [2:0]                             out_face,
  output logic [SIDE_W-1:0]                      out_side
);
  localparam int CW = tex_pkg::REQ_COORD_W;
  localparam int ONE = 1 << tex_pkg::COORD_FRAC;
  localparam int PW = 1 + CW + CW + 3 + SIDE_W;  // {moved, u, v, face, side}

  // Beyond the face: the direction of its point on the face's plane.
  logic outside;
  assign outside = in_valid && in_cube && (in_u < 0 || in_u > CW'(ONE) || in_v < 0 || in_v > CW'(ONE));
  function automatic logic signed [CW-1:0] saturate(input logic signed [CW+2:0] x);
    if (x > (CW+3)'(32'sh7FFF_FFFF)) saturate = 32'sh7FFF_FFFF;
    else if (x < -(CW+3)'(33'sh0_8000_0000)) saturate = 32'sh8000_0000;
    else saturate = CW'(x);
  endfunction
  logic signed [CW+2:0] sc, tc;  // 2s - 1, 2t - 1 (exact)
  assign sc = ((CW+3)'(in_u) <<< 1) - (CW+3)'(ONE);
  assign tc = ((CW+3)'(in_v) <<< 1) - (CW+3)'(ONE);
  logic signed [CW-1:0] rx, ry, rz;
  always_comb begin
    case (in_face)
      3'd0:    begin rx = CW'(ONE);  ry = saturate(-tc); rz = saturate(-sc); end
      3'd1:    begin rx = -CW'(ONE); ry = saturate(-tc); rz = saturate(sc);  end
      3'd2:    begin rx = saturate(sc); ry = CW'(ONE);  rz = saturate(tc);  end
      3'd3:    begin rx = saturate(sc); ry = -CW'(ONE); rz = saturate(-tc); end
      3'd4:    begin rx = saturate(sc); ry = saturate(-tc); rz = CW'(ONE);  end
      default: begin rx = saturate(-sc); ry = saturate(-tc); rz = -CW'(ONE); end
    endcase
  end

  logic [2:0]           face;
  logic signed [CW-1:0] s, t;
  logic                 zero, rc_negative_1;  // (tex_cube's derivatives' outputs: not used here)
  logic [16:0]          recip;
  logic [4:0]           k;
  logic [2:0]           face_1;
  tex_cube_face u_face (
    .clk(clk), .en(en), .valid(outside), .rx(rx), .ry(ry), .rz(rz), .face(face), .s(s), .t(t), .zero(zero),
    .recip(recip), .k(k), .face_1(face_1), .rc_negative_1(rc_negative_1)
  );
  logic unused_derivative_outputs;
  assign unused_derivative_outputs = ^{zero, recip, k, face_1, rc_negative_1};

  // The probe beside it, 4 clocks.
  logic [PW-1:0] line_out;
  tex_delay #(.W(PW), .DEPTH(4)) u_line (
    .clk(clk), .rst(rst), .en(en), .in_valid(in_valid), .in_data({outside, in_u, in_v, in_face, in_side}),
    .out_valid(out_valid), .out_data(line_out)
  );
  logic                 moved;
  logic signed [CW-1:0] u4, v4;
  logic [2:0]           face4;
  assign {moved, u4, v4, face4, out_side} = line_out;
  assign out_u    = moved ? s : u4;
  assign out_v    = moved ? t : v4;
  assign out_face = moved ? face : face4;
endmodule
