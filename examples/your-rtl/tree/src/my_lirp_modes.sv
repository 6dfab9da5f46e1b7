// The rounding modes of the contract's OutRound parameter, as a package in a file of any name
// (phongsim compiles the files that declare packages first, whatever they are called).
package my_lirp_modes;
  localparam int Floor = 0;
  localparam int TiesUp = 1;
  localparam int TiesEven = 2;
endpackage
