#include "core/text.h"
#include "scene/toml_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace mirage {

namespace {

const char* typeName(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::table: return "a table";
        case toml::node_type::array: return "an array";
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        default: return "a date/time";
    }
}

FileLoc nodeLoc(const toml::node& n, const std::string& file) {
    const auto& src = n.source();
    return {file, int(src.begin.line), int(src.begin.column)};
}

}  // namespace

TableReader::TableReader(const toml::table& table, std::string file, std::string path)
    : mTable(&table), mFile(std::move(file)), mPath(std::move(path)) {}

std::string TableReader::where() const {
    return mPath.empty() ? std::string("the top level") : "[" + mPath + "]";
}

bool TableReader::has(const std::string& key) const { return mTable->contains(key); }

FileLoc TableReader::tableLoc() const { return nodeLoc(*mTable, mFile); }

FileLoc TableReader::loc(const std::string& key) const {
    const toml::node* n = mTable->get(key);
    return n ? nodeLoc(*n, mFile) : tableLoc();
}

void TableReader::fail(const std::string& key, const std::string& message) const {
    std::string prefix = key.empty() ? where() : "'" + key + "' in " + where();
    throw MirageError(loc(key), prefix + ": " + message);
}

const toml::node* TableReader::node(const std::string& key) const {
    if (std::find(mRead.begin(), mRead.end(), key) == mRead.end()) mRead.push_back(key);
    return mTable->get(key);
}

double TableReader::getNumber(const std::string& key) const {
    const toml::node* n = node(key);
    if (!n) throw MirageError(tableLoc(), "missing required key '" + key + "' in " + where());
    if (auto v = n->value<double>()) {
        if (!std::isfinite(*v)) fail(key, "expected a finite number");
        return *v;
    }
    fail(key, std::string("expected a number, found ") + typeName(*n));
}

double TableReader::getNumber(const std::string& key, double def) const {
    return has(key) ? getNumber(key) : (node(key), def);
}

double TableReader::getNumber(const std::string& key, double def, double lo, double hi) const {
    double v = getNumber(key, def);
    if (v < lo || v > hi) {
        std::ostringstream os;
        os << "value " << v << " is out of range; expected " << lo << " to " << hi;
        fail(key, os.str());
    }
    return v;
}

int64_t TableReader::getInt(const std::string& key, int64_t def, int64_t lo, int64_t hi) const {
    const toml::node* n = node(key);
    if (!n) return def;
    auto v = n->value_exact<int64_t>();
    if (!v) fail(key, std::string("expected an integer, found ") + typeName(*n));
    if (*v < lo || *v > hi)
        fail(key, "value " + std::to_string(*v) + " is out of range; expected " +
                      std::to_string(lo) + " to " + std::to_string(hi));
    return *v;
}

bool TableReader::getBool(const std::string& key, bool def) const {
    const toml::node* n = node(key);
    if (!n) return def;
    auto v = n->value_exact<bool>();
    if (!v) fail(key, std::string("expected true or false, found ") + typeName(*n));
    return *v;
}

std::string TableReader::getString(const std::string& key) const {
    const toml::node* n = node(key);
    if (!n) throw MirageError(tableLoc(), "missing required key '" + key + "' in " + where());
    auto v = n->value_exact<std::string>();
    if (!v) fail(key, std::string("expected a string, found ") + typeName(*n));
    return *v;
}

std::string TableReader::getString(const std::string& key, const std::string& def) const {
    return has(key) ? getString(key) : (node(key), def);
}

bool TableReader::getChoice(const std::string& key, const std::string& first,
                            const std::string& second, const std::string& noun) const {
    const std::string v = getString(key, first);
    if (v != first && v != second)
        fail(key, "unknown " + noun + " '" + v + "'; expected " + first + " or " + second);
    return v == first;
}

std::vector<double> TableReader::getNumbers(const std::string& key, size_t minCount,
                                            size_t maxCount) const {
    const toml::node* n = node(key);
    if (!n) throw MirageError(tableLoc(), "missing required key '" + key + "' in " + where());
    const toml::array* a = n->as_array();
    auto expected = [&] {
        return minCount == maxCount ? "an array of " + std::to_string(minCount) + " numbers"
                                    : "an array of " + std::to_string(minCount) + " to " +
                                          std::to_string(maxCount) + " numbers";
    };
    if (!a) fail(key, "expected " + expected() + ", found " + typeName(*n));
    if (a->size() < minCount || a->size() > maxCount)
        fail(key, "expected " + expected() + ", found " + std::to_string(a->size()));
    std::vector<double> out;
    for (const auto& e : *a) {
        auto v = e.value<double>();
        if (!v || !std::isfinite(*v))
            throw MirageError(nodeLoc(e, mFile), "'" + key + "' in " + where() +
                                                     ": expected finite numbers, found " +
                                                     typeName(e));
        out.push_back(*v);
    }
    return out;
}

std::vector<std::string> TableReader::getStrings(const std::string& key) const {
    const toml::node* n = node(key);
    if (!n) return {};
    const toml::array* a = n->as_array();
    if (!a) fail(key, std::string("expected an array of strings, found ") + typeName(*n));
    std::vector<std::string> out;
    for (const auto& e : *a) {
        auto v = e.value<std::string>();
        if (!v)
            throw MirageError(nodeLoc(e, mFile), "'" + key + "' in " + where() +
                                                     ": expected strings, found " + typeName(e));
        out.push_back(*v);
    }
    return out;
}

Vec3 TableReader::getVec3(const std::string& key) const {
    auto v = getNumbers(key, 3, 3);
    Vec3 out{float(v[0]), float(v[1]), float(v[2])};
    // Finite as a double is not enough: positions and directions are single precision.
    if (!isFinite(out)) fail(key, "expected numbers within ±3.4e38 (single precision)");
    return out;
}

Vec3 TableReader::getVec3(const std::string& key, const Vec3& def) const {
    return has(key) ? getVec3(key) : (node(key), def);
}

TableReader TableReader::table(const std::string& key) const {
    auto t = optionalTable(key);
    if (!t) throw MirageError(tableLoc(), "missing required table '" + key + "' in " + where());
    return *t;
}

std::optional<TableReader> TableReader::optionalTable(const std::string& key) const {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    const toml::table* t = n->as_table();
    if (!t) fail(key, std::string("expected a table, found ") + typeName(*n));
    return TableReader(*t, mFile, mPath.empty() ? key : mPath + "." + key);
}

std::vector<TableReader> TableReader::tables(const std::string& key) const {
    std::vector<TableReader> out;
    const toml::node* n = node(key);
    if (!n) return out;
    if (const toml::table* t = n->as_table()) {  // a single [key] table is one element
        out.emplace_back(*t, mFile, mPath.empty() ? key : mPath + "." + key);
        return out;
    }
    const toml::array* a = n->as_array();
    if (!a) fail(key, std::string("expected an array of tables [[") + key + "]], found " +
                          typeName(*n));
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::table* t = (*a)[i].as_table();
        if (!t)
            throw MirageError(nodeLoc((*a)[i], mFile),
                              "'" + key + "' in " + where() + ": expected tables, found " +
                                  typeName((*a)[i]));
        out.emplace_back(*t, mFile,
                         (mPath.empty() ? key : mPath + "." + key) + "." + std::to_string(i));
    }
    return out;
}

std::vector<std::string> TableReader::keys() const {
    std::vector<std::string> k;
    for (const auto& [key, value] : *mTable) k.emplace_back(key.str());
    return k;
}

void TableReader::finish() const {
    for (const auto& [key, value] : *mTable) {
        std::string k(key.str());
        if (std::find(mRead.begin(), mRead.end(), k) != mRead.end()) continue;
        const std::string expected = joinList(mRead);
        const auto& src = key.source();
        FileLoc at = src.begin.line ? FileLoc{mFile, int(src.begin.line), int(src.begin.column)}
                                    : nodeLoc(value, mFile);
        throw MirageError(at, "unknown key '" + k + "' in " + where() +
                              (expected.empty() ? "" : "; expected one of: " + expected));
    }
}

toml::table parseTomlText(const std::string& text, const std::string& name) {
    try {
        return toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        const auto& b = e.source().begin;
        throw MirageError(FileLoc{name, int(b.line), int(b.column)},
                          "TOML syntax error: " + boundedMessage(std::string(e.description())));
    }
}

toml::table parseTomlFile(const std::string& path) {
    // A directory opens as an empty stream on Linux: it would parse as an empty scene.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw MirageError(FileLoc{path, 0, 0}, "is a directory, expected a scene file (.toml)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MirageError(FileLoc{path, 0, 0}, "cannot open the file (missing or unreadable)");
    std::stringstream ss;
    ss << in.rdbuf();
    return parseTomlText(ss.str(), path);
}

void applyOverride(toml::table& doc, const std::string& assignment) {
    size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw MirageError("--set '" + assignment + "': expected key=value, e.g. film.spp=64");
    std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);

    // The value: TOML if it parses as one, else a plain string.
    toml::table parsed;
    try {
        parsed = toml::parse("v = " + text);
    } catch (const toml::parse_error&) {
        parsed = toml::table{{"v", text}};
    }
    toml::node& value = *parsed.get("v");

    std::vector<std::string> parts;
    std::stringstream ss(path);
    for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
    toml::node* cur = &doc;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
        const std::string& p = parts[i];
        toml::node* next = nullptr;
        if (auto* t = cur->as_table()) {
            next = t->get(p);
            if (!next) {
                t->insert(p, toml::table{});
                next = t->get(p);
            }
        } else if (auto* a = cur->as_array()) {
            char* end = nullptr;
            unsigned long idx = std::strtoul(p.c_str(), &end, 10);
            if (*end == '\0' && idx < a->size()) next = a->get(idx);
        }
        if (!next || !(next->is_table() || next->is_array()))
            throw MirageError("--set '" + assignment + "': '" + p +
                              "' is not a table or a valid array index in the scene");
        cur = next;
    }
    const std::string& last = parts.back();
    if (auto* t = cur->as_table()) {
        t->insert_or_assign(last, std::move(value));
    } else if (auto* a = cur->as_array()) {
        char* end = nullptr;
        unsigned long idx = std::strtoul(last.c_str(), &end, 10);
        if (*end != '\0' || idx >= a->size())
            throw MirageError("--set '" + assignment + "': '" + last + "' is not a valid index");
        a->replace(a->begin() + long(idx), std::move(value));
    } else {
        throw MirageError("--set '" + assignment + "': the parent is not a table");
    }
}

}  // namespace mirage
