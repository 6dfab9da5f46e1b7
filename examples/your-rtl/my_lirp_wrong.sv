// my_lirp_wrong: my_lirp with a deliberate bug (ties round up instead of to even), the example of
// a failing comparison in docs/your-rtl.md. Pass both files:
//   phongsim cosim lirp --rtl examples/your-rtl/my_lirp.sv examples/your-rtl/my_lirp_wrong.sv \
//     --top my_lirp_wrong
module my_lirp_wrong #(
  parameter int PFmt        = 32'h1010a,
  parameter int AFmt        = 32'h0010a,
  parameter int OutFmt      = 32'h1010a,
  parameter int OutRound    = 2,
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
    .TiesUp(1'b1)
  ) u_lirp (.*);
endmodule
