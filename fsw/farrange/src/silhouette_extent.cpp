#include "visnav/farrange/silhouette_extent.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace visnav::far {

namespace {

constexpr int kMinSide = 8;  ///< fewer blocks a side leave too small a ring to fit the background on

/// Sum of a block's pixels on a [0, 1] scale; the caller keeps it inside the image.
double blockSum(const MonoImage& image, int x0, int y0, int side) {
  double sum = 0.0;
  if (image.depth == MonoImage::Depth::kU8) {
    for (int y = y0; y < y0 + side; ++y) {
      const std::uint8_t* row = image.u8.row(y);
      int s = 0;
      for (int x = x0; x < x0 + side; ++x) s += row[x];
      sum += s;
    }
    return sum / 255.0;
  }
  for (int y = y0; y < y0 + side; ++y) {
    const std::uint16_t* row = image.u16.row(y);
    for (int x = x0; x < x0 + side; ++x) sum += row[x];
  }
  return sum / static_cast<double>(image.max_code);
}

}  // namespace

void SilhouetteExtent::init() {
  constexpr std::size_t cells = static_cast<std::size_t>(kMaxSide) * kMaxSide;
  m_means.reserve(cells);
  m_work.reserve(cells);
  m_mask.reserve(cells);
  m_stack.reserve(cells);
}

SilhouetteMeasure SilhouetteExtent::measure(const MonoImage& image, const Vec2& centre_px, double half_px,
                                            double seed_radius_px, int min_block_px, double k_sigma,
                                            double level_ratio) {
  SilhouetteMeasure out;
  if (image.empty() || m_means.capacity() == 0 || !centre_px.allFinite() || !(half_px > 0.0) ||
      !(k_sigma > 0.0) || min_block_px < 1)
    return out;
  // Bounded before the int casts: the window never needs more than the image.
  const double image_side = static_cast<double>(std::max(image.width(), image.height()));
  const double half = std::min(half_px, image_side);
  // A centre this far off the image has no window on it (and would overflow the int casts below).
  if (std::abs(centre_px.x()) > 4.0 * image_side || std::abs(centre_px.y()) > 4.0 * image_side) return out;
  const int block = std::max(min_block_px, static_cast<int>(std::ceil(2.0 * half / kMaxSide)));
  const int side = std::min(kMaxSide, static_cast<int>(2.0 * half) / block);
  if (side < kMinSide) return out;
  // The window's top-left corner, then clipped to the image in whole blocks.
  const int wx = static_cast<int>(std::lround(centre_px.x() - 0.5 * side * block));
  const int wy = static_cast<int>(std::lround(centre_px.y() - 0.5 * side * block));
  const int i0 = wx < 0 ? (-wx + block - 1) / block : 0;
  const int j0 = wy < 0 ? (-wy + block - 1) / block : 0;
  const int i1 = std::min(side, (image.width() - wx) / block);
  const int j1 = std::min(side, (image.height() - wy) / block);
  const int nx = i1 - i0;
  const int ny = j1 - j0;
  if (nx < kMinSide || ny < kMinSide) return out;
  const int x0 = wx + i0 * block;
  const int y0 = wy + j0 * block;
  const bool clipped_left = i0 > 0;
  const bool clipped_top = j0 > 0;
  const bool clipped_right = i1 < side;
  const bool clipped_bottom = j1 < side;
  const double area = static_cast<double>(block) * block;
  const auto count = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  m_means.clear();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      m_means.push(static_cast<float>(blockSum(image, x0 + i * block, y0 + j * block, block) / area));

  // The background: a plane a + b i + c j fitted to the border ring's means, which a gradient across the
  // window leaves flat; its spread is the ring's median absolute residual. A target reaching into the ring
  // would pull a least-squares plane towards it, so the fit starts from the ring's median level and each
  // least-squares pass leaves out the ring's blocks that departed from the pass before.
  const auto onRing = [&](int i, int j) { return i == 0 || j == 0 || i == nx - 1 || j == ny - 1; };
  const auto mean = [&](int i, int j) {
    return static_cast<double>(
        m_means[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)]);
  };
  Vec3 plane = Vec3::Zero();
  const auto residual = [&](int i, int j) {
    return mean(i, j) - (plane.x() + plane.y() * i + plane.z() * j);
  };
  const auto ringSpread = [&]() {
    m_work.clear();
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (onRing(i, j)) m_work.push(static_cast<float>(residual(i, j)));
    return m_work.begin() + m_work.size() / 2;
  };
  float* middle = ringSpread();
  std::nth_element(m_work.begin(), middle, m_work.end());
  plane.x() = static_cast<double>(*middle);
  double threshold = 0.0;
  for (int pass = 0; pass < 3; ++pass) {
    middle = ringSpread();
    for (float& r : m_work) r = std::fabs(r);
    std::nth_element(m_work.begin(), middle, m_work.end());
    // A floor for a noiseless ring (synthetic flat backgrounds): a quarter grey level of 8 bits.
    out.noise = std::max(1.4826 * static_cast<double>(*middle), 0.25 / 255.0);
    threshold = k_sigma * out.noise;
    if (pass == 2) break;
    Mat3 normal = Mat3::Zero();
    Vec3 rhs = Vec3::Zero();
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!onRing(i, j) || std::fabs(residual(i, j)) > threshold) continue;
        const Vec3 a(1.0, i, j);
        normal += a * a.transpose();
        rhs += a * mean(i, j);
      }
    const Vec3 fitted = normal.ldlt().solve(rhs);
    if (!fitted.allFinite()) return out;
    plane = fitted;
  }
  out.block_px = block;

  // The departing block nearest the fix seeds the region. The region grows only over blocks departing by
  // `level_ratio` of the strongest departure about the fix as well: a faint glow beside a bright target
  // departs from the ring's plane too, and joined to the target it read a satellite at 181 m as 48 m
  // (campaign smallsat/5015).
  m_mask.clear();
  int seed = -1;
  double seed_d2 = seed_radius_px * seed_radius_px;
  double level = 0.0;
  const auto cellCentre = [&](int i, int j) { return Vec2(x0 + (i + 0.5) * block, y0 + (j + 0.5) * block); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double departure = std::fabs(residual(i, j));
      const bool departs = departure > threshold;
      m_mask.push(departs ? 1U : 0U);
      if (!departs) continue;
      const double d2 = (cellCentre(i, j) - centre_px).squaredNorm();
      if (d2 <= seed_radius_px * seed_radius_px) level = std::max(level, departure);
      if (d2 <= seed_d2) {
        seed_d2 = d2;
        seed = j * nx + i;
      }
    }
  if (seed < 0) return out;
  const double grow_threshold = std::max(threshold, level_ratio * level);
  for (std::size_t k = 0; k < count; ++k)
    if (m_mask[k] == 1U &&
        !(std::fabs(residual(static_cast<int>(k) % nx, static_cast<int>(k) / nx)) > grow_threshold))
      m_mask[k] = 0U;
  m_mask[static_cast<std::size_t>(seed)] = 1U;

  // 8-connected growth; every block enters the stack once (marked on push), so count bounds it.
  m_stack.clear();
  m_stack.push(seed);
  m_mask[static_cast<std::size_t>(seed)] = 2U;
  Vec2 sum = Vec2::Zero();
  std::size_t top = 0;
  while (top < m_stack.size() && top < count) {
    const int index = m_stack[top++];
    const int i = index % nx;
    const int j = index / nx;
    sum += cellCentre(i, j);
    ++out.blocks;
    if (onRing(i, j)) {
      out.touches_window = true;
      out.cut_by_image = out.cut_by_image || (i == 0 && clipped_left) || (j == 0 && clipped_top) ||
                         (i == nx - 1 && clipped_right) || (j == ny - 1 && clipped_bottom);
    }
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di;
        const int b = j + dj;
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        const std::size_t k =
            static_cast<std::size_t>(b) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(a);
        if (m_mask[k] != 1U) continue;
        m_mask[k] = 2U;
        m_stack.push(static_cast<std::int32_t>(k));
      }
  }
  out.centroid_px = sum / static_cast<double>(out.blocks);
  m_work.clear();
  for (std::size_t s = 0; s < m_stack.size(); ++s) {
    const int index = m_stack[s];
    const double r = (cellCentre(index % nx, index / nx) - out.centroid_px).norm();
    out.extent_px = std::max(out.extent_px, r);
    m_work.push(static_cast<float>(std::fabs(residual(index % nx, index / nx))));
  }
  // A body's blocks depart about as much as its core does; a glow joined to a small bright target is most
  // of the region and departs far less (smallsat/5015 at 622 m read 58 m with the growth rule alone).
  float* middle_block = m_work.begin() + m_work.size() / 2;
  std::nth_element(m_work.begin(), middle_block, m_work.end());
  out.median_level_ratio = level > 0.0 ? static_cast<double>(*middle_block) / level : 0.0;
  out.found = !out.touches_window && !(out.median_level_ratio < 2.0 * level_ratio);
  return out;
}

}  // namespace visnav::far
