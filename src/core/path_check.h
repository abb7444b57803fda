// Looking up a path a scene names, without throwing. std::filesystem::exists(p) throws
// filesystem_error when the system cannot answer at all (a name longer than the file system
// allows, a folder in the path that is a file, no permission to search a folder): a scene's
// mistyped path must end in one message naming the key, not in an uncaught exception.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace mirage {

// "" when p exists; "not found" when it does not; otherwise "unreadable (" + the system's
// reason + ")", e.g. "unreadable (File name too long)".
inline std::string pathProblem(const std::filesystem::path& p) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(p, ec);
    if (ec) return "unreadable (" + ec.message() + ")";
    return exists ? std::string() : std::string("not found");
}

}  // namespace mirage
