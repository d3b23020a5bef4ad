#pragma once
/// \file cases.hpp
/// Paired values of a study file (docs/user/sweeps.md#cases): a list of cases, each a label
/// and the scene keys it sets together, as a sweep's cases axis and an envelope's `cases:`
/// write them:
///
///     - {label: phantomx, robot.urdf: ../robots/phantomx_mark4.urdf, robot.forward_axis: +x}
///     - {label: kraby, robot.urdf: ../robots/kraby.urdf, robot.forward_axis: +y}
///
/// Labels are non-empty, single-line and distinct; every case sets the same keys (those of
/// the first case, in its order), each a dotted key path holding a single value or a list;
/// p/q is the number p divided by q; a robot.urdf value is a path relative to the study
/// file (stored absolute).
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/spec_reader.hpp"

namespace YAML {
class Node;
}

namespace hexdyn {

struct CaseList {
  std::vector<std::string> labels;               ///< one per case
  std::vector<std::string> keys;                 ///< the keys each case sets
  std::vector<std::vector<std::string>> values;  ///< [case][key]: YAML text for apply_override
  std::size_t size() const { return labels.size(); }
  /// The overrides of case `c`, in the order of `keys`.
  std::vector<Override> overrides(std::size_t c) const;
  /// "k1=v1, k2=v2" of case `c`, for messages.
  std::string text(std::size_t c) const;
};

/// Reads the list at `path` (e.g. "axes[0].cases") of the study file `file`. Throws
/// ConfigError "FILE: path[k].key: got X, expected Y" (via `r`).
CaseList read_case_list(const SpecReader& r, const YAML::Node& cases, const std::string& path,
                        const std::string& file);

/// Each case with all its keys on the scene tree `tree` (the base with `set:`), validated:
/// a case that is not valid there throws ConfigError "FILE: path[k] (LABEL: k=v, ...): why".
void check_cases_on(const SpecReader& r, const CaseList& cases, const YAML::Node& tree,
                    const std::string& path);

/// Adds each URDF a case names to `inputs` (role "URDF"), so that hashes cover them.
void add_case_inputs(std::vector<InputFile>& inputs, const CaseList& cases);

}  // namespace hexdyn
