// Golden vector files: evaluate a CSV of input vectors through the model or the RTL and write
// the outputs as CSV. The same input through either backend gives byte-identical files.
//
// Input: a header row naming every input field of the pipeline (any order), then one row per
// vector. Values are raw integers in the field's format (decimal, or 0x hex for the bit
// pattern), or reals with `real` (rounded to nearest, ties to even; out of range is an error).
// Empty lines and lines starting with '#' are skipped.
// Output: a header row of the output fields, one row per output transaction in order (for
// one-output-per-vector pipelines such as LIRP, row i belongs to input row i); raw integers, or
// reals with `real`.
//
// Both files are streamed: a row is read when the model or the RTL takes it and an output row
// written when it comes out, so memory does not grow with the number of vectors.
#pragma once

#include <cstdio>
#include <filesystem>

#include "model/pipeline.h"
#include "sim/cosim/contract.h"
#include "sim/cosim/cosim.h"

namespace phongsim {

struct EvalResult {
  std::size_t rows = 0;       // output rows written
  std::uint64_t vectors = 0;  // input vectors read
  ContractCounts contract;    // the vectors against the input contract (none: nothing counted)
};

// Writes the output CSV to `out`. `make_dut` empty means the model backend. Counts the vectors
// against `contract` in file order (the pipeline's, sim/cosim/contract.h; a default one counts
// nothing). Throws Error naming file, line and column for malformed input (what was written to
// `out` by then is the caller's to discard: base/output_file.h does).
// With `stages` and `stages_out`, also writes the model's stage values of every vector to
// `stages_out` as CSV, one row per vector and stage (a pipeline's stages can vary from vector to
// vector): vector,stage,format,raw,real.
using StagesFn = std::vector<StageValue> (*)(PipelineModel&, std::span<const std::int64_t>);
EvalResult eval_csv(PipelineModel& model, const DutFactory& make_dut,
                    const std::filesystem::path& in, std::FILE* out, bool real,
                    InputContract contract = {}, StagesFn stages = nullptr,
                    std::FILE* stages_out = nullptr);

}  // namespace phongsim
