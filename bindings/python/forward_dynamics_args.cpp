#include "forward_dynamics_args.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace hexdyn_python {
namespace {

std::string number_text(double v, int digits = 6) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// "name[i, j, k]": the argument of `s` indexed as numpy indexes it, `inner` the index within
/// one sample (the sample's index i first when the argument holds T samples; "name" alone
/// for one sample and no inner index).
std::string index_text(const Samples& s, py::ssize_t i, const std::vector<py::ssize_t>& inner) {
  std::vector<py::ssize_t> index;
  if (s.batched) index.push_back(i);
  index.insert(index.end(), inner.begin(), inner.end());
  std::string out = s.name;
  for (std::size_t d = 0; d < index.size(); ++d)
    out += (d ? ", " : "[") + std::to_string(index[d]) + (d + 1 == index.size() ? "]" : "");
  return out;
}

/// The index within one sample of its flat component k.
std::vector<py::ssize_t> unflatten(const Samples& s, py::ssize_t k) {
  std::vector<py::ssize_t> inner(s.shape.size());
  for (std::size_t d = s.shape.size(); d-- > 0;) {
    inner[d] = k % s.shape[d];
    k /= s.shape[d];
  }
  return inner;
}

/// "(a, b, c)": the `n` values at `v`.
std::string tuple_text(const double* v, int n) {
  std::string out = "(";
  for (int k = 0; k < n; ++k) out += (k ? ", " : "") + number_text(v[k]);
  return out + ")";
}

}  // namespace

Samples samples_of(const DoubleArray& a, const std::vector<py::ssize_t>& shape, const char* name,
                   const char* function) {
  Samples s;
  s.function = function;
  s.data = a.data();
  s.shape = shape;
  s.name = name;
  s.width = 1;
  for (py::ssize_t n : shape) s.width *= n;
  const auto nd = static_cast<std::size_t>(a.ndim());
  s.batched = nd == shape.size() + 1;
  bool ok = nd == shape.size() || s.batched;
  for (std::size_t i = 0; ok && i < shape.size(); ++i)
    ok = a.shape(static_cast<py::ssize_t>(nd - shape.size() + i)) == shape[i];
  if (!ok) {
    std::string want;
    for (py::ssize_t n : shape) want += (want.empty() ? "" : ", ") + std::to_string(n);
    std::string got;
    for (std::size_t i = 0; i < nd; ++i)
      got += (i ? ", " : "") + std::to_string(a.shape(static_cast<py::ssize_t>(i)));
    throw py::value_error(std::string(function) + ": " + name + " has shape (" + got +
                          "), expected (" + want + ") or (T, " + want + ")");
  }
  if (s.batched) s.count = a.shape(0);
  return s;
}

void check_finite(const Samples& s) {
  if (s.data == nullptr) return;
  for (py::ssize_t i = 0; i < s.count; ++i)
    for (py::ssize_t k = 0; k < s.width; ++k)
      if (!std::isfinite(s.at(i)[k]))
        throw py::value_error(std::string(s.function) + ": " + index_text(s, i, unflatten(s, k)) +
                              " is " + number_text(s.at(i)[k]) + ", expected a finite number");
}

void check_unit_quaternions(const Samples& s) {
  for (py::ssize_t i = 0; i < s.count; ++i) {
    const double* q = s.at(i);
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(std::abs(norm - 1.0) <= kUnitQuaternionTolerance))
      throw py::value_error(std::string(s.function) + ": " + index_text(s, i, {}) + " = " +
                            tuple_text(q, 4) + " has norm " + number_text(norm, 9) +
                            ", expected a unit quaternion (w, x, y, z): a norm within " +
                            number_text(kUnitQuaternionTolerance) + " of 1");
  }
}

void check_sphere_foot_normals(const hexdyn::RobotModel& model, const Samples& s) {
  if (s.data == nullptr) return;
  for (py::ssize_t i = 0; i < s.count; ++i)
    for (int l = 0; l < model.legs(); ++l) {
      const double* n = s.at(i) + 3 * l;
      const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (model.foot_radius_m[static_cast<std::size_t>(l)] > 0.0 && !(norm >= kLeastNormalNorm))
        throw py::value_error(std::string(s.function) + ": " + index_text(s, i, {l}) + " = " +
                              tuple_text(n, 3) + ", the normal under leg L" +
                              std::to_string(l + 1) + "'s sphere foot, has norm " +
                              number_text(norm) + ", expected a direction: a norm of at least " +
                              number_text(kLeastNormalNorm) + " (it is normalised)");
    }
}

}  // namespace hexdyn_python
