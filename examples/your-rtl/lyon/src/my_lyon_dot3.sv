// my_lyon_dot3 - exact dot product of two signed 3-vectors (no rounding; the caller requantizes):
//   sum = (a_x*b_x + a_y*b_y) + a_z*b_z
// Components are packed from bit 0 up (x in the low bits), each AW or BW bits wide.
// Combinational. Used for z = N'.N', dot = N.V, diff = N.L and dd = D.D.
module my_lyon_dot3 #(
  parameter int AW = 12,
  parameter int BW = 12,
  localparam int PW = AW + BW,     // one product
  localparam int SW = AW + BW + 2  // the sum of three
) (
  input  logic [3*AW-1:0] a_i,
  input  logic [3*BW-1:0] b_i,
  output logic [  SW-1:0] sum_o
);
  logic signed [PW-1:0] p_x, p_y, p_z;

  assign p_x   = $signed(a_i[0*AW+:AW]) * $signed(b_i[0*BW+:BW]);
  assign p_y   = $signed(a_i[1*AW+:AW]) * $signed(b_i[1*BW+:BW]);
  assign p_z   = $signed(a_i[2*AW+:AW]) * $signed(b_i[2*BW+:BW]);
  assign sum_o = (SW'(p_x) + SW'(p_y)) + SW'(p_z);
endmodule
