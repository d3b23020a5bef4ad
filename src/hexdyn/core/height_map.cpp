#include "hexdyn/core/height_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hexdyn {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The cell containing coordinate `u` along an axis of n nodes from u0 spaced r: its lower
/// node index in [0, n − 2] and the fraction in [0, 1] (clamped: the border continues).
void locate(double u, double u0, double r, int n, int& k, double& w) {
  const double s = std::clamp((u - u0) / r, 0.0, static_cast<double>(n - 1));
  k = std::min(static_cast<int>(std::floor(s)), n - 2);
  w = s - k;
}

/// One-dimensional squared-distance transform of f (n entries, spacing 1) into d
/// (Felzenszwalb and Huttenlocher 2012, "Distance transforms of sampled functions").
void transform_1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                  std::vector<double>& z, std::vector<int>& arg) {
  const int n = static_cast<int>(f.size());
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    double s = -kInf;
    while (k >= 0) {
      const double a = q, b = v[k];
      s = ((f[q] + a * a) - (f[v[k]] + b * b)) / (2.0 * a - 2.0 * b);
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : s;
    z[k + 1] = kInf;
  }
  for (int q = 0, j = 0; q < n; ++q) {
    if (k < 0) {
      d[q] = kInf;
      arg[q] = -1;
      continue;
    }
    while (z[j + 1] < q) ++j;
    d[q] = (q - v[j]) * static_cast<double>(q - v[j]) + f[v[j]];
    arg[q] = v[j];  // the sample whose parabola is lowest at q
  }
}

}  // namespace

double HeightMap::height(double x, double y) const {
  int i = 0, j = 0;
  double u = 0.0, w = 0.0;
  locate(x, x0_m, resolution_m, nx, j, u);
  locate(y, y0_m, resolution_m, ny, i, w);
  const double lo = at(i, j) + u * (at(i, j + 1) - at(i, j));
  const double hi = at(i + 1, j) + u * (at(i + 1, j + 1) - at(i + 1, j));
  return lo + w * (hi - lo);
}

Eigen::Vector2d HeightMap::gradient(double x, double y) const {
  int i = 0, j = 0;
  double u = 0.0, w = 0.0;
  locate(x, x0_m, resolution_m, nx, j, u);
  locate(y, y0_m, resolution_m, ny, i, w);
  const bool in_x = x > x0_m && x < x0_m + (nx - 1) * resolution_m;
  const bool in_y = y > y0_m && y < y0_m + (ny - 1) * resolution_m;
  const double dzdu = (1.0 - w) * (at(i, j + 1) - at(i, j)) + w * (at(i + 1, j + 1) - at(i + 1, j));
  const double dzdw = (1.0 - u) * (at(i + 1, j) - at(i, j)) + u * (at(i + 1, j + 1) - at(i, j + 1));
  return {in_x ? dzdu / resolution_m : 0.0, in_y ? dzdw / resolution_m : 0.0};
}

Vec3 HeightMap::normal(double x, double y) const {
  const Eigen::Vector2d g = gradient(x, y);
  return Vec3(-g.x(), -g.y(), 1.0).normalized();
}

double HeightMap::max_height_along(double ax, double ay, double bx, double by,
                                   double radius) const {
  const double r = radius + resolution_m;
  const auto col = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - x0_m) / resolution_m)), 0, nx - 1);
  };
  const auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - y0_m) / resolution_m)), 0, ny - 1);
  };
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  double best = -kInf;
  for (int i = row(std::min(ay, by) - r); i <= std::min(ny - 1, row(std::max(ay, by) + r) + 1); ++i)
    for (int j = col(std::min(ax, bx) - r); j <= std::min(nx - 1, col(std::max(ax, bx) + r) + 1);
         ++j) {
      // Distance of node (i, j) to the segment.
      const double px = x(j) - ax, py = y(i) - ay;
      const double t = len2 > 0.0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
      if (std::hypot(px - t * dx, py - t * dy) <= r) best = std::max(best, at(i, j));
    }
  return best == -kInf ? height(ax, ay) : best;
}

double HeightMap::node_clearance(int i, int j) const {
  const int k = nearest_bad[static_cast<std::size_t>(i) * nx + j];
  return k < 0 ? kInf : std::hypot(x(k % nx) - x(j), y(k / nx) - y(i));
}

double HeightMap::clearance(double x, double y) const {
  int i = 0, j = 0;
  double u = 0.0, w = 0.0;
  locate(x, x0_m, resolution_m, nx, j, u);
  locate(y, y0_m, resolution_m, ny, i, w);
  double best = kInf;
  for (int a = i; a <= i + 1; ++a)
    for (int b = j; b <= j + 1; ++b) {
      const int k = nearest_bad[static_cast<std::size_t>(a) * nx + b];
      if (k >= 0) best = std::min(best, std::hypot(this->x(k % nx) - x, this->y(k / nx) - y));
    }
  return best;
}

void prepare_height_map(HeightMap& m, double edge_height_m, double max_slope_rad) {
  const int nx = m.nx, ny = m.ny;
  const double tan_max = std::tan(max_slope_rad), r = m.resolution_m;
  std::vector<double> f(static_cast<std::size_t>(nx) * ny, kInf);
  for (int i = 0; i < ny; ++i)
    for (int j = 0; j < nx; ++j) {
      const double z = m.at(i, j);
      bool bad = false;
      for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int a = i + di, b = j + dj;
        if (a >= 0 && a < ny && b >= 0 && b < nx && std::abs(m.at(a, b) - z) > edge_height_m)
          bad = true;
      }
      const int jl = std::max(j - 1, 0), jr = std::min(j + 1, nx - 1);
      const int il = std::max(i - 1, 0), ir = std::min(i + 1, ny - 1);
      const double gx = (m.at(i, jr) - m.at(i, jl)) / ((jr - jl) * r);
      const double gy = (m.at(ir, j) - m.at(il, j)) / ((ir - il) * r);
      if (std::hypot(gx, gy) > tan_max) bad = true;
      if (bad) f[static_cast<std::size_t>(i) * nx + j] = 0.0;
    }
  // Squared distances in node units, columns then rows, with the nearest node kept: after the
  // columns, row_of[i, j] is the row of the nearest no-foothold node in column j.
  const int n = std::max(nx, ny);
  std::vector<double> line(n), out(n), z(n + 1);
  std::vector<int> v(n), arg(n), row_of(f.size(), -1);
  for (int j = 0; j < nx; ++j) {
    line.resize(ny);
    out.resize(ny);
    arg.resize(ny);
    for (int i = 0; i < ny; ++i) line[i] = f[static_cast<std::size_t>(i) * nx + j];
    transform_1d(line, out, v, z, arg);
    for (int i = 0; i < ny; ++i) {
      f[static_cast<std::size_t>(i) * nx + j] = out[i];
      row_of[static_cast<std::size_t>(i) * nx + j] = arg[i];
    }
  }
  m.nearest_bad.assign(f.size(), -1);
  for (int i = 0; i < ny; ++i) {
    line.assign(f.begin() + static_cast<std::ptrdiff_t>(i) * nx,
                f.begin() + static_cast<std::ptrdiff_t>(i + 1) * nx);
    out.resize(nx);
    arg.resize(nx);
    transform_1d(line, out, v, z, arg);
    for (int j = 0; j < nx; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * nx + j;
      if (arg[j] >= 0)  // column arg[j], the row its column pass found
        m.nearest_bad[k] = row_of[static_cast<std::size_t>(i) * nx + arg[j]] * nx + arg[j];
    }
  }
}

}  // namespace hexdyn
