#include "tools/pareto.h"

#include <algorithm>
#include <cmath>

namespace haif {

std::vector<size_t> paretoFront(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = std::min(x.size(), y.size());
  std::vector<size_t> order;
  for (size_t i = 0; i < n; ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) order.push_back(i);
  // Cheapest first (ties: smaller error, then input order); a point is on the front when its
  // error is below every cheaper point's.
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return x[a] < x[b] || (x[a] == x[b] && y[a] < y[b]); });
  std::vector<size_t> front;
  double best = INFINITY;
  for (size_t i : order)
    if (y[i] < best) {
      front.push_back(i);
      best = y[i];
    }
  return front;
}

}  // namespace haif
