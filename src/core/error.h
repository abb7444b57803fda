// One exception type for every user-input mistake (scene files, grids, command-line values).
// It is thrown where the mistake is found, caught once in main, and printed as
// "file:line:column: message", then Mirage exits non-zero. Broken internal invariants are not
// user errors: they use MIRAGE_CHECK.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace mirage {

struct FileLoc {
    std::string file;
    int line = 0, column = 0;  // 1-based; 0 = unknown
    std::string str() const;
};

class MirageError : public std::runtime_error {
public:
    explicit MirageError(const std::string& msg) : std::runtime_error(msg) {}
    MirageError(const FileLoc& loc, const std::string& msg)
        : std::runtime_error(loc.str() + ": " + msg), mLoc(loc) {}
    const FileLoc& location() const { return mLoc; }

private:
    FileLoc mLoc;
};

// Bound a message taken from a third-party library: OpenVDB's reader can report garbage of
// gigabytes on a corrupt file, and a user message must stay readable.
std::string boundedMessage(const std::string& msg, size_t maxChars = 300);

[[noreturn]] void checkFailed(const char* expr, const char* file, int line);

}  // namespace mirage

#define MIRAGE_CHECK(expr) \
    ((expr) ? (void)0 : ::mirage::checkFailed(#expr, __FILE__, __LINE__))
#ifdef NDEBUG
#define MIRAGE_DCHECK(expr) ((void)0)
#else
#define MIRAGE_DCHECK(expr) MIRAGE_CHECK(expr)
#endif
