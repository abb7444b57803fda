// Frame numbers: $F / #### patterns in paths, and the frame ranges of a sequence.
#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/text.h"
#include "scene/scene.h"

namespace mirage {

// A frame number pads to at most this many digits. An int frame has at most 10; a wider pad
// is a typo (`$F888888888` would ask for a gigabyte of zeros), refused with a clear message.
constexpr size_t kMaxFramePad = 32;

std::string expandFramePattern(const std::string& pattern, int frame) {
    auto tooWide = [&]() {
        return MirageError("frame pattern in '" + boundedMessage(pattern, 120) +
                           "' pads to more than " + std::to_string(kMaxFramePad) +
                           " digits (expected $F, $F4 or #### for a 4-digit frame)");
    };
    std::string out;
    for (size_t i = 0; i < pattern.size();) {
        if (pattern[i] == '$' && i + 1 < pattern.size() && pattern[i + 1] == 'F') {
            size_t j = i + 2;
            size_t width = 0;
            while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) {
                width = width * 10 + size_t(pattern[j++] - '0');
                if (width > kMaxFramePad) throw tooWide();
            }
            std::string num = std::to_string(std::abs(frame));
            if (num.size() < width) num.insert(0, width - num.size(), '0');
            out += (frame < 0 ? "-" : "") + num;
            i = j;
        } else if (pattern[i] == '#') {
            size_t j = i;
            while (j < pattern.size() && pattern[j] == '#') ++j;
            if (j - i > kMaxFramePad) throw tooWide();
            std::string num = std::to_string(frame);
            if (num.size() < j - i) num.insert(0, (j - i) - num.size(), '0');
            out += num;
            i = j;
        } else {
            out += pattern[i++];
        }
    }
    return out;
}

bool hasFramePattern(const std::string& pattern) {
    return pattern.find("$F") != std::string::npos || pattern.find('#') != std::string::npos;
}

std::vector<int> parseFrameRange(const std::string& range) {
    const std::string expected =
        "--frames '" + boundedMessage(range, 120) +
        "': expected A-B with A ≤ B, or A-BxS for every S-th frame, e.g. 1-24 or 1-48x2";
    int a = 0, b = 0, step = 1, used = 0;
    char dash = 0, x = 0;
    const int n = std::sscanf(range.c_str(), "%d%c%d%n", &a, &dash, &b, &used);
    if (n != 3 || dash != '-' || b < a) throw MirageError(expected);
    const std::string rest = range.substr(size_t(used));
    if (!rest.empty()) {
        int more = 0;
        if (std::sscanf(rest.c_str(), "%c%d%n", &x, &step, &more) != 2 || x != 'x' || step < 1 ||
            size_t(more) != rest.size())
            throw MirageError(expected);
    }
    std::vector<int> frames;
    for (long long f = a; f <= b; f += step) frames.push_back(int(f));
    return frames;
}

}  // namespace mirage
