// `hexdyn envelope ENVELOPE -o FILE [-v]` (cli/command.hpp; envelope/envelope.hpp).
#include <iostream>

#include "hexdyn/cli/subcommands.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/io/output.hpp"

namespace hexdyn::cli {

int envelope_command(const Args& args) {
  const EnvelopeSpec spec = load_envelope_spec(args.input);
  check_output_target(args.output, spec.inputs);  // the envelope file is one of them
  const ProgressScope progress(std::cerr, "envelope", 5.0, "envelope");  // a line every 5 s
  const EnvelopeResult result = compute_envelope(spec, args.verbose ? &std::cerr : nullptr);
  write_envelope_file(args.output, spec, result);
  std::cerr << "hexdyn: wrote " << args.output << " (" << result.probes.size() << " probes, "
            << result.wall_time_s << " s)\n";
  return 0;
}

}  // namespace hexdyn::cli
