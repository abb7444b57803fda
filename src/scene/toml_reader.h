// Reading TOML tables with the error discipline of Mirage's scene files: every value is read
// through a TableReader, which records the keys it was asked for, so that a key nobody read is
// reported as unknown (with its line and column, and the keys that were expected); wrong types
// and out-of-range values name the file, line and column too.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/error.h"
#include "core/math.h"

namespace mirage {

class TableReader {
public:
    TableReader(const toml::table& table, std::string file, std::string path);

    bool has(const std::string& key) const;
    FileLoc loc(const std::string& key) const;  // of the key's value, or of the table
    FileLoc tableLoc() const;
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

    // Required forms throw when the key is missing; the others return the default.
    double getNumber(const std::string& key) const;
    double getNumber(const std::string& key, double def) const;
    // A number within [lo, hi] (inclusive).
    double getNumber(const std::string& key, double def, double lo, double hi) const;
    int64_t getInt(const std::string& key, int64_t def, int64_t lo, int64_t hi) const;
    bool getBool(const std::string& key, bool def) const;
    std::string getString(const std::string& key) const;
    std::string getString(const std::string& key, const std::string& def) const;
    // One of two words, `first` when the key is missing: true for `first`, false for `second`;
    // anything else fails with "unknown <noun> '<value>'; expected <first> or <second>".
    bool getChoice(const std::string& key, const std::string& first, const std::string& second,
                   const std::string& noun) const;
    Vec3 getVec3(const std::string& key) const;
    Vec3 getVec3(const std::string& key, const Vec3& def) const;
    std::vector<double> getNumbers(const std::string& key, size_t minCount, size_t maxCount) const;
    // An array of strings; empty when the key is missing.
    std::vector<std::string> getStrings(const std::string& key) const;
    const toml::node* node(const std::string& key) const;  // marks the key as read

    TableReader table(const std::string& key) const;  // required
    std::optional<TableReader> optionalTable(const std::string& key) const;
    std::vector<TableReader> tables(const std::string& key) const;  // array of tables
    std::vector<std::string> keys() const;  // all keys of the table (marks none)

    // Throws for the first key that was never read, listing the keys that were.
    void finish() const;

    const std::string& file() const { return mFile; }
    const std::string& path() const { return mPath; }

private:
    std::string where() const;  // "[camera]" or "the top level"
    const toml::table* mTable;
    std::string mFile, mPath;
    mutable std::vector<std::string> mRead;
};

// Parses a TOML file (or text) into a table; syntax errors become MirageError with location.
toml::table parseTomlFile(const std::string& path);
toml::table parseTomlText(const std::string& text, const std::string& name);

// Applies a command-line override "a.b.0.c=value" to a document: the value is parsed as TOML
// (numbers, booleans, arrays; anything else is taken as a string). Numeric path parts index
// arrays. Throws MirageError naming the override when the path does not exist.
void applyOverride(toml::table& doc, const std::string& assignment);

}  // namespace mirage
