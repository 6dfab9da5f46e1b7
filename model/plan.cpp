#include "model/plan.h"

#include <fmt/format.h>

#include <atomic>
#include <cstdlib>
#include <string_view>

#include "base/error.h"

namespace phongsim::fx {
namespace {

constexpr Isa kIsas[] = {Isa::baseline, Isa::avx2, Isa::avx512};

bool supported(Isa isa) {
#ifdef PHONGSIM_ISA_CLONES
  __builtin_cpu_init();  // harmless if done; needed if this runs before libgcc's constructor
#endif
  switch (isa) {
    case Isa::baseline:
      return true;
#ifdef PHONGSIM_ISA_CLONES
    case Isa::avx2:
      return __builtin_cpu_supports("x86-64-v3") > 0;
    case Isa::avx512:
      return __builtin_cpu_supports("x86-64-v4") > 0;
#endif
    default:
      return false;
  }
}

Isa checked(Isa isa, std::string_view source) {
  if (!supported(isa)) {
    throw Error(fmt::format("{}{}: this CPU does not run it (it runs {})", source, isa_name(isa),
                            isa_name(supported_isas().back())));
  }
  return isa;
}

Isa from_environment() {
  const char* env = std::getenv("PHONGSIM_ISA");
  if (env == nullptr || *env == '\0') return supported_isas().back();
  for (const Isa isa : kIsas) {
    if (std::string_view(env) == isa_name(isa)) return checked(isa, "PHONGSIM_ISA=");
  }
  throw Error(fmt::format("PHONGSIM_ISA={}: not an instruction set (baseline, avx2, avx512)", env));
}

std::atomic<int> g_chosen{-1};  // an Isa once chosen

}  // namespace

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::avx2:
      return "avx2";
    case Isa::avx512:
      return "avx512";
    default:
      return "baseline";
  }
}

std::vector<Isa> supported_isas() {
  std::vector<Isa> isas;
  for (const Isa isa : kIsas) {
    if (supported(isa)) isas.push_back(isa);
  }
  return isas;
}

Isa kernel_isa() {
  int chosen = g_chosen.load(std::memory_order_relaxed);
  if (chosen < 0) {
    chosen = static_cast<int>(from_environment());
    g_chosen.store(chosen, std::memory_order_relaxed);
  }
  return static_cast<Isa>(chosen);
}

void set_kernel_isa(Isa isa) {
  g_chosen.store(static_cast<int>(checked(isa, "")), std::memory_order_relaxed);
}

}  // namespace phongsim::fx
