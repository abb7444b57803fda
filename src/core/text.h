// Lists in messages and reports: "a, b, c".
#pragma once

#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace mirage {

// The items in order, separated by `separator` ("" for an empty list).
std::string joinList(const std::vector<std::string>& items, const std::string& separator = ", ");

// The same over any range, each element turned into text by `text(element)`.
template <class Range, class ToText,
          class = decltype(std::declval<ToText&>()(*std::begin(std::declval<const Range&>())))>
std::string joinList(const Range& items, ToText text, const std::string& separator = ", ") {
    std::string out;
    bool first = true;
    for (const auto& item : items) {
        if (!first) out += separator;
        out += text(item);
        first = false;
    }
    return out;
}

}  // namespace mirage
