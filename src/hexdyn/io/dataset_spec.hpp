#pragma once
/// \file dataset_spec.hpp
/// The vocabulary of hexdyn's HDF5 contracts (io/schema.hpp and the schema headers it
/// includes): the shape of a dataset in terms of a file's sizes and the netCDF dimensions of
/// its axes, the element types, and the structs that declare a dataset, an attribute and the
/// CF flags of a dataset of codes, with the path templates' substitution. The sizes the shapes
/// name (T, L, J, n, N, ...) are described in schema.hpp.
#include <string>

namespace hexdyn::schema {

/// Shape of a dataset in terms of the run's sizes.
enum class Shape {
  kScalar,               ///< ()
  kText,                 ///< () variable-length UTF-8 string
  kTextList,             ///< (m) variable-length UTF-8 strings, m may be 0
  kJointNames,           ///< (J) strings, one per joint of the robot
  kLegNames,             ///< (L) strings, one per leg of the robot
  kJ,                    ///< (J), one number per joint
  kT,                    ///< (T)
  kT3,                   ///< (T,3)
  kT4,                   ///< (T,4)
  kTLeg,                 ///< (T,L), one number per sample and leg
  kTJoint,               ///< (T,J), one number per sample and joint
  kTLegXyz,              ///< (T,L,3), one vector per sample and leg
  kN,                    ///< (n), one entry per touchdown, n may be 0
  kScenarios,            ///< (N), one entry per scenario, index order
  kScenarioAxes,         ///< (N,A), one row per scenario, one column per axis
  kScenarioJoints,       ///< (N,J), one row per scenario, one column per joint
  kAxisValues,           ///< (V), one entry per value of an axis
  kCaseKeys,             ///< (K), the keys a cases axis sets
  kCaseValues,           ///< (V,K), one row per case, one column per key it sets
  kEnvelopeTreads,       ///< (W), tread depths of an envelope
  kEnvelopeDuties,       ///< (B), duty factors of an envelope
  kEnvelopeSpeeds,       ///< (S), peak speeds of an envelope
  kEnvelopeCriteria,     ///< (C), criteria of an envelope
  kEnvelopeCells,        ///< (W,B,S), one entry per tread, duty factor and speed
  kEnvelopeGrid,         ///< (W,B,S,C), one entry per cell and criterion
  kEnvelopeProbes,       ///< (P), one entry per probe (a criterion evaluated at one riser)
  kEnvelopeCases,        ///< (D), cases of an envelope with `cases:`
  kEnvelopeCaseKeys,     ///< (K), keys its cases set
  kEnvelopeCaseValues,   ///< (D,K), one row per case, one column per key
  kEnvelopeCaseCells,    ///< (D,W,B,S), one entry per case, tread depth, duty factor and speed
  kEnvelopeCaseGrid,     ///< (D,W,B,S,C), one entry per case, cell and criterion
  kEnvelopeRisers,       ///< (R), risers of a friction search (`search: friction`)
  kEnvelopeMuGrid,       ///< (W,B,S,R), one entry per cell and riser of a friction search
  kEnvelopeCaseMuGrid,   ///< (D,W,B,S,R), one entry per case, cell and riser
  kCycles,               ///< (Y), one entry per gait cycle
  kCycles3,              ///< (Y,3), one vector per gait cycle (a replay's drift)
  kLegValues,            ///< (L), one number per leg
  kVector3,              ///< (3), one vector
  kTerrainPoints,        ///< (K), one entry per vertex of the terrain's height profile
  kMapColumns,           ///< (MX), one entry per column (x) of a height map
  kMapRows,              ///< (MY), one entry per row (y) of a height map
  kMapGrid,              ///< (MY,MX), one entry per node of a height map
  kXyz,                  ///< (3) strings "x", "y", "z"
  kWxyz,                 ///< (4) strings "w", "x", "y", "z"
  kAxes,                 ///< (A), one entry per sweep axis
  kRobustReplays,        ///< (RP), one entry per replay of a robustness study
  kRobustReplaySteps,    ///< (RP,ST), one entry per replay and stair step
  kRobustReplayLinks,    ///< (RP,LK), one entry per replay and leg link
  kRobustReplayJoints,   ///< (RP,J), one entry per replay and joint
  kRobustReplayXyz,      ///< (RP,3), one vector per replay
  kRobustSteps,          ///< (ST), stair steps of a robustness study
  kRobustLinks,          ///< (LK), leg links of the robot (the body each joint moves)
  kRobustClasses,        ///< (6), failure classes
  kRobustPerturbations,  ///< (PT), the perturbations of a tolerance search
};

/// The netCDF dimensions of a shape's axes, space-separated, outermost first ("" for a
/// scalar); "{key}" is the dimension of a sweep axis, named by its key (a cases axis: by its
/// name, and "{key}_key" the keys its cases set, e.g. "case_key"). A dimension D of
/// a file (or of a kept run's group) has its coordinate variable at "/D" of that root
/// (io/labels.hpp): the names, component labels or values along D, or the index 0..n−1;
/// each group whose datasets use D holds a copy (the group coordinates below).
// clang-format off
constexpr const char* dimension_names(Shape shape) {
  switch (shape) {
    case Shape::kScalar: return "";
    case Shape::kText: return "";
    case Shape::kTextList: return "message";
    case Shape::kJointNames: return "joint";
    case Shape::kLegNames: return "leg";
    case Shape::kJ: return "joint";
    case Shape::kT: return "time";
    case Shape::kT3: return "time xyz";
    case Shape::kT4: return "time wxyz";
    case Shape::kTLeg: return "time leg";
    case Shape::kTJoint: return "time joint";
    case Shape::kTLegXyz: return "time leg xyz";
    case Shape::kN: return "impact";
    case Shape::kScenarios: return "scenario";
    case Shape::kScenarioAxes: return "scenario axis";
    case Shape::kScenarioJoints: return "scenario joint";
    case Shape::kAxisValues: return "{key}";
    case Shape::kCaseKeys: return "{key}_key";
    case Shape::kCaseValues: return "{key} {key}_key";
    case Shape::kEnvelopeTreads: return "tread_depth";
    case Shape::kEnvelopeDuties: return "duty_factor";
    case Shape::kEnvelopeSpeeds: return "peak_speed";
    case Shape::kEnvelopeCriteria: return "criterion";
    case Shape::kEnvelopeCells: return "tread_depth duty_factor peak_speed";
    case Shape::kEnvelopeGrid: return "tread_depth duty_factor peak_speed criterion";
    case Shape::kEnvelopeProbes: return "probe";
    case Shape::kEnvelopeCases: return "case";
    case Shape::kEnvelopeCaseKeys: return "case_key";
    case Shape::kEnvelopeCaseValues: return "case case_key";
    case Shape::kEnvelopeCaseCells: return "case tread_depth duty_factor peak_speed";
    case Shape::kEnvelopeCaseGrid: return "case tread_depth duty_factor peak_speed criterion";
    case Shape::kEnvelopeRisers: return "riser";
    case Shape::kEnvelopeMuGrid: return "tread_depth duty_factor peak_speed riser";
    case Shape::kEnvelopeCaseMuGrid: return "case tread_depth duty_factor peak_speed riser";
    case Shape::kCycles: return "gait_cycle";
    case Shape::kCycles3: return "gait_cycle xyz";
    case Shape::kLegValues: return "leg";
    case Shape::kVector3: return "xyz";
    case Shape::kTerrainPoints: return "terrain_point";
    case Shape::kMapColumns: return "map_x";
    case Shape::kMapRows: return "map_y";
    case Shape::kMapGrid: return "map_y map_x";
    case Shape::kXyz: return "xyz";
    case Shape::kWxyz: return "wxyz";
    case Shape::kAxes: return "axis";
    case Shape::kRobustReplays: return "replay";
    case Shape::kRobustReplaySteps: return "replay step";
    case Shape::kRobustReplayLinks: return "replay link";
    case Shape::kRobustReplayJoints: return "replay joint";
    case Shape::kRobustReplayXyz: return "replay xyz";
    case Shape::kRobustSteps: return "step";
    case Shape::kRobustLinks: return "link";
    case Shape::kRobustClasses: return "failure_class";
    case Shape::kRobustPerturbations: return "perturbation";
  }
  return "";
}
// clang-format on

/// Element type stored in the file.
enum class Element { kFloat64, kInt8, kInt32, kInt64, kString };

/// One dataset of the contract.
struct DatasetSpec {
  const char* path;   ///< absolute HDF5 path
  const char* units;  ///< value of the mandatory `units` attribute
  Shape shape = Shape::kScalar;
  Element element = Element::kFloat64;
  const char* long_name = "";  ///< CF `long_name`: what the values are, in words
};

/// One attribute of the contract: on the object `object`, named `name`.
struct AttributeSpec {
  const char* object;  ///< absolute HDF5 path of the group or dataset (may be a template)
  const char* name;
  Element element = Element::kString;  ///< stored as a scalar of this type
};

/// CF flags of a dataset of codes 0, 1, 2, ...: `flag_values` (the codes, in the
/// dataset's element type) and `flag_meanings` (one word per code, space-separated).
struct FlagSpec {
  const char* path;      ///< absolute HDF5 path of the dataset (below a kept run's group too)
  const char* meanings;  ///< CF `flag_meanings`, the word of code 0 first
};

/// `path` with its placeholder "{i}", "{id}" or "{key}" replaced by `value` ("/axes/{i}/key", "2"
/// → "/axes/2/key"); `path` unchanged when it has none.
inline std::string at(const char* path, const std::string& value) {
  std::string s(path);
  for (const char* placeholder : {"{i}", "{id}", "{key}"}) {
    const auto p = s.find(placeholder);
    if (p != std::string::npos)
      return s.replace(p, std::char_traits<char>::length(placeholder), value);
  }
  return s;
}

}  // namespace hexdyn::schema
