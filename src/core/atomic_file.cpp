#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace mirage {

namespace fs = std::filesystem;

std::string temporaryPathBeside(const std::string& path) {
    static std::atomic<uint64_t> counter{0};
    const fs::path target(path);
    const std::string name = "." + target.filename().string() + ".tmp-" +
                             std::to_string(::getpid()) + "-" +
                             std::to_string(counter.fetch_add(1, std::memory_order_relaxed));
    return (target.parent_path() / name).string();
}

void replaceFileAtomically(const std::string& path,
                           const std::function<void(const std::string& tmp)>& write,
                           const std::string& renameFailure) {
    const std::string tmp = temporaryPathBeside(path);
    auto removeTmp = [&tmp] {
        std::error_code ignored;
        fs::remove(tmp, ignored);
    };
    try {
        write(tmp);
    } catch (...) {
        removeTmp();
        throw;
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        removeTmp();
        throw MirageError(FileLoc{path, 0, 0}, renameFailure + ": " + ec.message());
    }
}

void createParentFolders(const std::string& path) {
    const fs::path dir = fs::path(path).parent_path();
    std::error_code ignored;
    if (!dir.empty()) fs::create_directories(dir, ignored);
}

void writeTextFileAtomically(const std::string& path, const std::string& text,
                             const std::string& writeFailure) {
    replaceFileAtomically(path, [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out.flush()) throw MirageError(FileLoc{path, 0, 0}, writeFailure);
    });
}

}  // namespace mirage
