// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A few analyses kept for reuse, the most recently used first (the sparse solvers' analyses
// of the fits: a scan's sections mostly share their matrix patterns).
#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace section::detail {

/// The entry of `recent` for which `same(entry)` holds, else a new one made by
/// `make(entry)` in place of the least recently used when `kept` are there; moved to the
/// front. A throw from `make` leaves `recent` as it was.
template <class T, class Same, class Make>
T& recently_used(std::vector<std::unique_ptr<T>>& recent, std::size_t kept, Same&& same, Make&& make) {
  auto found =
      std::find_if(recent.begin(), recent.end(), [&](const std::unique_ptr<T>& e) { return same(*e); });
  if (found == recent.end()) {
    auto fresh = std::make_unique<T>();
    make(*fresh);
    if (recent.size() < kept) recent.emplace_back();
    found = recent.end() - 1;
    *found = std::move(fresh);
  }
  std::rotate(recent.begin(), found, found + 1);
  return *recent.front();
}

}  // namespace section::detail
