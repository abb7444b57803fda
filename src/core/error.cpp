#include "core/error.h"

namespace mirage {

std::string FileLoc::str() const {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) {
        s += ":" + std::to_string(line);
        if (column > 0) s += ":" + std::to_string(column);
    }
    return s;
}

std::string boundedMessage(const std::string& msg, size_t maxChars) {
    std::string out;
    out.reserve(std::min(msg.size(), maxChars) + 16);
    for (size_t i = 0; i < msg.size() && out.size() < maxChars; ++i) {
        unsigned char c = static_cast<unsigned char>(msg[i]);
        out += (c >= 32 && c < 127) || c == '\n' ? char(c) : '?';
    }
    if (msg.size() > maxChars) out += "… (" + std::to_string(msg.size()) + " bytes)";
    return out;
}

void checkFailed(const char* expr, const char* file, int line) {
    std::fprintf(stderr, "mirage: internal check failed: %s (%s:%d)\n", expr, file, line);
    std::abort();
}

}  // namespace mirage
