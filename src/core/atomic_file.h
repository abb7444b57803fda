// Replacing a file so that a reader, a crash or a failed write never sees half of it: the new
// content goes to a temporary file in the destination's folder (the same file system, so the
// rename is atomic on POSIX) and is renamed over the destination only once it is complete.
#pragma once

#include <functional>
#include <string>

namespace mirage {

// A temporary path beside `path`, unique to this call: "<dir>/.<name>.tmp-<pid>-<n>", with n a
// process-wide counter, so that two threads (or two processes) writing the same destination
// never share a temporary.
std::string temporaryPathBeside(const std::string& path);

// Calls write(tmp) to fill a fresh temporary beside `path`, then renames it over `path`. When
// `write` throws, the temporary is removed and the exception propagates; `path` keeps whatever
// it held. A failed rename throws MirageError naming `path`: renameFailure + ": " + the reason.
// The folder of `path` must exist. No fsync: the guarantee is against partial files, not
// against a power cut.
void replaceFileAtomically(const std::string& path,
                           const std::function<void(const std::string& tmp)>& write,
                           const std::string& renameFailure = "cannot move the file into place");

// Creates the folder of `path` and its parents where missing. Quiet on failure: the write
// that follows reports the missing folder with its own message.
void createParentFolders(const std::string& path);

// replaceFileAtomically with `text` as the whole content; a failed write throws MirageError
// naming `path`: writeFailure.
void writeTextFileAtomically(const std::string& path, const std::string& text,
                             const std::string& writeFailure = "cannot write the file");

}  // namespace mirage
