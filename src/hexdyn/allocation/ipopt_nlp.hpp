#pragma once
/// \file ipopt_nlp.hpp
/// The allocation QP (allocation/qp.hpp) in Ipopt's TNLP form, strict or with penalised
/// slacks: the adapter behind the Ipopt back end (allocation/ipopt_backend.cpp explains the form
/// and the sign of the multipliers). Internal to the hexdyn_allocation_ipopt target.
#include <Eigen/Dense>
#include <IpTNLP.hpp>
#include <vector>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn::ipopt_nlp {

using Ipopt::Index;
using Ipopt::Number;

inline constexpr double kIpoptInf = 2e19;  // beyond Ipopt's nlp_{lower,upper}_bound_inf (±1e19)

/// kStrict: the problem as posed; kSlack: the penalised form with slack variables.
enum class Mode { kStrict, kSlack };

/// An inequality row with its slacks (slack mode): lower ≤ C x + s⁺ − s⁻ ≤ upper.
struct RelaxedRow {
  int row = 0;
  int plus = -1;   ///< index of s⁺ among the slack variables, −1 without a lower bound
  int minus = -1;  ///< index of s⁻, −1 without an upper bound
  int slacks() const { return (plus >= 0) + (minus >= 0); }
};

/// The QP (strict or with slacks) in Ipopt's TNLP form. Reconfigured by `setup` before
/// every solve; the object itself lives as long as the backend.
class QpTnlp : public Ipopt::TNLP {
 public:
  // --- input, set by the backend before OptimizeTNLP ---
  const QpProblem* p = nullptr;
  Eigen::MatrixXd H;  ///< full symmetric H
  Mode mode = Mode::kStrict;
  std::vector<RelaxedRow> relaxed;   ///< slack mode: the rows with a finite bound
  int relaxed_slacks = 0;            ///< Σ slacks() over `relaxed`
  std::vector<double> slack_weight;  ///< ρ per slack variable
  int n = 0, n_slack = 0, m_eq = 0, m_in = 0, n_cones = 0;
  double eps = 1e-9;        ///< cone smoothing [N]
  Eigen::VectorXd start_x;  ///< n + n_slack
  bool start_multipliers = false;
  Eigen::VectorXd start_lambda;   ///< Ipopt multipliers of all constraints
  Eigen::VectorXd start_z_lower;  ///< n + n_slack

  // --- output, written by finalize_solution ---
  bool finalized = false;
  Eigen::VectorXd x_out;       ///< n + n_slack
  Eigen::VectorXd lambda_out;  ///< Ipopt sign
  Eigen::VectorXd z_lower_out;
  int iterations_out = 0;
  double nlp_error_out = 0.0;  ///< Ipopt's scaled optimality error at the returned point

  void setup(const QpProblem& problem, Mode m, double rho, double cone_eps);

  int cone_slack(int k) const { return n_slack - n_cones + k; }  // slack mode only
  int first_cone_row() const {
    return m_eq + (mode == Mode::kStrict ? m_in : static_cast<int>(relaxed.size()));
  }
  int constraints() const { return first_cone_row() + n_cones; }
  int nv() const { return n + n_slack; }
  int hess_x_entries() const { return n * (n + 1) / 2; }
  static int tri(int i, int j) { return i * (i + 1) / 2 + j; }  // i ≥ j

  // --- Ipopt::TNLP ---
  bool get_nlp_info(Index& nv_out, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override;
  bool get_bounds_info(Index nv_in, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override;
  bool get_starting_point(Index nv_in, bool init_x, Number* x, bool init_z, Number* z_L,
                          Number* z_U, Index m, bool init_lambda, Number* lambda) override;

  /// √(t1² + t2² + ε²) of cone k.
  double smooth_norm(const Number* x, int k) const;
  /// μ n of cone k, plus its slack in slack mode.
  double mu_n_plus_slack(const Number* x, int k) const;

  bool eval_f(Index, const Number* x, bool, Number& obj) override;
  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override;
  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override;
  bool eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* iRow, Index* jCol,
                  Number* values) override;
  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index, const Number* lambda, bool,
              Index nele, Index* iRow, Index* jCol, Number* values) override;

  void finalize_solution(Ipopt::SolverReturn, Index nv_in, const Number* x, const Number* z_L,
                         const Number*, Index m, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities* ip_cq) override;
};

}  // namespace hexdyn::ipopt_nlp
