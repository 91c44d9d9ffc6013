// The Pareto front of points that cost x and err y: those no other point beats on both.
#pragma once

#include <cstddef>
#include <vector>

namespace haif {

/// Indices of the points for which no other point has x <= and y <= with one of them strictly
/// smaller (both minimised), ordered by increasing x. Points with a non-finite coordinate are left out;
/// of identical points only the first is kept.
std::vector<size_t> paretoFront(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace haif
