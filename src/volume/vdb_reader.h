// Sequential little-endian reads from a VDB file where every read is first checked against the
// file size, so that a length or offset from the file is reported, never trusted. Shared by the
// file-index scan (vdb_format.cpp) and the tree walk (vdb_tree.cpp).
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace mirage::vdbformat {

// Names and type names longer than this are a corrupt length field, not a long name.
constexpr uint32_t kMaxNameBytes = 1u << 16;

class Reader {
public:
    Reader(const std::string& path, std::ifstream& in, uint64_t size)
        : mPath(path), mIn(in), mSize(size) {}

    uint64_t pos() const { return mPos; }
    uint64_t size() const { return mSize; }
    uint64_t remaining() const { return mPos < mSize ? mSize - mPos : 0; }
    const std::string& path() const { return mPath; }
    void seek(uint64_t p) { mPos = p; }

    [[noreturn]] void fail(const std::string& msg) const { throw MirageError(FileLoc{mPath}, msg); }
    void require(uint64_t n, const std::string& what) const {
        if (n > mSize || mPos > mSize - n)
            fail("truncated: " + what + " at byte " + std::to_string(mPos) + " needs " +
                 std::to_string(n) + " bytes but the file has " + std::to_string(mSize) + " bytes");
    }
    void read(void* dst, uint64_t n, const std::string& what) {
        require(n, what);
        if (mPos < mWindowStart || mPos - mWindowStart + n > mWindow.size()) fill(n);
        std::memcpy(dst, mWindow.data() + (mPos - mWindowStart), n);
        mPos += n;
    }
    template <typename T>
    T pod(const std::string& what) {
        T v{};
        read(&v, sizeof(T), what);
        return v;
    }
    void skip(uint64_t n, const std::string& what) {
        require(n, what);
        mPos += n;
    }
    // OpenVDB string: uint32 length, then the bytes.
    std::string str(const std::string& what) {
        uint32_t n = pod<uint32_t>(what);
        if (n > kMaxNameBytes)
            fail("corrupt: " + what + " at byte " + std::to_string(mPos - 4) + " claims " +
                 std::to_string(n) + " bytes");
        std::string s(n, '\0');
        read(s.data(), n, what);
        return s;
    }

private:
    // The file from mPos on, at least n bytes of it (require() has checked that they exist),
    // into the window: one read, of twice the last window where the reads go on from it (a
    // walk through a grid), else of the smallest (a look at a header elsewhere).
    void fill(uint64_t n) {
        const bool onwards = !mWindow.empty() && mPos >= mWindowStart &&
                             mPos - mWindowStart < mWindow.size() + mWindowBytes;
        mWindowBytes = onwards ? std::min(2 * mWindowBytes, kMaxWindowBytes) : kMinWindowBytes;
        const uint64_t bytes =
            std::max<uint64_t>(n, std::min<uint64_t>(mWindowBytes, mSize - mPos));
        mWindow.resize(size_t(bytes));
        mIn.clear();
        mIn.seekg(std::streamoff(mPos));
        mIn.read(mWindow.data(), std::streamsize(bytes));
        if (!mIn) {
            mWindow.clear();
            fail("read error at byte " + std::to_string(mPos) + ": " + std::strerror(errno));
        }
        mWindowStart = mPos;
    }

    // A tree walk reads a leaf's mask and block header, then skips its ~1 KB of values: read
    // from the stream one by one, each read after a skip costs a seek and a refill of the
    // stream's buffer (two system calls and 8 KB copied per leaf, seconds at 10⁹ voxels).
    // Through a window of its own the walk reads the file once, in large pieces.
    static constexpr uint64_t kMinWindowBytes = uint64_t(64) << 10;
    static constexpr uint64_t kMaxWindowBytes = uint64_t(4) << 20;

    const std::string& mPath;
    std::ifstream& mIn;
    uint64_t mSize;
    uint64_t mPos = 0;
    std::vector<char> mWindow;  // the file's bytes [mWindowStart, mWindowStart + size)
    uint64_t mWindowStart = 0;
    uint64_t mWindowBytes = kMinWindowBytes;  // the last fill's size
};

}  // namespace mirage::vdbformat
