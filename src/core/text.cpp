#include "core/text.h"

namespace mirage {

std::string joinList(const std::vector<std::string>& items, const std::string& separator) {
    return joinList(items, [](const std::string& s) -> const std::string& { return s; }, separator);
}

}  // namespace mirage
