// The SystemVerilog that Verilator reads but Yosys 0.23 (synth) or Icarus Verilog 11
// (--simulator icarus) does not, said in one line when one of them fails on a design
// (docs/your-rtl.md, "The portable subset").
#pragma once

#include <string>
#include <string_view>

namespace phongsim {

// When `tool_output` names a source line (file:line) that uses a construct `tool` ("Yosys" or
// "Icarus Verilog 11") is known not to read, "; <file>:<line> has <construct>, which <tool> does
// not read: instead, <what to write> (docs/your-rtl.md, "The portable subset")"; else "".
[[nodiscard]] std::string portable_hint(std::string_view tool_output, std::string_view tool);

}  // namespace phongsim
