// tex_layer: the layer an array request reads (the model's stage::request_layer). A sample's or a
// gather's layer coordinate is rounded to the nearest layer, a tie to the even one, and clamped
// to 0..layers - 1 (Vulkan's layer of an array image: no filtering across layers; a 2D texture is
// an array of one layer); a texel fetch's layer is an integer, taken as it is, and `outside` when
// it is not 0..layers - 1 (the fetch then reads nothing and answers 0).
// Handshake: none. Latency: 0 (combinational: an increment and two compares, at tex_unit_cached's
//   request port, into tex_probe's tag). Throughput: 1 per clock.
// Ports:
//   coord     : signed REQ_COORD_W bits, Q16.16 layers (a fetch: a signed integer)
//   fetch     : the request is a texel fetch
//   layers_m1 : unsigned LAYER_W bits, the texture's layer count - 1
//   layer     : unsigned LAYER_W bits, the layer read (a fetch outside the layers: its low bits)
//   outside   : a fetch's layer lies outside 0..layers - 1
module tex_layer (
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] coord,
  input  logic                                   fetch,
  input  logic [tex_pkg::LAYER_W-1:0]            layers_m1,
  output logic [tex_pkg::LAYER_W-1:0]            layer,
  output logic                                   outside
);
  localparam int CW = tex_pkg::REQ_COORD_W;
  localparam int FR = tex_pkg::TEXEL_COORD_FRAC;
  localparam int LW = tex_pkg::LAYER_W;
  // Round half to even: (coord + 1/2 - 2^-16 + the integer part's lowest bit) >> 16, exact in one
  // more bit than the coordinate.
  logic signed [CW:0]    biased;
  logic signed [CW-FR:0] rounded;
  assign biased  = $signed({coord[CW-1], coord}) + $signed((CW+1)'((1 << (FR - 1)) - 1))
                   + $signed({{CW{1'b0}}, coord[FR]});
  assign rounded = (CW-FR+1)'(biased >>> FR);
  logic signed [CW-FR:0] last_r;  // layers - 1, as wide as the rounded coordinate
  logic signed [CW-1:0]  last_i;  // and as a fetch's integer
  assign last_r = $signed({{(CW-FR+1-LW){1'b0}}, layers_m1});
  assign last_i = $signed({{(CW-LW){1'b0}}, layers_m1});
  always_comb begin
    outside = fetch && (coord < 0 || coord > last_i);
    if (fetch)                layer = coord[LW-1:0];
    else if (rounded < 0)     layer = '0;
    else if (rounded > last_r) layer = layers_m1;
    else                      layer = rounded[LW-1:0];
  end
endmodule
