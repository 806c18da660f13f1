#include "core/nearest_neighbour/FlannIndex.hpp"

#include <deque>

#include <flann/flann.hpp>

namespace uavslam {

using FlannTree = flann::Index<flann::L2_Simple<float>>;

// A map whose points all share one height (a planar scanner on a ground robot) is indexed in x-y
// only. FLANN's randomised trees split on a dimension drawn among those of the largest variance,
// and with three dimensions that includes a z of zero variance: such splits send every point to
// one side, the trees degenerate into chains, and a search walks them (while developing this, Intel
// took about twice as long in 3D). The first point of another height turns the index 3D.
struct FlannIndex::Impl {
  Impl(int trees, int checks) : trees(trees), search(checks) { search.cores = 1; }

  // FLANN keeps pointers into the added rows, so each batch lives in its own, never-moved block
  // of x y z rows; a planar index reads the first two columns of each row (a stride of 3).
  std::deque<std::vector<float>> blocks;
  int trees;
  std::unique_ptr<FlannTree> tree;
  flann::SearchParams search;
  std::size_t size = 0;
  std::size_t dimensions = 2;
  float height = 0.0f;  // of every point, while planar
  mutable std::vector<float> query_buffer;
  mutable std::vector<std::size_t> index_buffer;
  mutable std::vector<float> distance_buffer;

  flann::Matrix<float> rows_of(std::vector<float>& block) const {
    return {block.data(), block.size() / 3, dimensions, 3 * sizeof(float)};
  }
  bool all_at_height(const std::vector<float>& block) const {
    for (std::size_t i = 2; i < block.size(); i += 3) {
      if (block[i] != height) return false;
    }
    return true;
  }
  void insert(std::vector<float>& block) {
    if (!tree) {
      tree = std::make_unique<FlannTree>(rows_of(block), flann::KDTreeIndexParams(trees));
      tree->buildIndex();
    } else {
      // Extends the trees in place; rebuilds them only when the map has doubled since the last
      // build.
      tree->addPoints(rows_of(block), 2.0f);
    }
  }
  void rebuild_in_3d() {
    dimensions = 3;
    tree.reset();
    for (std::vector<float>& block : blocks) insert(block);
  }
};

FlannIndex::FlannIndex(int trees, int checks) : impl_(std::make_unique<Impl>(trees, checks)) {}
FlannIndex::~FlannIndex() = default;

void FlannIndex::add_points(const Points& points) {
  if (points.empty()) return;
  std::vector<float>& block = impl_->blocks.emplace_back();
  block.reserve(points.size() * 3);
  for (const Vec3& p : points)
    block.insert(block.end(), {float(p.x()), float(p.y()), float(p.z())});
  if (impl_->size == 0) impl_->height = block[2];
  impl_->size += points.size();
  if (impl_->dimensions == 2 && !impl_->all_at_height(block)) {
    impl_->rebuild_in_3d();
  } else {
    impl_->insert(block);
  }
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
  flann::Matrix<float> q(impl_->query_buffer.data(), n, impl_->dimensions, 3 * sizeof(float));
  flann::Matrix<std::size_t> indices(impl_->index_buffer.data(), n, 1);
  flann::Matrix<float> distances(impl_->distance_buffer.data(), n, 1);
  impl_->tree->knnSearch(q, indices, distances, 1, impl_->search);
  for (std::size_t i = 0; i < n; ++i) {
    // A planar index measures x-y only: the query's height difference completes the distance.
    const double dz = impl_->dimensions == 2 ? queries[i].z() - impl_->height : 0.0;
    nearest[i] = {impl_->index_buffer[i], double(impl_->distance_buffer[i]) + dz * dz};
  }
}

}  // namespace uavslam
