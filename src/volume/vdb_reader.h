// Sequential little-endian reads from a VDB file where every read is first checked against the
// file size, so that a length or offset from the file is reported, never trusted. Shared by the
// file-index scan (vdb_format.cpp) and the tree walk (vdb_tree.cpp).
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

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

    [[noreturn]] void fail(const std::string& msg) const {
        throw MirageError(FileLoc{mPath}, msg);
    }
    void require(uint64_t n, const std::string& what) const {
        if (n > mSize || mPos > mSize - n)
            fail("truncated: " + what + " at byte " + std::to_string(mPos) + " needs " +
                 std::to_string(n) + " bytes but the file has " + std::to_string(mSize) +
                 " bytes");
    }
    void read(void* dst, uint64_t n, const std::string& what) {
        require(n, what);
        if (mStreamPos != mPos) mIn.seekg(std::streamoff(mPos));
        mIn.read(static_cast<char*>(dst), std::streamsize(n));
        if (!mIn)
            fail("read error at byte " + std::to_string(mPos) + ": " + std::strerror(errno));
        mPos += n;
        mStreamPos = mPos;
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
    const std::string& mPath;
    std::ifstream& mIn;
    uint64_t mSize;
    uint64_t mPos = 0;
    uint64_t mStreamPos = ~uint64_t(0);  // where the stream is; unknown at first
};

}  // namespace mirage::vdbformat
