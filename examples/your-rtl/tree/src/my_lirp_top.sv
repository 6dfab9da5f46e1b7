// my_lirp_top: examples/your-rtl/my_lirp.sv as a real RTL tree has it (docs/your-rtl.md, "File
// lists, include folders and defines"): a top in a file list (lists/files.f) that names a package
// (src/my_lirp_modes.sv), an include file in an include folder (inc/my_lirp_top.svh) and a define
// (MY_LIRP_TIES_UP: 1 makes ties round up, the failing example).
//   phongsim cosim lirp -F examples/your-rtl/tree/lists/files.f --top my_lirp_top
`include "my_lirp_top.svh"
module my_lirp_top #(
  parameter int PFmt        = 32'h1010a,
  parameter int AFmt        = 32'h0010a,
  parameter int OutFmt      = 32'h1010a,
  parameter int OutRound    = my_lirp_modes::TiesEven,
  parameter int OutOverflow = 1,
  localparam int PW = PFmt / 65536 + (PFmt / 256) % 256 + PFmt % 256,
  localparam int AW = AFmt / 65536 + (AFmt / 256) % 256 + AFmt % 256,
  localparam int OW = OutFmt / 65536 + (OutFmt / 256) % 256 + OutFmt % 256
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            in_valid_i,
  output logic            in_ready_o,
  input  logic [3*PW-1:0] in_p0_i,
  input  logic [3*PW-1:0] in_p1_i,
  input  logic [  AW-1:0] in_a_i,
  output logic            out_valid_o,
  input  logic            out_ready_i,
  output logic [3*OW-1:0] out_p_o
);
  my_lirp #(
    .PFmt(PFmt), .AFmt(AFmt), .OutFmt(OutFmt), .OutRound(OutRound), .OutOverflow(OutOverflow),
    .TiesUp(1'(`MY_LIRP_TIES_UP))
  ) u_lirp (.*);
endmodule
