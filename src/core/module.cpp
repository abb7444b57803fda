#include "core/module.h"

#include <dlfcn.h>
#include <unistd.h>

#include <limits.h>
#include <mutex>
#include <vector>

#include "core/error.h"

namespace mirage {

namespace {

std::string folderOf(const std::string& path) {
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// The folders a module is looked for in, in order, without repeats.
std::vector<std::string> moduleFolders() {
    std::vector<std::string> folders;
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&moduleEntry), &info) && info.dli_fname)
        folders.push_back(folderOf(info.dli_fname));
    char exe[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        const std::string f = folderOf(std::string(exe, size_t(n)));
        if (folders.empty() || folders.front() != f) folders.push_back(f);
    }
    return folders;
}

}  // namespace

void* moduleEntry(const std::string& file, const char* entry, const std::string& purpose) {
    // dlopen counts its references and dlsym is thread-safe; the lock keeps the first load's
    // message and the search in one piece when two threads load at once.
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    std::string tried, error;
    for (const std::string& folder : moduleFolders()) {
        const std::string path = folder + "/" + file;
        tried += (tried.empty() ? "" : ", ") + path;
        if (access(path.c_str(), F_OK) != 0) continue;
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* e = dlerror();
            error = e ? e : "unknown error";
            continue;
        }
        if (void* symbol = dlsym(handle, entry)) return symbol;
        error = path + " has no " + entry;
    }
    throw MirageError(purpose + " need Mirage's module " + file + ", not found or not loadable (" +
                      (error.empty() ? "looked for " + tried : tried + ": " + error) +
                      "); build it with the command (pipeline/build.sh)");
}

}  // namespace mirage
