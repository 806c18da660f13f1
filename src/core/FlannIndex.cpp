#include "core/FlannIndex.hpp"

#include <deque>

#include <flann/flann.hpp>

namespace uavslam {

using FlannTree = flann::Index<flann::L2_Simple<float>>;

struct FlannIndex::Impl {
  Impl(int trees, int checks) : tree(flann::KDTreeIndexParams(trees)), search(checks) {
    search.cores = 1;
  }
  // FLANN keeps pointers into the added rows, so each batch lives in its own, never-moved block.
  std::deque<std::vector<float>> blocks;
  FlannTree tree;
  flann::SearchParams search;
  std::size_t size = 0;
  mutable std::vector<float> query_buffer;
  mutable std::vector<std::size_t> index_buffer;
  mutable std::vector<float> distance_buffer;
};

FlannIndex::FlannIndex(int trees, int checks) : impl_(std::make_unique<Impl>(trees, checks)) {}
FlannIndex::~FlannIndex() = default;

void FlannIndex::add_points(const Points& points) {
  if (points.empty()) return;
  std::vector<float>& block = impl_->blocks.emplace_back();
  block.reserve(points.size() * 3);
  for (const Vec3& p : points)
    block.insert(block.end(), {float(p.x()), float(p.y()), float(p.z())});
  flann::Matrix<float> rows(block.data(), points.size(), 3);
  if (impl_->size == 0) {
    impl_->tree.buildIndex(rows);
  } else {
    // Extends the trees in place; rebuilds them only when the map has doubled since the last build.
    impl_->tree.addPoints(rows, 2.0f);
  }
  impl_->size += points.size();
}

std::size_t FlannIndex::size() const {
  return impl_->size;
}

void FlannIndex::find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const {
  nearest.resize(queries.size());
  if (queries.empty() || impl_->size == 0) return;
  const std::size_t n = queries.size();
  impl_->query_buffer.resize(n * 3);
  impl_->index_buffer.resize(n);
  impl_->distance_buffer.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) impl_->query_buffer[3 * i + k] = float(queries[i][k]);
  }
  flann::Matrix<float> q(impl_->query_buffer.data(), n, 3);
  flann::Matrix<std::size_t> indices(impl_->index_buffer.data(), n, 1);
  flann::Matrix<float> distances(impl_->distance_buffer.data(), n, 1);
  impl_->tree.knnSearch(q, indices, distances, 1, impl_->search);
  for (std::size_t i = 0; i < n; ++i) {
    nearest[i] = {impl_->index_buffer[i], double(impl_->distance_buffer[i])};
  }
}

}  // namespace uavslam
