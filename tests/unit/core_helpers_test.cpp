// Tests for the small helpers of core/: replacing a file atomically (core/atomic_file.h), lists
// in messages (core/text.h) and the "#N" names of unnamed grids (core/grid_name.h).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/grid_name.h"
#include "core/text.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Everything in `dir` but the file itself: temporaries a write left behind.
std::vector<std::string> leftovers(const std::string& dir, const std::string& keep) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename() != keep) out.push_back(e.path().filename().string());
    return out;
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
    const std::string dir = test::tempDir(), path = dir + "/result.csv";
    writeTextFileAtomically(path, "old content\n");
    auto halfThenFail = [](const std::string& tmp) {
        std::ofstream(tmp) << "half of the new con";
        throw std::runtime_error("disk full");
    };
    EXPECT_THROW(replaceFileAtomically(path, halfThenFail), std::runtime_error);
    EXPECT_EQ(readFile(path), "old content\n");
    EXPECT_TRUE(leftovers(dir, "result.csv").empty());
}

TEST(AtomicFile, AWriterSeesItsOwnTemporaryBesideTheTarget) {
    const std::string dir = test::tempDir(), path = dir + "/image.exr";
    std::string seen;
    replaceFileAtomically(path, [&](const std::string& tmp) {
        seen = tmp;
        std::ofstream(tmp) << "new";
        EXPECT_FALSE(fs::exists(path)) << "the target appeared before the rename";
    });
    EXPECT_EQ(fs::path(seen).parent_path(), fs::path(dir));
    EXPECT_NE(seen, path);
    EXPECT_FALSE(fs::exists(seen));
    EXPECT_EQ(readFile(path), "new");
}

TEST(AtomicFile, AMissingFolderIsOneMessageNamingTheFile) {
    const std::string path = test::tempDir() + "/no/such/folder/out.txt";
    try {
        writeTextFileAtomically(path, "x");
        FAIL() << "no error for a missing folder";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

TEST(AtomicFile, ConcurrentWritersOfOneFileNeverShareATemporary) {
    const std::string dir = test::tempDir(), path = dir + "/shared.txt";
    constexpr int kThreads = 8, kWrites = 40;
    // Each writer's content is long and unique, so a torn or interleaved file shows.
    auto content = [](int t, int i) {
        return std::string(4096 + t * 97 + i, char('a' + t)) + "#" + std::to_string(i) + "\n";
    };
    std::vector<std::thread> threads;
    std::vector<std::string> errors(kThreads);
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            try {
                for (int i = 0; i < kWrites; ++i) writeTextFileAtomically(path, content(t, i));
            } catch (const std::exception& e) {
                errors[size_t(t)] = e.what();
            }
        });
    for (auto& th : threads) th.join();
    for (const std::string& e : errors) EXPECT_EQ(e, "");
    const std::string last = readFile(path);
    bool whole = false;
    for (int t = 0; t < kThreads; ++t)
        for (int i = 0; i < kWrites; ++i) whole |= last == content(t, i);
    EXPECT_TRUE(whole) << "the file holds no writer's complete content (" << last.size()
                       << " bytes)";
    EXPECT_TRUE(leftovers(dir, "shared.txt").empty());
}

TEST(AtomicFile, TemporaryNamesAreUniqueAcrossThreads) {
    constexpr int kThreads = 4, kNames = 2000;
    std::vector<std::vector<std::string>> names(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int i = 0; i < kNames; ++i)
                names[size_t(t)].push_back(temporaryPathBeside("out/frame.exr"));
        });
    for (auto& th : threads) th.join();
    std::set<std::string> all;
    for (const auto& v : names)
        for (const auto& n : v) {
            EXPECT_EQ(fs::path(n).parent_path(), fs::path("out"));
            all.insert(n);
        }
    EXPECT_EQ(all.size(), size_t(kThreads * kNames));
}

TEST(JoinList, SeparatesTheItemsInOrder) {
    EXPECT_EQ(joinList({}), "");
    EXPECT_EQ(joinList({"one"}), "one");
    EXPECT_EQ(joinList({"a", "b", "c"}), "a, b, c");
    EXPECT_EQ(joinList({"a", "", "c"}), "a, , c");
    EXPECT_EQ(joinList({"x", "y"}, " | "), "x | y");
}

TEST(JoinList, TurnsEachElementIntoTextFirst) {
    const std::vector<int> v = {3, 1, 2};
    EXPECT_EQ(joinList(v, [](int i) { return std::to_string(i * 10); }), "30, 10, 20");
    EXPECT_EQ(joinList(std::vector<int>{}, [](int i) { return std::to_string(i); }), "");
}

TEST(GridName, AnUnnamedGridIsItsIndexInTheFile) {
    EXPECT_EQ(gridIndexName(0), "#0");
    EXPECT_EQ(gridIndexName(12), "#12");
    EXPECT_EQ(gridName("", 3), "#3");
    EXPECT_EQ(gridName("density", 3), "density");
    EXPECT_EQ(quotedGridName("", 1), "#1");
    EXPECT_EQ(quotedGridName("temperature", 1), "'temperature'");
}

}  // namespace
}  // namespace mirage
