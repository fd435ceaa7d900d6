// Meshes keep only the nodes their elements use: shared by the composed hull's mirror and the
// B-rep mesher's output.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace fairlines::detail {

/// Renumbers the node indices of `elements` to the nodes they use, in order of first use
/// (a negative index, a quad's unused fourth corner, stays), and returns those nodes' positions
/// as the rows of an (n_used, 3) matrix.
template <std::size_t K>
Eigen::MatrixXd keep_used_nodes(std::vector<std::array<int, K>>& elements, const std::vector<Eigen::Vector3d>& nodes) {
  std::vector<int> used(nodes.size(), -1);
  int n = 0;
  for (auto& e : elements)
    for (int& v : e)
      if (v >= 0) {
        if (used[v] < 0) used[v] = n++;
        v = used[v];
      }
  Eigen::MatrixXd positions(n, 3);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (used[i] >= 0) positions.row(used[i]) = nodes[i].transpose();
  return positions;
}

/// The elements as the rows of an integer matrix, one column per corner.
template <std::size_t K>
Eigen::MatrixXi element_rows(const std::vector<std::array<int, K>>& elements) {
  Eigen::MatrixXi rows(static_cast<Eigen::Index>(elements.size()), static_cast<Eigen::Index>(K));
  for (std::size_t f = 0; f < elements.size(); ++f)
    for (std::size_t k = 0; k < K; ++k)
      rows(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(k)) = elements[f][k];
  return rows;
}

}  // namespace fairlines::detail
