// Avenues — where an offset into a text falls: its line and column, for readers' messages
// ("house.xml:12:5: ..."), found by a binary search of the line starts rather than by
// counting from the start at every message. Part of core/, below every other module.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string_view>
#include <utility>
#include <vector>

namespace avenues {

/// Byte offset → 1-based line and column.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text) {
    starts_.push_back(0);
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') starts_.push_back(i + 1);
  }
  /// {0, 0} for a negative offset (pugixml's "none").
  std::pair<int, int> at(ptrdiff_t offset) const {
    if (offset < 0) return {0, 0};
    const auto it = std::upper_bound(starts_.begin(), starts_.end(), size_t(offset));
    const size_t line = size_t(it - starts_.begin());
    return {int(line), int(size_t(offset) - starts_[line - 1] + 1)};
  }
  /// The line alone.
  size_t line(ptrdiff_t offset) const { return size_t(at(offset).first); }

 private:
  std::vector<size_t> starts_;
};

}  // namespace avenues
