// TEX_PARAM_ERROR(msg): the failure of an elaboration-time parameter check, in a generate branch of
// every module that checks its parameters (each includes this file). $error at elaboration
// (Verilator, Yosys); Icarus 11 has no elaboration-time $error, so an initial $fatal there.
`ifndef TEX_PARAM_ERROR
`ifdef __ICARUS__
`define TEX_PARAM_ERROR(msg) initial $fatal(1, msg);
`else
`define TEX_PARAM_ERROR(msg) $error(msg);
`endif
`endif
