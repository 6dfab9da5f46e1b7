// The Verilator arguments of an RTL plugin: phongsim's own (the defaults, the --x-init random and
// coverage variants) and the ones a user adds through $PHONGSIM_VERILATOR_FLAGS, accepted only
// from a list of arguments that cannot change the design or how it simulates. A verdict names
// the configuration's parameters and the RTL given; an argument that could change either (a
// parameter, a define, a source, the top, the X semantics, a file of more arguments) is refused.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace phongsim {

// The arguments `text` (white-space separated) stands for, each checked against the allowlist
// the way Verilator reads it (one dash or two): optimization (-O0..-O3, -O<letters>,
// -f[no-]<optimization>), --threads N and the other sizing options (--output-split N,
// --unroll-count N, ...), trace options (--trace-depth N, --trace-structs, ...), lint warnings
// (-Wno-<CODE>, -Wall, ...), and -CFLAGS/-LDFLAGS whose value is a compiler optimization or
// debugging flag from a list (-O2, -march=native, -fno-plt, -g, -flto, -frandom-seed=X, ...).
// Error naming the first argument that is not on the list, and why.
[[nodiscard]] std::vector<std::string> verilator_extra_flags(std::string_view text);

// $PHONGSIM_VERILATOR_FLAGS through verilator_extra_flags (empty when unset).
[[nodiscard]] std::vector<std::string> verilator_env_flags();

}  // namespace phongsim
